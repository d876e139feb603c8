//! Shared set-up of the `fvk-plate` verification tests and of the study example
//! (`models/examples/fvk_plate_study.rs`): square plates under uniform pressure, the paper's
//! example 1 as a plate, linear solves, spurious-mode probes and mode measurements.
//!
//! Also declares the shear-integration variants the study compares with [`FvkPlate`]: the same
//! density with the shear term integrated with the full 3×3 rule, and a Lyly–Stenberg–Vihinen
//! stabilised shear term $`\tfrac12 kGh\,\frac{h^2}{h^2 + \alpha h_e^2}|\nabla w - \theta|^2`$
//! with the element diameter $`h_e`$ given as the parameter `element_size` (uniform meshes).

#![allow(dead_code)]

use std::sync::Arc;
use wrinkle_models::FvkPlate;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::mesh::graded_breakpoints;
use wrinkle_runtime::fem::{BodyLoad, DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::linear::factor::{FactorizationKind, SparseFactorization};
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};

/// Young's modulus of every case (MPa).
pub const YOUNG: f64 = 70000.0;
/// Poisson ratio of every case.
pub const POISSON: f64 = 0.3;

/// Kirchhoff centre deflection of a clamped square plate under uniform pressure, in units of
/// $`qL^4/D`$ (Timoshenko & Woinowsky-Krieger, Table 35: 0.00126; more digits 0.00126532).
pub const CLAMPED_CENTRE: f64 = 0.001_265_32;
/// Same for a simply supported square plate (Navier series: 0.00406235).
pub const SIMPLY_SUPPORTED_CENTRE: f64 = 0.004_062_35;

wrinkle_macros::energy_model! {
    /// FvK plate with the transverse shear integrated with the full 3×3 rule (locks when thin).
    model FvkPlateFullShear as "fvk-plate-full-shear" {
        fields: u, v, w, theta_x, theta_y;
        parameters: young, poisson, thickness;
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let shear_stiffness = 5 / 6 * young / (2 * (1 + poisson)) * thickness;
        let gx = u.x + 0.5 * w.x^2;
        let gy = v.y + 0.5 * w.y^2;
        let gxy = u.y + v.x + w.x * w.y;
        let kxx = theta_x.x;
        let kyy = theta_y.y;
        let kxy = 0.5 * (theta_x.y + theta_y.x);
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = 0.5 * bending_stiffness
            * (kxx^2 + kyy^2 + 2 * poisson * kxx * kyy + 2 * (1 - poisson) * kxy^2);
        energy shear = 0.5 * shear_stiffness * ((w.x - theta_x)^2 + (w.y - theta_y)^2);
    }
}

wrinkle_macros::energy_model! {
    /// FvK plate with Lyly–Stenberg–Vihinen stabilised shear, 2×2 rule.
    model FvkPlateStabilisedReduced as "fvk-plate-stabilised-reduced" {
        fields: u, v, w, theta_x, theta_y;
        parameters: young, poisson, thickness, element_size, stabilisation;
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let shear_stiffness = 5 / 6 * young / (2 * (1 + poisson)) * thickness
            * thickness^2 / (thickness^2 + stabilisation * element_size^2);
        let gx = u.x + 0.5 * w.x^2;
        let gy = v.y + 0.5 * w.y^2;
        let gxy = u.y + v.x + w.x * w.y;
        let kxx = theta_x.x;
        let kyy = theta_y.y;
        let kxy = 0.5 * (theta_x.y + theta_y.x);
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = 0.5 * bending_stiffness
            * (kxx^2 + kyy^2 + 2 * poisson * kxx * kyy + 2 * (1 - poisson) * kxy^2);
        energy shear [reduced] = 0.5 * shear_stiffness * ((w.x - theta_x)^2 + (w.y - theta_y)^2);
    }
}

