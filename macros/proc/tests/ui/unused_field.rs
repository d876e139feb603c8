wrinkle_macros::energy_model! {
    /// Field `v` appears in no term.
    model Unused as "unused" {
        fields: u, v, w;
        parameters: k;
        energy e = k * (u.x + w.x^2)^2;
    }
}

fn main() {}
