wrinkle_macros::energy_model! {
    /// Uses a name that does not exist and one declared later.
    model Unknown as "unknown" {
        fields: w;
        parameters: k;
        energy e = k * w^2 + stiffness * w.x^2 + later * w;
        let later = 2 * k;
    }
}

fn main() {}