wrinkle_macros::energy_model! {
    /// FvK plate with Lyly–Stenberg–Vihinen stabilised shear, 3×3 rule.
    model FvkPlateStabilisedFull as "fvk-plate-stabilised-full" {
        fields: u, v, w, theta_x, theta_y;
        parameters: young, poisson, thickness, element_size, stabilisation;
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let shear_stiffness = 5 / 6 * young / (2 * (1 + poisson)) * thickness
            * thickness^2 / (thickness^2 + stabilisation * element_size^2);
        let gx = u.x + 0.5 * w.x^2;
        let gy = v.y + 0.5 * w.y^2;
        let gxy = u.y + v.x + w.x * w.y;
        let kxx = theta_x.x;
        let kyy = theta_y.y;
        let kxy = 0.5 * (theta_x.y + theta_y.x);
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = 0.5 * bending_stiffness
            * (kxx^2 + kyy^2 + 2 * poisson * kxx * kyy + 2 * (1 - poisson) * kxy^2);
        energy shear = 0.5 * shear_stiffness * ((w.x - theta_x)^2 + (w.y - theta_y)^2);
    }
}

wrinkle_macros::energy_model! {
    /// Mass-like density ½ w² (plus ½ rotary (u² + v² + θ²), left at 0): its tangent is the
    /// consistent "mass" matrix of the deflection, for the eigenvalue probes.
    model PlateMass as "plate-mass" {
        fields: u, v, w, theta_x, theta_y;
        parameters: young, poisson, thickness, rotary;
        energy mass = 0.5 * w^2 + 0.5 * rotary * (u^2 + v^2 + theta_x^2 + theta_y^2);
    }
}

/// A model with its parameters set by name (`young`, `poisson`, `thickness` and any extra).
pub fn model<M: EnergyModel>(thickness: f64, extra: &[(&str, f64)]) -> M {
    let mut m = M::from_parameters(&vec![0.0; M::SPEC.parameters.len()]);
    for (name, value) in [
        ("young", YOUNG),
        ("poisson", POISSON),
        ("thickness", thickness),
    ]
    .into_iter()
    .chain(extra.iter().copied())
    {
        m.set_parameter(name, value).unwrap();
    }
    m
}

/// The registered plate model.
pub fn plate(thickness: f64) -> FvkPlate {
    model(thickness, &[])
}

/// Bending stiffness $`D = Eh^3/(12(1-\nu^2))`$.
pub fn bending_stiffness(thickness: f64) -> f64 {
    YOUNG * thickness.powi(3) / (12.0 * (1.0 - POISSON * POISSON))
}

/// Support of the square plate's edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// $`w = \theta_x = \theta_y = 0`$.
    Clamped,
    /// Hard simple support: $`w = 0`$ and the tangential rotation zero.
    SimplySupported,
}

fn fixed(edge: &str, field: usize) -> DirichletCondition {
    DirichletCondition::fixed(edge, field)
}

fn field<M: EnergyModel>(name: &str) -> usize {
    M::SPEC.field_index(name).unwrap()
}

/// Dirichlet conditions of the plate fields (`w`, rotations) on every edge of a rectangle.
pub fn plate_supports<M: EnergyModel>(support: Support) -> Vec<DirichletCondition> {
    let (w, tx, ty) = (
        field::<M>("w"),
        field::<M>("theta_x"),
        field::<M>("theta_y"),
    );
    let mut conditions = Vec::new();
    for edge in ["left", "right", "bottom", "top"] {
        conditions.push(fixed(edge, w));
        let along_y = edge == "left" || edge == "right";
        match support {
            Support::Clamped => {
                conditions.push(fixed(edge, tx));
                conditions.push(fixed(edge, ty));
            }
            // On X = const the tangential rotation is θ_y, on Y = const it is θ_x.
            Support::SimplySupported => conditions.push(fixed(edge, if along_y { ty } else { tx })),
        }
    }
    conditions
}

/// Unit square plate on an `n × n` uniform mesh, $`u = v = 0`$ on the boundary, plate supports
/// on every edge, uniform pressure `pressure` on `w`.
pub fn square_plate<M: EnergyModel>(
    model: M,
    n: usize,
    support: Support,
    pressure: f64,
) -> Problem<M> {
    let mesh = Arc::new(Mesh::rectangle(1.0, 1.0, n, n, 1.0).unwrap());
    let mut conditions = plate_supports::<M>(support);
    for edge in ["left", "right", "bottom", "top"] {
        conditions.push(fixed(edge, field::<M>("u")));
        conditions.push(fixed(edge, field::<M>("v")));
    }
    let load = BodyLoad {
        field: field::<M>("w"),
        value: pressure,
        proportional: false,
    };
    let loads = Loads {
        body_loads: vec![load],
        ..Loads::default()
    };
    Problem::new(model, mesh, &conditions, &loads).unwrap()
}

