wrinkle_macros::energy_model! {
    /// A term that is a constant.
    model Constant as "constant" {
        fields: w;
        parameters: k;
        energy spring = k * w^2;
        energy offset = 3 * k^2;
    }
}

fn main() {}
