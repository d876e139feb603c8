wrinkle_macros::energy_model! {
    /// Quadrature must be `full` or `reduced`.
    model Quadrature as "quadrature" {
        fields: w;
        parameters: k;
        energy shear [gauss3] = k * w.x^2;
        energy support [reduced] = k * w^2;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Quadrature::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Quadrature::SPEC.name);
}
