wrinkle_macros::energy_model! {
    /// Only sqrt, sin, cos, exp and ln exist.
    model Functions as "functions" {
        fields: w;
        parameters: k;
        energy e = tan(k) * w^2 + cosh(k) * w.x^2;
    }
}

fn main() {}
