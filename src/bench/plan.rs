//! The benchmark's plan: which sweeps ([`Sweep`]), with which path methods ([`Method`]), at
//! which settings ([`Settings`]) — the points [`Plan::points`] lists for one model.

/// Which sweep a point belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Sweep {
    /// The reference point itself (finest mesh, highest order, tightest tolerance).
    Reference,
    /// Mesh refinement at the reference's order and tolerance.
    Mesh,
    /// ANM order at the reference mesh and tolerance.
    Order,
    /// Series tolerance at the reference mesh and order.
    Tolerance,
}

impl Sweep {
    /// Name in the CSV and JSON files.
    pub fn as_str(self) -> &'static str {
        match self {
            Sweep::Reference => "reference",
            Sweep::Mesh => "mesh",
            Sweep::Order => "order",
            Sweep::Tolerance => "tolerance",
        }
    }
}

/// The path-following method of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// ANM with Padé approximants (`solver.pade = true`, the default).
    AnmPade,
    /// The classical ANM: power series only (`solver.pade = false`).
    Anm,
    /// Newton–Riks arc length (`solver.method = "riks"`; order and ε unused).
    Riks,
}

impl Method {
    /// Every method, the default first.
    pub const ALL: [Method; 3] = [Method::AnmPade, Method::Anm, Method::Riks];

    /// Name in the CSV and JSON files and the run directories.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::AnmPade => "anm-pade",
            Method::Anm => "anm",
            Method::Riks => "riks",
        }
    }

    /// Whether the method has an order $`N`$ and a series tolerance $`\varepsilon`$ (the ANM
    /// variants; Riks has neither).
    pub fn uses_series(self) -> bool {
        !matches!(self, Method::Riks)
    }

    /// `", N = 15, ε = 1e-6"` for an ANM method, nothing for Riks (the terminal and `bench.md`).
    pub fn series_settings(self, order: usize, series_tolerance: f64) -> String {
        if self.uses_series() {
            format!(", N = {order}, ε = {series_tolerance:.0e}")
        } else {
            String::new()
        }
    }

    /// Name in the plot's legend.
    pub fn label(self) -> &'static str {
        match self {
            Method::AnmPade => "ANM+Padé",
            Method::Anm => "ANM",
            Method::Riks => "Riks",
        }
    }

    /// Whether the ANM order and series tolerance mean anything for this method.
    pub fn is_anm(self) -> bool {
        self != Method::Riks
    }
}

/// The settings a point varies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Elements along X.
    pub nx: usize,
    /// Elements along Y.
    pub ny: usize,
    /// ANM truncation order $`N`$.
    pub order: usize,
    /// Series tolerance $`\varepsilon`$ of the step length.
    pub series_tolerance: f64,
    /// Path-following method.
    pub method: Method,
}

/// The sweeps of one model.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Meshes `(nx, ny)`, coarse to fine; the last is the reference mesh.
    pub meshes: Vec<(usize, usize)>,
    /// ANM orders, increasing; the last is the reference's.
    pub orders: Vec<usize>,
    /// Series tolerances, decreasing; the last is the reference's.
    pub tolerances: Vec<f64>,
}

impl Plan {
    /// The plan of `model`: a model that resolves the wrinkles themselves (no envelope field
    /// among its roles, e.g. the plate) must resolve about 15 wavelengths along X (8 Q8
    /// elements each for the `mode_resolution` check), envelope models only the envelope.
    pub fn for_model(model: &str, quick: bool) -> Plan {
        let plate = wrinkle_models::catalogue()
            .into_iter()
            .find(|spec| spec.name == model)
            .and_then(|spec| crate::physics::Layout::from_spec(spec).ok())
            .is_some_and(|layout| !layout.is_envelope());
        let meshes = match (plate, quick) {
            (false, false) => vec![(8, 4), (16, 8), (32, 16), (64, 32)],
            (false, true) => vec![(8, 4), (12, 6), (16, 8)],
            (true, false) => vec![(64, 16), (96, 24), (128, 32)],
            (true, true) => vec![(32, 8), (48, 12), (64, 16)],
        };
        let (orders, tolerances) = if quick {
            (vec![12, 20], vec![1e-5, 1e-7])
        } else {
            (
                vec![8, 12, 16, 20, 30],
                vec![1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
            )
        };
        Plan {
            meshes,
            orders,
            tolerances,
        }
    }

    /// Finest mesh, highest order, tightest tolerance, default method.
    pub fn reference(&self) -> Settings {
        let (nx, ny) = self.meshes.last().copied().unwrap_or((32, 16));
        Settings {
            nx,
            ny,
            order: self.orders.iter().copied().max().unwrap_or(20),
            series_tolerance: self.tolerances.iter().copied().fold(1e-7, f64::min),
            method: Method::AnmPade,
        }
    }

    /// Every point but the reference: the mesh sweep of every method, then the order and
    /// tolerance sweeps of both ANM variants.
    pub fn points(&self) -> Vec<(Sweep, Settings)> {
        let reference = self.reference();
        // Every method × every variant of one setting, method by method.
        let sweep = |sweep: Sweep, methods: &[Method], variants: Vec<Settings>| {
            methods
                .iter()
                .flat_map(|&method| {
                    variants
                        .iter()
                        .map(move |s| (sweep, Settings { method, ..*s }))
                })
                .collect::<Vec<_>>()
        };
        let anm: Vec<Method> = Method::ALL.into_iter().filter(|m| m.is_anm()).collect();
        let meshes = self.meshes.iter().map(|&(nx, ny)| Settings {
            nx,
            ny,
            ..reference
        });
        let orders = self
            .orders
            .iter()
            .map(|&order| Settings { order, ..reference });
        let tolerances = self.tolerances.iter().map(|&series_tolerance| Settings {
            series_tolerance,
            ..reference
        });
        sweep(Sweep::Mesh, &Method::ALL, meshes.collect())
            .into_iter()
            .chain(sweep(Sweep::Order, &anm, orders.collect()))
            .chain(sweep(Sweep::Tolerance, &anm, tolerances.collect()))
            .filter(|(_, settings)| *settings != reference)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::Method;

    /// Riks has no order and no series tolerance: none is listed for it.
    #[test]
    fn only_the_anm_lists_its_order_and_tolerance() {
        assert_eq!(
            Method::AnmPade.series_settings(15, 1e-6),
            ", N = 15, ε = 1e-6"
        );
        assert_eq!(Method::Anm.series_settings(20, 1e-8), ", N = 20, ε = 1e-8");
        assert_eq!(Method::Riks.series_settings(15, 1e-6), "");
    }
}
