wrinkle_macros::energy_model! {
    /// Uses a name that does not exist and one declared later.
    model Unknown as "unknown" {
        fields: w;
        parameters: k;
        energy e = k * w^2 + stiffness * w.x^2 + later * w;
        let later = 2 * k;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Unknown::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Unknown::SPEC.name);
}
