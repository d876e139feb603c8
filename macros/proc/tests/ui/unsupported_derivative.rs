wrinkle_macros::energy_model! {
    /// Third derivatives, unknown axes and derivatives of non-fields.
    model Derivatives as "derivatives" {
        fields: w;
        parameters: k;
        let c = 2 * k;
        energy e = w.xxx^2 + w.z * w + c.x * w + k.y * w;
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Derivatives::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Derivatives::SPEC.name);
}
