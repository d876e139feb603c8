wrinkle_macros::energy_model! {
    /// Exponents must be integer literals.
    model Exponents as "exponents" {
        fields: w;
        parameters: n;
        energy e = w^n + w.x^2.5 + w.y^(1 + 1);
    }
}

fn main() {}
