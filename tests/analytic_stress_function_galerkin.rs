//! Multi-term Galerkin solution of the stress-function problem (55) of Damil, Potier-Ferry & Hu
//! (2014) (`src/closed_form/stress_function.rs`), of which the one-term C(α) of (62) is the
//! truncation.
//!
//! Reference: an independent 40-digit computation (mpmath 1.3, `mp.dps = 40`, 192-point
//! Gauss–Legendre, basis (1 − r²)²(1 − s²)² P_2m(r) P_2n(s) directly — not the library's
//! equivalent Shen basis —, dense LU) of C_K = √(8 I_3/(3π⁴(1 − ν²) bᵀA⁻¹b)) (i.e. with
//! J = (π²/4) bᵀA⁻¹b), ν = 0.3, K terms per direction:
//!
//! | K | terms | C_K (α = 1)           | C_K (α = 0.5)         |
//! |---|-------|-----------------------|-----------------------|
//! | 1 |   1   | 1.6509242685072267188 | 1.1303105782426547347 |
//! | 2 |   4   | 1.5796730141768946589 | 1.0898696342715747695 |
//! | 3 |   9   | 1.5790297051937046118 | 1.0892873670088603137 |
//! | 4 |  16   | 1.5790220251259830781 | 1.0892664932399811827 |
//! | 5 |  25   | 1.5790217807437458620 | 1.0892640830237101635 |
//! | 6 |  36   | 1.5790217745452858138 | 1.0892638641695726970 |
//! | 7 |  49   | 1.5790217743310032351 | 1.0892638419943730844 |
//! | 8 |  64   | 1.5790217738215432486 | 1.0892638397819099134 |
//! | 9 |  81   | 1.5790217734592754795 | 1.0892638396261343991 |
//! |10 | 100   | 1.5790217732692444396 | 1.0892638396165500923 |
//!
//! Expected: the one-term solution equals C(α) of (62) to rounding; the sequence matches the
//! reference; J increases (Galerkin under-estimates a compliance) so C decreases; the changes
//! shrink to ~1e-12 at K = 20 (the tail is slow and, for α = 1 and 0.5, non-monotone around
//! K = 7–12). Converged values (K = 20, 400 terms, this library): C = 1.5790217731038 (α = 1),
//! 1.0892638395392 (α = 0.5), 3.8909876956410 (α = 2); the one-term closed form is above them by
//! 4.55 %, 3.77 % and 16.2 %.

use wrinkle::closed_form::amplitude_coefficient;
use wrinkle::closed_form::stress_function::{ConvergenceStop, converge, relative_changes, solve};

const REFERENCE_SQUARE: [f64; 10] = [
    1.650_924_268_507_226_7,
    1.579_673_014_176_894_7,
    1.579_029_705_193_704_6,
    1.579_022_025_125_983,
    1.579_021_780_743_745_9,
    1.579_021_774_545_285_8,
    1.579_021_774_331_003,
    1.579_021_773_821_543_2,
    1.579_021_773_459_275_5,
    1.579_021_773_269_244_4,
];

const REFERENCE_HALF: [f64; 10] = [
    1.130_310_578_242_654_7,
    1.089_869_634_271_574_8,
    1.089_287_367_008_860_3,
    1.089_266_493_239_981_2,
    1.089_264_083_023_710_2,
    1.089_263_864_169_572_7,
    1.089_263_841_994_373_1,
    1.089_263_839_781_909_9,
    1.089_263_839_626_134_4,
    1.089_263_839_616_550_1,
];

#[test]
fn one_term_galerkin_is_the_closed_form_amplitude_coefficient() {
    for aspect_ratio in [0.25, 0.5, 1.0, 2.0] {
        for poisson_ratio in [0.0, 0.3, 0.45] {
            let one_term = solve(aspect_ratio, poisson_ratio, 1).unwrap();
            let closed = amplitude_coefficient(aspect_ratio, poisson_ratio);
            assert_eq!(one_term.terms, 1);
            assert!(
                ((one_term.amplitude_coefficient - closed) / closed).abs() < 1e-14,
                "α = {aspect_ratio}, ν = {poisson_ratio}: {} vs {closed}",
                one_term.amplitude_coefficient
            );
        }
    }
}

#[test]
fn multi_term_galerkin_matches_the_forty_digit_reference() {
    for (aspect_ratio, reference) in [(1.0, REFERENCE_SQUARE), (0.5, REFERENCE_HALF)] {
        for (index, expected) in reference.iter().enumerate() {
            let solution = solve(aspect_ratio, 0.3, index + 1).unwrap();
            assert_eq!(solution.terms, (index + 1) * (index + 1));
            let error = ((solution.amplitude_coefficient - expected) / expected).abs();
            assert!(
                error < 1e-12,
                "α = {aspect_ratio}, K = {}: {} vs {expected} ({error:e})",
                index + 1,
                solution.amplitude_coefficient
            );
        }
    }
}

#[test]
fn multi_term_galerkin_converges_with_shrinking_differences() {
    for (aspect_ratio, converged, excess) in [
        (0.5, 1.089_263_839_539_2, 0.0377),
        (1.0, 1.579_021_773_103_8, 0.0455),
        (2.0, 3.890_987_695_641_0, 0.162),
    ] {
        let solutions: Vec<_> = (1..=20)
            .map(|terms| solve(aspect_ratio, 0.3, terms).unwrap())
            .collect();
        // Nested spaces: the compliance J increases, so C decreases.
        for pair in solutions.windows(2) {
            assert!(pair[1].load_integral >= pair[0].load_integral * (1.0 - 1e-13));
        }
        let changes = relative_changes(&solutions);
        // Every later change is below each of the first five (K = 2..6) …
        for (index, change) in changes.iter().enumerate().take(5) {
            let later = changes[index + 1..].iter().fold(0.0f64, |a, b| a.max(*b));
            assert!(later < *change, "α = {aspect_ratio}, K = {}", index + 2);
        }
        // … and the last ones are at the 1e-12 level.
        assert!(
            changes[changes.len() - 3..].iter().all(|c| *c < 2e-12),
            "{changes:?}"
        );
        let last = solutions[19].amplitude_coefficient;
        assert!(
            ((last - converged) / converged).abs() < 1e-12,
            "α = {aspect_ratio}: {last}"
        );
        // The one-term closed form over-estimates the converged C.
        let one_term_excess = solutions[0].amplitude_coefficient / last - 1.0;
        assert!(
            (one_term_excess - excess).abs() < 1e-3,
            "α = {aspect_ratio}: {one_term_excess}"
        );
    }
}

#[test]
fn convergence_runner_reports_why_it_stopped() {
    let converged = converge(1.0, 0.3, 24, 1e-12).unwrap();
    assert_eq!(converged.stop, ConvergenceStop::Converged);
    let changes = relative_changes(&converged.solutions);
    assert!(changes[changes.len() - 2..].iter().all(|c| *c <= 1e-12));
    // The K = 17, 18 changes are 5.3e-13 and 2.5e-13: it stops at 324 terms.
    assert_eq!(converged.converged().terms, 324);
    let limited = converge(1.0, 0.3, 3, 1e-9).unwrap();
    assert_eq!(limited.stop, ConvergenceStop::TermLimit);
    assert_eq!(limited.solutions.len(), 3);
    assert_eq!(limited.converged().terms, 9);
}
