wrinkle_macros::energy_model! {
    /// A role (other than `other`) names one field.
    model Roles as "roles" {
        fields: w [deflection], z [deflection];
        parameters: k;
        energy e = k * (w.x^2 + z.x^2);
    }
}

fn main() {}