/// Solution of the problem linearised about $`U = 0`$: $`K_t(0)\,U = F_0`$, with the kind of
/// factorisation that succeeded (Cholesky means positive definite).
pub fn linear_solve<M: EnergyModel>(problem: &Problem<M>) -> (Vec<f64>, FactorizationKind) {
    let n = problem.free_count();
    let mut k = problem.new_matrix();
    problem.tangent_into(&vec![0.0; n], 0.0, &mut k);
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let kind = factor.factorize(&k).unwrap();
    let mut u = problem.loads.fixed.clone();
    factor.solve_in_place(&mut u).unwrap();
    (u, kind)
}

/// Value of `field` at the mesh point set `point` (e.g. `"centre"`) in a free-dof vector.
pub fn value_at<M: EnergyModel>(
    problem: &Problem<M>,
    free: &[f64],
    field_name: &str,
    point: &str,
) -> f64 {
    let node = problem.assembler.mesh().points[point][0];
    let global = problem.dofs().expand(free, 0.0);
    global[node * problem.dofs().field_count + field::<M>(field_name)]
}

/// Centre deflection of the linear square-plate problem in units of $`qL^4/D`$, and the
/// factorisation kind.
pub fn centre_deflection<M: EnergyModel>(
    model: M,
    n: usize,
    support: Support,
) -> (f64, FactorizationKind) {
    let thickness = model.parameter("thickness").unwrap();
    let problem = square_plate(model, n, support, 1.0);
    let (u, kind) = linear_solve(&problem);
    let w = value_at(&problem, &u, "w", "centre");
    (w * bending_stiffness(thickness), kind)
}

/// Smallest and largest eigenvalues of the Jacobi-scaled tangent
/// $`S = \mathrm{diag}(K)^{-1/2} K\,\mathrm{diag}(K)^{-1/2}`$ at the state `(free, load)`
/// (power iteration on $`S`$ and on $`S^{-1}`$, `iterations` each; the smallest is an upper
/// bound). A spurious zero-energy mode shows as a smallest eigenvalue at round-off level.
pub fn scaled_extreme_eigenvalues<M: EnergyModel>(
    problem: &Problem<M>,
    free: &[f64],
    load: f64,
    iterations: usize,
) -> (f64, f64) {
    let n = problem.free_count();
    let mut k = problem.new_matrix();
    problem.tangent_into(free, load, &mut k);
    let scale: Vec<f64> = (0..n).map(|i| k.get(i, i).abs().sqrt().recip()).collect();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    factor.factorize(&k).unwrap();
    let normalise = |x: &mut Vec<f64>| {
        let s = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        x.iter_mut().for_each(|v| *v /= s);
    };
    let start = |seed: usize| -> Vec<f64> {
        (0..n)
            .map(|i| (((i * 7919 + seed) % 1000) as f64 / 1000.0) - 0.5)
            .collect()
    };
    // Largest: x ← S x.
    let mut x = start(1);
    normalise(&mut x);
    let mut largest = 0.0;
    for _ in 0..iterations {
        let sx: Vec<f64> = x.iter().zip(&scale).map(|(v, s)| v * s).collect();
        let mut y = vec![0.0; n];
        k.multiply_into(&sx, &mut y);
        y.iter_mut().zip(&scale).for_each(|(v, s)| *v *= s);
        largest = y.iter().zip(&x).map(|(a, b)| a * b).sum::<f64>();
        x = y;
        normalise(&mut x);
    }
    // Smallest: x ← S⁻¹ x = D^{1/2} K⁻¹ D^{1/2} x.
    let mut x = start(3);
    normalise(&mut x);
    let mut inverse_largest = 0.0;
    for _ in 0..iterations {
        let mut y: Vec<f64> = x.iter().zip(&scale).map(|(v, s)| v / s).collect();
        factor.solve_in_place(&mut y).unwrap();
        y.iter_mut().zip(&scale).for_each(|(v, s)| *v /= s);
        inverse_largest = y.iter().zip(&x).map(|(a, b)| a * b).sum::<f64>();
        x = y;
        normalise(&mut x);
    }
    (1.0 / inverse_largest, largest)
}

