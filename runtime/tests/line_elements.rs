//! The line elements of the element contract: Line3 (quadratic Lagrange) and Hermite2 (cubic
//! Hermite, value and slope per node), and the line meshes they fill.
//!
//! Reproduced: partition of unity and the nodal (interpolation) property of the shape
//! functions; physical derivatives against centred finite differences of the value row
//! (step $`10^{-4}`$ of the reference coordinate, agreement to $`10^{-6}`$ relative); exact
//! reproduction of quadratics by Line3 (value and $`\partial_X`$, on an element whose middle
//! node is off-centre only to first order: the map is then not affine, so only on the affine
//! one) and of cubics by Hermite2 (value, $`\partial_X`$, $`\partial_X^2`$) to round-off; line
//! meshes, uniform and graded, with `left`/`right` point sets, point location and
//! interpolation.
//!
//! Beams on Hermite2 (test models in the energy DSL, with `v.xx`):
//! * **Winkler beam, linear buckling** (Swift–Hohenberg, the paper's eqs 1–3): axial force
//!   $`\lambda`$ at the right end of a simply supported beam ($`v = 0`$ at both ends, the moment
//!   free) on a foundation $`c`$; the critical load is
//!   $`\lambda = \min_n EI(n\pi/L)^2 + c(L/n\pi)^2`$. `EI = c = 1`, `L = 12` (the minimum is
//!   $`n = 4`$, $`\lambda = 2.008\,513\ldots`$); 12, 24, 48 elements: the error falls as
//!   $`h^4`$ (measured: errors 1.70e-3, 1.12e-4, 7.1e-6, rates 3.92, 3.98; asserted above 3.9;
//!   from 6 elements the first rate is 3.70).
//! * **Clamped cantilever under an end force** $`P`$: $`v = PX^2(3L - X)/(6EI)`$, a cubic,
//!   reproduced by the element to round-off at every point.
//! * A model reading `v.xx` on a Q8 or a Line3 mesh is refused naming the element.

use std::sync::Arc;

use wrinkle_runtime::fem::{
    DirichletCondition, Element, ElementKind, ElementValues, GaussRule, Hermite2, Line3, Loads,
    Mesh, MeshError, NodalComponent, PointLoad,
};
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBucklingOptions, linear_buckling};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};

wrinkle_macros::energy_model! {
    /// Axially loaded beam on a linear Winkler foundation (test model).
    model WinklerBeam as "test-winkler-beam" {
        fields: u [displacement_x], v [deflection];
        parameters: ei, es, c;
        energy membrane = 0.5 * es * (u.x + 0.5 * v.x^2)^2;
        energy bending [reduced] = 0.5 * ei * v.xx^2;
        energy winkler = 0.5 * c * v^2;
    }
}

wrinkle_macros::energy_model! {
    /// Euler–Bernoulli bending alone (test model).
    model Bending as "test-bending" {
        fields: v [deflection];
        parameters: ei;
        energy bending [reduced] = 0.5 * ei * v.xx^2;
    }
}

/// Element values of `E` at the single reference point `xi` (weight 1).
fn at_point<E: Element>(coordinates: &[[f64; 2]], xi: f64) -> ElementValues {
    let rule = GaussRule {
        points: vec![[xi, 0.0]],
        weights: vec![1.0],
    };
    ElementValues::new::<E>(0, coordinates, &rule).expect("a valid element")
}

/// $`\sum_b \varphi_b U_b`$ of basis row `row` at the single point of `values`.
fn combine(values: &ElementValues, row: usize, dofs: &[f64]) -> f64 {
    values
        .row(0, row)
        .iter()
        .zip(dofs)
        .map(|(b, u)| b * u)
        .sum()
}

const LINE3: [[f64; 2]; 3] = [[1.3, 0.0], [2.1, 0.0], [1.7, 0.0]];
/// A Line3 whose middle node is off-centre: the map is quadratic (still one-to-one).
const LINE3_CURVED_MAP: [[f64; 2]; 3] = [[1.3, 0.0], [2.1, 0.0], [1.8, 0.0]];
const HERMITE: [[f64; 2]; 2] = [[1.3, 0.0], [2.1, 0.0]];

#[test]
fn line3_shape_functions_partition_unity_and_are_nodal() {
    for (j, &[xi_j, _]) in Line3::REFERENCE_NODES.iter().enumerate() {
        let n = Line3::shape_values(xi_j);
        for (i, value) in n.iter().enumerate() {
            assert_eq!(*value, if i == j { 1.0 } else { 0.0 }, "N_{i}(ξ_{j})");
        }
    }
    for xi in [-0.83, -0.2, 0.0, 0.41, 0.97] {
        let values = at_point::<Line3>(&LINE3_CURVED_MAP, xi);
        let sum: f64 = values.row(0, 0).iter().sum();
        let slope: f64 = values.row(0, 1).iter().sum();
        assert!((sum - 1.0).abs() < 1e-15 && slope.abs() < 1e-13, "ξ = {xi}");
    }
}

