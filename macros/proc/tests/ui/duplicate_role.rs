wrinkle_macros::energy_model! {
    /// A role (other than `other`) names one field.
    model Roles as "roles" {
        fields: w [deflection], z [deflection];
        parameters: k;
        energy e = k * (w.x^2 + z.x^2);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Roles::from_parameters(&[1.0]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Roles::SPEC.name);
}
