wrinkle_macros::energy_model! {
    /// Functions are only allowed on parameter-only expressions.
    model Functions as "functions" {
        fields: w;
        parameters: k;
        let g = k * w.x;
        energy e = cos(k) * w^2 + sin(g + k);
    }
}

fn main() {}
