wrinkle_macros::energy_model! {
    /// A term that is a constant.
    model Constant as "constant" {
        fields: w;
        parameters: k;
        energy spring = k * w^2;
        energy offset = 3 * k^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Constant::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Constant::SPEC.name);
}
