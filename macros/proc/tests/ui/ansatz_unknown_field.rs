wrinkle_macros::energy_model! {
    /// The ansatz names a coefficient field the model does not declare.
    model Misnamed as "misnamed" {
        fields: u [displacement_x], w [envelope];
        parameters: wavenumber;
        microscopic bar {
            fields: u, w;
            parameters: stiffness;
            energy stretching = 0.5 * stiffness * (u.x + 0.5 * w.x^2)^2 + w.xx^2;
        }
        ansatz {
            wavenumber: wavenumber;
            u = u;
            w = 2 Re(w1 e^{i Q e.X});
        }
        energy stretching = average(stretching);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Misnamed::new(1.0, 0.2);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Misnamed::SPEC.name);
}
