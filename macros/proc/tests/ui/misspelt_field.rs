wrinkle_macros::energy_model! {
    /// A field name misspelt in a term.
    model Misspelt as "misspelt" {
        fields: u [displacement_x], w [deflection];
        parameters: k;
        energy e = k * (u.x^2 + wx^2);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Misspelt::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Misspelt::SPEC.name);
}
