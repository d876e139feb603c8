wrinkle_macros::energy_model! {
    /// Field `v` appears in no term.
    model Unused as "unused" {
        fields: u, v, w;
        parameters: k;
        energy e = k * (u.x + w.x^2)^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Unused::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Unused::SPEC.name);
}
