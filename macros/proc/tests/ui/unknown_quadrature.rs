wrinkle_macros::energy_model! {
    /// Quadrature must be `full` or `reduced`.
    model Quadrature as "quadrature" {
        fields: w;
        parameters: k;
        energy shear [gauss3] = k * w.x^2;
        energy support [reduced] = k * w^2;
    }
}

fn main() {}