#[test]
fn hermite2_value_functions_partition_unity_and_interpolate_values_and_slopes() {
    // Functions: value at node 0, slope at node 0, value at node 1, slope at node 1.
    let h = HERMITE[1][0] - HERMITE[0][0];
    for (node, xi) in [(0, -1.0), (1, 1.0)] {
        let values = at_point::<Hermite2>(&HERMITE, xi);
        for b in 0..4 {
            let is_value = b == 2 * node;
            let is_slope = b == 2 * node + 1;
            let expected_value = if is_value { 1.0 } else { 0.0 };
            let expected_slope = if is_slope { 1.0 } else { 0.0 };
            assert!(
                (values.row(0, 0)[b] - expected_value).abs() < 1e-15,
                "φ_{b}(X_{node})"
            );
            let slope = values.row(0, 1)[b];
            assert!(
                (slope - expected_slope).abs() < 1e-14,
                "φ_{b}'(X_{node}) = {slope}"
            );
        }
    }
    for xi in [-0.7, 0.0, 0.3, 0.9] {
        let values = at_point::<Hermite2>(&HERMITE, xi);
        // v = 1: both nodal values 1, slopes 0.
        assert!((combine(&values, 0, &[1.0, 0.0, 1.0, 0.0]) - 1.0).abs() < 1e-15);
        assert!(combine(&values, 1, &[1.0, 0.0, 1.0, 0.0]).abs() < 1e-13);
        assert!(combine(&values, 2, &[1.0, 0.0, 1.0, 0.0]).abs() < 1e-12);
    }
    assert!((h - 0.8_f64).abs() < 1e-15);
}

/// Centred differences of the value row against the derivative rows: row 1 against
/// $`\Delta\varphi/\Delta X`$, and (when the element supplies it) row 2 against the second
/// difference.
fn check_derivatives<E: Element>(coordinates: &[[f64; 2]], second: bool) {
    let step = 1e-4;
    for xi in [-0.77, -0.1, 0.35, 0.88] {
        let (minus, centre, plus) = (
            at_point::<E>(coordinates, xi - step),
            at_point::<E>(coordinates, xi),
            at_point::<E>(coordinates, xi + step),
        );
        let dx = plus.points[0][0] - minus.points[0][0];
        for b in 0..E::FUNCTIONS {
            let difference = (plus.row(0, 0)[b] - minus.row(0, 0)[b]) / dx;
            let exact = centre.row(0, 1)[b];
            assert!(
                (difference - exact).abs() < 1e-6 * (1.0 + exact.abs()),
                "∂X φ_{b}({xi}): {exact} vs {difference}"
            );
            if second {
                let h = 0.5 * dx;
                let difference =
                    (plus.row(0, 0)[b] - 2.0 * centre.row(0, 0)[b] + minus.row(0, 0)[b]) / (h * h);
                let exact = centre.row(0, 2)[b];
                assert!(
                    (difference - exact).abs() < 1e-5 * (1.0 + exact.abs()),
                    "∂XX φ_{b}({xi}): {exact} vs {difference}"
                );
            }
        }
    }
}

#[test]
fn line_derivatives_match_finite_differences() {
    check_derivatives::<Line3>(&LINE3, false);
    check_derivatives::<Line3>(&LINE3_CURVED_MAP, false);
    check_derivatives::<Hermite2>(&HERMITE, true);
}