/// Eigenvalues of the dense Jacobi-scaled tangent at the state `(free, load)`, ascending
/// (small problems only).
pub fn scaled_spectrum<M: EnergyModel>(problem: &Problem<M>, free: &[f64], load: f64) -> Vec<f64> {
    let mut k = problem.new_matrix();
    problem.tangent_into(free, load, &mut k);
    let n = problem.free_count();
    let dense = k.to_dense();
    let scale: Vec<f64> = (0..n).map(|i| dense[(i, i)].abs().sqrt().recip()).collect();
    let scaled = nalgebra::DMatrix::from_fn(n, n, |i, j| dense[(i, j)] * scale[i] * scale[j]);
    let mut values: Vec<f64> = nalgebra::SymmetricEigen::new(scaled)
        .eigenvalues
        .iter()
        .copied()
        .collect();
    values.sort_by(f64::total_cmp);
    values
}

/// Smallest eigenvalue $`\mu`$ of $`K\varphi = \mu M\varphi`$, with $`K`$ the tangent of
/// `problem` at `(free, load)` and $`M`$ the deflection mass matrix $`\int N_a N_b`$ of
/// `mass` (the same mesh and constraints), by inverse iteration (`iterations` steps; an upper
/// bound that converges from above). Physically it is the square of the lowest natural
/// frequency times $`\rho h`$; a spurious zero-energy mode of the deflection would make it
/// vanish. Returns $`\mu`$ and the relative change over the last step.
pub fn lowest_mass_eigenvalue<M: EnergyModel>(
    problem: &Problem<M>,
    mass: &Problem<PlateMass>,
    free: &[f64],
    load: f64,
    iterations: usize,
) -> (f64, f64) {
    let n = problem.free_count();
    assert_eq!(n, mass.free_count());
    let mut k = problem.new_matrix();
    problem.tangent_into(free, load, &mut k);
    let mut m = mass.new_matrix();
    mass.tangent_into(&vec![0.0; n], 0.0, &mut m);
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    factor.factorize(&k).unwrap();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut x: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 13) as f64 / 13.0)
        .collect();
    let (mut mu, mut change) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..iterations {
        let mut mx = vec![0.0; n];
        m.multiply_into(&x, &mut mx);
        let mut y = mx.clone();
        factor.solve_in_place(&mut y).unwrap();
        // Rayleigh quotient xᵀ M x / xᵀ M y with y = K⁻¹ M x.
        let next = dot(&x, &mx) / dot(&y, &mx);
        change = ((next - mu) / next).abs();
        mu = next;
        let mut my = vec![0.0; n];
        m.multiply_into(&y, &mut my);
        let norm = dot(&y, &my).sqrt();
        x = y.iter().map(|v| v / norm).collect();
    }
    (mu, change)
}

/// Unit square plate, `n × n` mesh, with no Dirichlet condition at all.
pub fn free_square_plate<M: EnergyModel>(model: M, n: usize) -> Problem<M> {
    let mesh = Arc::new(Mesh::rectangle(1.0, 1.0, n, n, 1.0).unwrap());
    Problem::new(model, mesh, &[], &Default::default()).unwrap()
}

/// The paper's example 1 (THEORY.md §9): length along X.
pub const EXAMPLE1_LX: f64 = 400.0;
/// Width along Y.
pub const EXAMPLE1_LY: f64 = 200.0;
/// Thickness.
pub const EXAMPLE1_THICKNESS: f64 = 0.05;
/// Tension $`N_Y`$ on the Y edges (N/mm).
pub const EXAMPLE1_TENSION: f64 = 10.0;

/// `[0, lx] × [0, ly]` with `nx × ny` Q8 elements and separate symmetric geometric gradings
/// along X and Y (ratio largest/smallest element), built from [`Mesh::rectangle`] by moving its
/// grid lines (node numbering, edges and named points unchanged).
pub fn rectangle(lx: f64, ly: f64, nx: usize, ny: usize, grading_x: f64, grading_y: f64) -> Mesh {
    let mut mesh = Mesh::rectangle(lx, ly, nx, ny, 1.0).unwrap();
    let xs = graded_breakpoints(lx, nx, grading_x);
    let ys = graded_breakpoints(ly, ny, grading_y);
    let remap = |value: f64, length: f64, n: usize, breaks: &[f64]| {
        let k = (value / length * (2 * n) as f64).round() as usize;
        if k.is_multiple_of(2) {
            breaks[k / 2]
        } else {
            0.5 * (breaks[k / 2] + breaks[k / 2 + 1])
        }
    };
    for node in mesh.nodes.iter_mut() {
        *node = [remap(node[0], lx, nx, &xs), remap(node[1], ly, ny, &ys)];
    }
    mesh
}

