wrinkle_macros::energy_model! {
    /// A model without any energy term.
    model Empty as "empty" {
        fields: w;
        parameters: k;
        let g = k * w;
    }
}

fn main() {}
