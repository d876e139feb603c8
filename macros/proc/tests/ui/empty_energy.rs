wrinkle_macros::energy_model! {
    /// A model without any energy term.
    model Empty as "empty" {
        fields: w;
        parameters: k;
        let g = k * w;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Empty::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Empty::SPEC.name);
}
