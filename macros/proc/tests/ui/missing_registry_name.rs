wrinkle_macros::energy_model! {
    /// The registry name is mandatory.
    model Nameless {
        fields: w;
        energy e = w^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Nameless::from_parameters(&[]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Nameless::SPEC.name);
}