#[test]
fn line3_reproduces_quadratics_and_hermite2_cubics_exactly() {
    let quadratic = |x: f64| [0.7 - 1.1 * x + 0.45 * x * x, -1.1 + 0.9 * x];
    let dofs: Vec<f64> = LINE3.iter().map(|p| quadratic(p[0])[0]).collect();
    let values = ElementValues::new::<Line3>(0, &LINE3, &GaussRule::line(3)).unwrap();
    for q in 0..values.point_count() {
        let x = values.points[q][0];
        let [value, slope] = quadratic(x);
        let row =
            |r: usize| -> f64 { values.row(q, r).iter().zip(&dofs).map(|(b, u)| b * u).sum() };
        assert!((row(0) - value).abs() < 1e-14 && (row(1) - slope).abs() < 1e-13);
    }
    let length: f64 = values.weights.iter().sum();
    assert!((length - 0.8).abs() < 1e-15);

    let cubic = |x: f64| {
        [
            0.3 + 0.5 * x - 1.2 * x * x + 0.4 * x.powi(3),
            0.5 - 2.4 * x + 1.2 * x * x,
            -2.4 + 2.4 * x,
        ]
    };
    // Dofs: value and slope dv/dX at each node.
    let dofs: Vec<f64> = HERMITE
        .iter()
        .flat_map(|p| [cubic(p[0])[0], cubic(p[0])[1]])
        .collect();
    let values = ElementValues::new::<Hermite2>(0, &HERMITE, &GaussRule::line(4)).unwrap();
    for q in 0..values.point_count() {
        let exact = cubic(values.points[q][0]);
        for (r, want) in exact.iter().enumerate() {
            let got: f64 = values.row(q, r).iter().zip(&dofs).map(|(b, u)| b * u).sum();
            assert!(
                (got - want).abs() < 1e-13,
                "row {r} at point {q}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn line_meshes_uniform_and_graded_with_end_points() {
    for kind in [ElementKind::Line3, ElementKind::Hermite2] {
        for grading in [1.0, 4.0] {
            let mesh = Mesh::line(12.0, 6, grading, kind).unwrap();
            assert_eq!(mesh.element_count(), 6);
            let nodes = if kind == ElementKind::Line3 { 13 } else { 7 };
            assert_eq!(mesh.nodes.len(), nodes);
            assert_eq!(mesh.boundary_nodes("left"), Some(vec![0]));
            assert_eq!(mesh.boundary_nodes("right"), Some(vec![nodes - 1]));
            assert_eq!(mesh.nodes[nodes - 1], [12.0, 0.0]);
            // Nodes left to right.
            assert!(mesh.nodes.windows(2).all(|pair| pair[0][0] < pair[1][0]));
            let sizes: Vec<f64> = (0..6)
                .map(|e| {
                    let c = mesh.element_coordinates(e);
                    c[1][0] - c[0][0]
                })
                .collect();
            let ratio = sizes.iter().cloned().fold(0.0, f64::max)
                / sizes.iter().cloned().fold(f64::INFINITY, f64::min);
            assert!((ratio - grading).abs() < 1e-12, "{kind}: {sizes:?}");
        }
    }
    assert_eq!(
        Mesh::line(1.0, 2, 1.0, ElementKind::Quad8).unwrap_err(),
        MeshError::NotALineElement(ElementKind::Quad8)
    );
    assert!(matches!(
        Mesh::new(
            ElementKind::Line3,
            vec![[0.0, 0.0], [1.0, 0.1], [0.5, 0.0]],
            vec![0, 1, 2]
        ),
        Err(MeshError::OffAxis { node: 1, .. })
    ));
}

#[test]
fn line_meshes_locate_and_interpolate_polynomials_of_their_degree() {
    // Line3: quadratic; one field at each node.
    let quadratic = |x: f64| 2.0 - 0.3 * x + 0.05 * x * x;
    let mesh = Mesh::line(10.0, 5, 3.0, ElementKind::Line3).unwrap();
    let values: Vec<f64> = mesh.nodes.iter().map(|p| quadratic(p[0])).collect();
    // Hermite2: cubic, two fields (the second holds the cubic), value and slope per node.
    let cubic = |x: f64| {
        [
            1.0 + x - 0.2 * x * x + 0.01 * x.powi(3),
            1.0 - 0.4 * x + 0.03 * x * x,
        ]
    };
    let hermite = Mesh::line(10.0, 5, 3.0, ElementKind::Hermite2).unwrap();
    let dofs: Vec<f64> = hermite
        .nodes
        .iter()
        .flat_map(|p| {
            let [v, slope] = cubic(p[0]);
            [0.0, 0.0, v, slope]
        })
        .collect();
    for x in [0.0, 0.37, 2.5, 5.0, 7.77, 10.0] {
        let at = mesh.interpolate(&values, 1, 0, [x, 0.0]).unwrap();
        assert!((at - quadratic(x)).abs() < 1e-13, "Line3 at {x}");
        let at = hermite.interpolate(&dofs, 2, 1, [x, 0.0]).unwrap();
        assert!((at - cubic(x)[0]).abs() < 1e-12, "Hermite2 at {x}");
        // The structured location and the element scan agree on the point.
        let mut general = hermite.clone();
        general.grid = None;
        let (e, [xi, _]) = general.locate([x, 0.0]).unwrap();
        let c = general.element_coordinates(e);
        let mapped = 0.5 * (1.0 - xi) * c[0][0] + 0.5 * (1.0 + xi) * c[1][0];
        assert!((mapped - x).abs() < 1e-12);
    }
    for outside in [[-0.1, 0.0], [10.1, 0.0], [5.0, 0.5]] {
        assert!(mesh.locate(outside).is_none(), "{outside:?}");
        let mut general = mesh.clone();
        general.grid = None;
        assert!(general.locate(outside).is_none(), "{outside:?} by scan");
    }
}

/// $`\min_n EI(n\pi/L)^2 + c(L/n\pi)^2`$: the simply supported Winkler beam's critical load.
fn winkler_closed_form(ei: f64, c: f64, length: f64) -> f64 {
    (1..1000)
        .map(|n| {
            let k = n as f64 * std::f64::consts::PI / length;
            ei * k * k + c / (k * k)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Critical load of the simply supported Winkler beam on `elements` Hermite2 elements: `u = 0`
/// at the left end, force $`-\lambda`$ on `u` at the right one, `v = 0` at both.
fn winkler_critical_load(length: f64, elements: usize) -> f64 {
    let mesh = Arc::new(Mesh::line(length, elements, 1.0, ElementKind::Hermite2).unwrap());
    let conditions = [
        DirichletCondition::fixed("left", 0),
        DirichletCondition::fixed("left", 1),
        DirichletCondition::fixed("right", 1),
    ];
    let loads = Loads {
        point_loads: vec![PointLoad {
            point: "right".into(),
            field: 0,
            component: NodalComponent::Value,
            value: -1.0,
            proportional: true,
        }],
        ..Loads::default()
    };
    let problem = Problem::new(WinklerBeam::new(1.0, 1e4, 1.0), mesh, &conditions, &loads).unwrap();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let result = linear_buckling(&problem, &mut factor, &LinearBucklingOptions::default()).unwrap();
    result.critical_loads[0]
}

#[test]
fn hermite2_winkler_beam_buckles_at_the_closed_form_load_with_error_h4() {
    let length = 12.0;
    let exact = winkler_closed_form(1.0, 1.0, length);
    assert!((exact - 2.008_513_364).abs() < 1e-8, "closed form {exact}");
    let errors: Vec<f64> = [12, 24, 48]
        .iter()
        .map(|&n| winkler_critical_load(length, n) - exact)
        .collect();
    let rates: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    println!("Winkler beam λ_c errors {errors:?}, rates {rates:?} (closed form {exact})");
    assert!(errors.iter().all(|&e| e > 0.0), "from above: {errors:?}");
    assert!(rates.iter().all(|&r| r > 3.9), "rates {rates:?}");
    assert!(errors[2] < 1e-5 * exact);
}

#[test]
fn hermite2_clamped_cantilever_reproduces_the_cubic_deflection() {
    let (length, ei, force) = (3.0, 2.5, 0.7);
    let mesh = Arc::new(Mesh::line(length, 5, 2.0, ElementKind::Hermite2).unwrap());
    let conditions = DirichletCondition::clamped("left", 0, ElementKind::Hermite2);
    let loads = Loads {
        point_loads: vec![PointLoad {
            point: "right".into(),
            field: 0,
            component: NodalComponent::Value,
            value: force,
            proportional: false,
        }],
        ..Loads::default()
    };
    let problem = Problem::new(Bending::new(ei), mesh.clone(), &conditions, &loads).unwrap();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut matrix = problem.new_matrix();
    let options = NewtonOptions {
        tolerance: 1e-13,
        ..NewtonOptions::default()
    };
    let zero = vec![0.0; problem.free_count()];
    let solution = newton(&problem, zero, 0.0, &mut factor, &mut matrix, &options).unwrap();
    let global = problem.dofs().expand(&solution.solution, 0.0);
    let exact = |x: f64| force * x * x * (3.0 * length - x) / (6.0 * ei);
    let tip = exact(length);
    for x in [0.0, 0.4, 1.1, 1.5, 2.2, 2.9, 3.0] {
        let v = mesh.interpolate(&global, 1, 0, [x, 0.0]).unwrap();
        assert!(
            (v - exact(x)).abs() < 1e-12 * tip,
            "v({x}) = {v}, exact {}",
            exact(x)
        );
    }
    // The slope dof is the physical dv/dX: P X (2L − X)/(2EI) at the tip.
    let last = mesh.nodes.len() - 1;
    let slope = global[problem.dofs().global_index(last, 0, 1)];
    let exact_slope = force * length * length / (2.0 * ei);
    assert!(
        (slope - exact_slope).abs() < 1e-12 * exact_slope,
        "tip slope {slope}"
    );
}

#[test]
fn v_xx_is_refused_on_q8_and_line3_naming_the_element() {
    let meshes = [
        Mesh::rectangle(2.0, 1.0, 2, 1, 1.0).unwrap(),
        Mesh::line(2.0, 2, 1.0, ElementKind::Line3).unwrap(),
    ];
    for mesh in meshes {
        let kind = mesh.kind;
        let error = Problem::new(
            WinklerBeam::new(1.0, 1.0, 1.0),
            Arc::new(mesh),
            &[],
            &Loads::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(
            error.contains(kind.name()) && error.contains("`v.xx`"),
            "{kind}: {error}"
        );
    }
}
