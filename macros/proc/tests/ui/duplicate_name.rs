wrinkle_macros::energy_model! {
    /// Names collide across fields, parameters, lets and terms.
    model Duplicates as "duplicates" {
        fields: u, w;
        parameters: k, u;
        let k = 2;
        energy e = k * w^2 + u.x^2;
        energy e = w.x^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Duplicates::from_parameters(&[1.0, 1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Duplicates::SPEC.name);
}
