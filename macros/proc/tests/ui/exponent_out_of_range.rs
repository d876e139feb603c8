wrinkle_macros::energy_model! {
    /// Exponents are integers from -64 to 64.
    model Steep as "steep" {
        fields: w;
        parameters: k;
        energy e = k * w^65 + w.x^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Steep::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Steep::SPEC.name);
}
