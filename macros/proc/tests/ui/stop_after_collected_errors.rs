wrinkle_macros::energy_model! {
    /// A bad quadrature rule, then a missing `;` that stops the parser: both are reported.
    model Late as "late" {
        fields: w;
        parameters: k;
        energy support [gauss] = k * w^2;
        energy bending = k * w.x^2
        energy shear = k * w.y^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Late::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Late::SPEC.name);
}
