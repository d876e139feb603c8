wrinkle_macros::energy_model! {
    /// A parameter's one attribute is `[varying]` (a function of position).
    model Winkler as "winkler" {
        fields: v [deflection];
        parameters: bending, foundation [varies];
        energy e = 0.5 * bending * v.x^2 + 0.5 * foundation * v^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Winkler::from_parameters(&[1.0, 1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1]);
    println!("{}: {energy}", Winkler::SPEC.name);
}
