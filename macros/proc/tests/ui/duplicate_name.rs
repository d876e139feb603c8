wrinkle_macros::energy_model! {
    /// Names collide across fields, parameters, lets and terms.
    model Duplicates as "duplicates" {
        fields: u, w;
        parameters: k, u;
        let k = 2;
        energy e = k * w^2 + u.x^2;
        energy e = w.x^2;
    }
}

fn main() {}
