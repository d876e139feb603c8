wrinkle_macros::energy_model! {
    /// Only sqrt, sin, cos, exp and ln exist.
    model Functions as "functions" {
        fields: w;
        parameters: k;
        energy e = tan(k) * w^2 + cosh(k) * w.x^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Functions::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Functions::SPEC.name);
}
