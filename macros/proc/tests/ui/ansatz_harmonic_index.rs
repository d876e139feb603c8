wrinkle_macros::energy_model! {
    /// Harmonic indices are integers.
    model HalfHarmonic as "half-harmonic" {
        fields: u [displacement_x], w [envelope], w2 [second_envelope];
        parameters: wavenumber;
        microscopic bar {
            fields: u, w;
            parameters: stiffness;
            energy stretching = 0.5 * stiffness * (u.x + 0.5 * w.x^2)^2;
        }
        ansatz {
            wavenumber: wavenumber;
            u = u;
            w = 2 Re(w e^{i Q e.X}) + 2 Re(w2 e^{1.5 i Q e.X});
        }
        energy stretching = average(stretching);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = HalfHarmonic::from_parameters(&[1.0, 0.2]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", HalfHarmonic::SPEC.name);
}
