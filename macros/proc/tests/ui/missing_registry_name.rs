wrinkle_macros::energy_model! {
    /// The registry name is mandatory.
    model Nameless {
        fields: w;
        energy e = w^2;
    }
}

fn main() {}