/// Example 1 as a plate: $`N_X = -\lambda`$ on the X edges (proportional), $`N_Y = 10`$ on the
/// Y edges, in-plane supports of `src/setup.rs` (`biaxial`): $`u = v = 0`$ at `centre`,
/// $`v = 0`$ at `right_middle`; clamped on every edge ($`w = \theta_x = \theta_y = 0`$).
pub fn example1<M: EnergyModel>(model: M, mesh: Mesh) -> Problem<M> {
    let (u, v) = (field::<M>("u"), field::<M>("v"));
    let mut conditions = vec![
        fixed("centre", u),
        fixed("centre", v),
        fixed("right_middle", v),
    ];
    conditions.extend(plate_supports::<M>(Support::Clamped));
    let tractions: Vec<EdgeTraction> = [
        ("left", [1.0, 0.0], true),
        ("right", [-1.0, 0.0], true),
        ("bottom", [0.0, -EXAMPLE1_TENSION], false),
        ("top", [0.0, EXAMPLE1_TENSION], false),
    ]
    .into_iter()
    .map(|(edge, traction, proportional)| EdgeTraction {
        edge: edge.into(),
        fields: [u, v],
        traction,
        proportional,
    })
    .collect();
    let loads = Loads {
        tractions,
        ..Loads::default()
    };
    Problem::new(model, Arc::new(mesh), &conditions, &loads).unwrap()
}

/// Linear buckling of a problem (pre-buckling Newton at λ = 0, geometric stiffness from dual
/// numbers), first mode.
///
/// The pre-buckling Newton tolerance is 1e-6 instead of the default 1e-8: at λ = 0 the `u` field
/// carries no force at all (pure $`N_Y`$), so its residual is measured against the floor
/// `FIELD_SCALE_FLOOR` = 1e-6 of the `v` scale, and round-off (≈ 1e-13 of that scale on
/// 50k+ dof graded meshes) then stalls the relative residual at 1e-8–4e-8. The state is
/// linear in the load: one iteration reaches it to round-off.
pub fn buckle<M: EnergyModel>(problem: &Problem<M>) -> LinearBuckling {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut options = LinearBucklingOptions::default();
    options.newton.tolerance = 1e-6;
    linear_buckling(problem, &mut factor, &options).unwrap()
}

/// `(X, w)` at the nodes on the line $`Y = y`$, sorted by X, from a free-dof vector.
pub fn profile_along_x<M: EnergyModel>(
    problem: &Problem<M>,
    free: &[f64],
    y: f64,
) -> Vec<(f64, f64)> {
    let mesh = problem.assembler.mesh();
    let global = problem.dofs().expand(free, 0.0);
    let nf = problem.dofs().field_count;
    let w = field::<M>("w");
    let mut line: Vec<(f64, f64)> = mesh
        .nodes
        .iter()
        .enumerate()
        .filter(|(_, p)| (p[1] - y).abs() < 1e-9 * (1.0 + y.abs()))
        .map(|(k, p)| (p[0], global[k * nf + w]))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    line
}

/// Zero crossings of a sampled profile (linear interpolation), ignoring samples whose magnitude
/// is below `1e-6` of the largest (round-off near clamped ends).
pub fn zero_crossings(profile: &[(f64, f64)]) -> Vec<f64> {
    let largest = profile.iter().fold(0.0_f64, |m, (_, w)| m.max(w.abs()));
    let significant: Vec<(f64, f64)> = profile
        .iter()
        .copied()
        .filter(|(_, w)| w.abs() > 1e-6 * largest)
        .collect();
    significant
        .windows(2)
        .filter(|p| p[0].1 * p[1].1 < 0.0)
        .map(|p| p[0].0 - p[0].1 * (p[1].0 - p[0].0) / (p[1].1 - p[0].1))
        .collect()
}

/// Wavelength $`2\times`$ the mean spacing of the zero crossings inside `[from, to]`.
pub fn wavelength(crossings: &[f64], from: f64, to: f64) -> f64 {
    let inside: Vec<f64> = crossings
        .iter()
        .copied()
        .filter(|x| *x >= from && *x <= to)
        .collect();
    2.0 * (inside[inside.len() - 1] - inside[0]) / (inside.len() - 1) as f64
}
