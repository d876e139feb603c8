wrinkle_macros::energy_model! {
    /// The carrier's wavenumber of an ansatz cannot vary over the domain.
    model Drifting as "drifting" {
        fields: u [displacement_x], w [envelope];
        parameters: wavenumber [varying];
        microscopic bar {
            fields: u, w;
            parameters: stiffness;
            energy stretching = 0.5 * stiffness * (u.x + 0.5 * w.x^2)^2 + w.xx^2;
        }
        ansatz {
            wavenumber: 2 * wavenumber;
            u = u;
            w = 2 Re(w e^{i Q e.X});
        }
        energy stretching = average(stretching);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Drifting::new(1.0, 0.2);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Drifting::SPEC.name);
}
