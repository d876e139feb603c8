wrinkle_macros::energy_model! {
    /// A microscopic energy that is not a polynomial in the fields cannot be averaged.
    model Rational as "rational" {
        fields: u [displacement_x], w [envelope];
        parameters: wavenumber;
        microscopic bar {
            fields: u, w;
            parameters: stiffness;
            let strain = u.x + 0.5 * w.x^2;
            energy stretching = 0.5 * stiffness * strain^2 / (1 + w.x^2);
            energy support = cos(w) * stiffness;
        }
        ansatz {
            wavenumber: wavenumber;
            u = u;
            w = 2 Re(w e^{i Q e.X});
        }
        energy stretching = average(stretching, mean(strain));
        energy support = average(support);
    }
}

use wrinkle_runtime::EnergyModel;

// Uses the model as an application would: a declaration error must not add errors here.
fn main() {
    let model = Rational::from_parameters(&[1.0, 0.2]);
    let energy: f64 = model.energy(0, &[0.5, 0.1, 0.2]);
    println!("{}: {energy}", Rational::SPEC.name);
}
