wrinkle_macros::energy_model! {
    /// Field roles are a fixed vocabulary.
    model Roles as "roles" {
        fields: u [displacement_x], w [transverse];
        parameters: k;
        energy e = k * (u.x^2 + w.x^2);
    }
}

fn main() {}
