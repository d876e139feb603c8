wrinkle_macros::energy_model! {
    /// Exponents must be integer literals.
    model Exponents as "exponents" {
        fields: w;
        parameters: n;
        energy e = w^n + w.x^2.5 + w.y^(1 + 1);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Exponents::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Exponents::SPEC.name);
}
