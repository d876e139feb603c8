wrinkle_macros::energy_model! {
    /// Second derivatives and derivatives of non-fields.
    model Derivatives as "derivatives" {
        fields: w;
        parameters: k;
        let c = 2 * k;
        energy e = w.xx^2 + w.z * w + c.x * w + k.y * w;
    }
}

fn main() {}
