//! The stress suite (issue 6): what must hold at the edges of what the solver is asked to
//! do. The cases, the error measure and the condition rule are those of
//! `tendyn_spec::stress` (read its module documentation first); in short:
//!
//! - errors are max-norm relative per output vector against the double-double run, the
//!   denominator floored at 1 % of the output's typical size (and for forward dynamics at
//!   the size of the terms it sums);
//! - every output `o` of every valid case stays within `C u κ_o`, with
//!   `κ_o = 1 + max|θ| (+ cond(E)·spread(p) for tension outputs) (+ cond(D^-½MD^-½) for
//!   forward dynamics)`, `C = 8 (bodies + unknowns)`; in `f64` and in `f32`;
//! - a case is well conditioned when that bound is at most 1e-9 in `f64` for every output,
//!   and then the error is at most 1e-9;
//! - out of range, the solver returns an error or a flag, never a silent NaN.
//!
//! Long sweeps are `#[ignore]`d; everything else measures each case once (40 states).

use std::sync::OnceLock;
use tendyn_core::{Data, DoubleDouble, Error, Model, Real};
use tendyn_spec::stress::{
    self, measure_case, CaseFigures, Options, StressCase, WELL_CONDITIONED_TARGET,
};

const U64: f64 = f64::EPSILON / 2.0;
const U32: f64 = (f32::EPSILON as f64) / 2.0;

/// Every case measured once, shared by the tests of this file (two threads).
fn figures() -> &'static [(StressCase, Result<CaseFigures, Error>)] {
    static ALL: OnceLock<Vec<(StressCase, Result<CaseFigures, Error>)>> = OnceLock::new();
    ALL.get_or_init(|| {
        let cases = stress::cases();
        let half = cases.len() / 2;
        let measure = |cs: &[StressCase]| -> Vec<(StressCase, Result<CaseFigures, Error>)> {
            cs.iter()
                .map(|c| (c.clone(), measure_case(c, Options::default(), None)))
                .collect()
        };
        let (a, b) = cases.split_at(half);
        std::thread::scope(|s| {
            let first = s.spawn(|| measure(a));
            let mut all = measure(b);
            let mut out = first.join().expect("measurement thread");
            out.append(&mut all);
            out
        })
    })
}

fn measured(name: &str) -> &'static CaseFigures {
    figures()
        .iter()
        .find(|(c, _)| c.name == name)
        .unwrap_or_else(|| panic!("no case {name}"))
        .1
        .as_ref()
        .unwrap_or_else(|e| panic!("{name} did not validate: {e}"))
}

#[test]
fn the_paper_examples_are_within_1e_12_in_f64_and_1e_5_in_f32() {
    for case in stress::paper_cases() {
        let f = measure_case(
            &case,
            Options {
                states: 200,
                f32: true,
            },
            None,
        )
        .unwrap();
        println!(
            "{}: f64 {:.1e} (median {:.1e}), f32 {:.1e} (median {:.1e})",
            f.name,
            f.runtime_f64.max,
            f.runtime_f64.median,
            f.runtime_f32.max,
            f.runtime_f32.median
        );
        assert!(
            f.runtime_f64.max <= 1e-12,
            "{}: f64 {:.2e}",
            f.name,
            f.runtime_f64.max
        );
        assert!(
            f.runtime_f32.max <= 1e-5,
            "{}: f32 {:.2e}",
            f.name,
            f.runtime_f32.max
        );
        assert!(
            f.runtime_f64.max > 0.0,
            "the reference must differ somewhere"
        );
        assert_eq!(f.outcomes.ok, 200);
    }
}

#[test]
fn every_output_of_every_valid_case_is_within_its_condition_bound() {
    let mut rejected = 0;
    for (case, f) in figures() {
        let Ok(f) = f else {
            rejected += 1;
            continue;
        };
        for o in &f.outputs {
            let (b64, b32) = (f.bound(o, U64), f.bound(o, U32));
            assert!(
                o.runtime_f64.max <= b64,
                "{} {}: f64 error {:.2e} above C u κ = {b64:.2e} (κ {:.2e})",
                case.name,
                o.name,
                o.runtime_f64.max,
                o.kappa
            );
            assert!(
                o.runtime_f32.max <= b32,
                "{} {}: f32 error {:.2e} above C u κ = {b32:.2e} (κ {:.2e})",
                case.name,
                o.name,
                o.runtime_f32.max,
                o.kappa
            );
        }
    }
    assert_eq!(
        rejected, 1,
        "only the rank-lost structure matrix is rejected"
    );
}

#[test]
fn well_conditioned_cases_are_within_1e_9_in_f64_and_the_rule_tells_them_apart() {
    let (mut well, mut ill) = (Vec::new(), Vec::new());
    for (case, f) in figures() {
        let Ok(f) = f else { continue };
        if f.well_conditioned() {
            assert!(
                f.runtime_f64.max <= WELL_CONDITIONED_TARGET,
                "{}: well conditioned but f64 is {:.2e} from the reference",
                case.name,
                f.runtime_f64.max
            );
            well.push(case.name.as_str());
        } else {
            ill.push((case.name.as_str(), f.runtime_f64.max));
        }
    }
    println!("well conditioned: {}", well.len());
    println!("ill conditioned: {ill:?}");
    // The rule must separate: the tiny drums and the nearly rank-deficient structure
    // matrices are not well conditioned, and everything with moderate condition is.
    for name in [
        "radius_ratio_1e-3",
        "radius_ratio_1e-2",
        "near_rank_loss_1e-6",
        "near_rank_loss_1e-8",
    ] {
        assert!(
            ill.iter().any(|(n, _)| *n == name),
            "{name} should be ill conditioned"
        );
    }
    assert!(
        well.len() > 50,
        "only {} well-conditioned cases",
        well.len()
    );
    // ... and the ill-conditioned ones do lose accuracy: the rule is not merely cautious.
    assert!(ill.iter().any(|(_, e)| *e > WELL_CONDITIONED_TARGET / 10.0));
}

/// Median error over states against the number of links, for a family of chains.
fn growth(family: &str, links: std::ops::RangeInclusive<usize>) -> Vec<(usize, f64)> {
    links
        .map(|n| (n, measured(&format!("{family}_{n}")).runtime_f64.median))
        .collect()
}

#[test]
fn error_grows_at_most_linearly_with_the_number_of_links() {
    for (family, links) in [("motor_chain", 2..=12), ("tendon_chain", 2..=11)] {
        let g = growth(family, links);
        let shown: Vec<String> = g.iter().map(|(n, e)| format!("{n}: {e:.1e}")).collect();
        println!("{family}: {}", shown.join(", "));
        let (n0, e0) = g[0];
        let (n1, e1) = g[g.len() - 1];
        // The longest chain against the shortest: at most proportional, with a factor 2 of
        // slack for the spread of a 40-state median.
        assert!(
            e1 / e0 <= 2.0 * n1 as f64 / n0 as f64,
            "{family}: median error {e0:.2e} at {n0} links, {e1:.2e} at {n1}"
        );
        // Least-squares slope of log(error) against log(links): at most 1 (linear).
        let pts: Vec<(f64, f64)> = g.iter().map(|&(n, e)| ((n as f64).ln(), e.ln())).collect();
        let k = pts.len() as f64;
        let (mx, my) = (
            pts.iter().map(|p| p.0).sum::<f64>() / k,
            pts.iter().map(|p| p.1).sum::<f64>() / k,
        );
        let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        println!("{family}: log-log slope {slope:.2}");
        assert!(slope <= 1.0, "{family}: error grows as links^{slope:.2}");
    }
}

#[test]
fn no_case_returns_a_silent_nan_or_disagrees_with_the_reference_on_errors_and_flags() {
    for (case, f) in figures() {
        let Ok(f) = f else { continue };
        let o = &f.outcomes;
        assert_eq!(
            o.silent_non_finite, 0,
            "{}: a non-finite number returned",
            case.name
        );
        assert_eq!(
            o.f32_silent_non_finite, 0,
            "{}: f32 returned a non-finite number",
            case.name
        );
        assert_eq!(
            o.error_mismatches, 0,
            "{}: f64 and reference disagree on errors",
            case.name
        );
        assert_eq!(
            o.flag_mismatches, 0,
            "{}: f64 and reference disagree on slack",
            case.name
        );
    }
}

#[test]
fn a_structure_matrix_past_the_rank_limit_is_rejected_naming_the_joints() {
    let case = stress::rank_loss(1e-11);
    match case.model() {
        Err(e @ Error::Routing { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.contains("full row rank") && msg.contains("l1") && msg.contains("l2"),
                "{msg}"
            );
        }
        other => panic!("expected a routing error, got {other:?}"),
    }
    // The last accepted one still solves in f64, to cond(E)·u; in f32 its structure matrix
    // is singular (ε = 1e-8 is below f32's resolution), and f32 says so instead of
    // returning numbers at the states that need the lost direction.
    let f = measured("near_rank_loss_1e-8");
    assert!(f.cond_e > 1e7 && f.outcomes.ok == f.outcomes.states);
    assert!(f.outcomes.f32_only_errors > 0);
    assert_eq!(f.outcomes.f32_silent_non_finite, 0);
}

#[test]
fn tensions_near_and_past_the_pretension_are_flagged_and_max_tension_is_an_error() {
    // Loop with a small pretension: some states slack (flagged), some not, and exactly
    // where one side is negative.
    let near = measured("loop_near_slack");
    assert!(
        near.outcomes.flagged > 0 && near.outcomes.flagged < near.outcomes.ok,
        "{:?}",
        near.outcomes
    );
    let none = measured("loop_no_pretension");
    assert_eq!(none.outcomes.flagged, none.outcomes.states);
    let case = stress::case("loop_near_slack");
    let model = case.model().unwrap();
    let mut s = Data::new(&model);
    for [q, qd, qdd] in case.states(model.dof(), 40) {
        let r = s.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        let negative = r.loop_sides[0].iter().any(|&t| t < 0.0);
        assert_eq!(r.slack_loops(), vec![negative]);
        assert!((r.loop_sides[0][0] + r.loop_sides[0][1] - 8.0).abs() < 1e-12);
    }
    // A tendon that some states need above its max_tension: an error naming it there, the
    // same states as the reference, numbers elsewhere.
    let max = measured("tendon_max_tension");
    assert!(
        max.outcomes.tension_errors > 0 && max.outcomes.ok > 0,
        "{:?}",
        max.outcomes
    );
    let msg = max.outcomes.first_error.as_deref().unwrap_or("");
    assert!(msg.contains("`T11` at its maximum 200 N"), "{msg}");
}

#[test]
fn a_massless_distal_link_makes_forward_dynamics_an_error_and_light_ones_stay_accurate() {
    let massless = measured("massless_distal");
    assert_eq!(massless.outcomes.singular_errors, massless.outcomes.states);
    assert_eq!(
        massless.outcomes.ok, massless.outcomes.states,
        "inverse dynamics still works"
    );
    for name in [
        "light_distal_1e-6",
        "light_distal_1e-9",
        "light_distal_1e-12",
    ] {
        let f = measured(name);
        let fd = f
            .outputs
            .iter()
            .find(|o| o.name == "forward_dynamics")
            .unwrap();
        // cond(M) is huge, but only through the scale of the light link: Cholesky's error
        // follows the diagonally scaled condition number, which stays small.
        assert!(f.cond_m.max > 1e6 && f.cond_m_scaled.max < 10.0, "{name}");
        assert!(
            fd.runtime_f64.max < 1e-14,
            "{name}: {:.2e}",
            fd.runtime_f64.max
        );
    }
}

fn mechanisms_for_range_checks() -> Vec<Model<f64>> {
    [
        "example1_endless",
        "example3_stanford_jpl",
        "tendon_chain_4",
        "motor_chain_3",
    ]
    .into_iter()
    .map(|n| stress::case(n).model().unwrap())
    .collect()
}

#[test]
fn non_finite_and_overflowing_states_are_errors_in_every_precision() {
    for m in mechanisms_for_range_checks() {
        let n = m.dof();
        let mut s = Data::new(&m);
        let ok = vec![0.3; n];
        let (mt, tt) = (vec![0.0; m.motors().len()], vec![1.0; m.tendons().len()]);
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut v = ok.clone();
            v[n - 1] = bad;
            for r in [
                s.inverse_dynamics(&m, &v, &ok, &ok).map(|_| ()),
                s.inverse_dynamics(&m, &ok, &v, &ok).map(|_| ()),
                s.inverse_dynamics(&m, &ok, &ok, &v).map(|_| ()),
                s.forward_dynamics(&m, &ok, &v, &mt, &tt).map(|_| ()),
                s.mass_matrix(&m, &v).map(|_| ()),
            ] {
                assert!(matches!(r, Err(Error::State(_))), "{}: {r:?}", m.name());
            }
        }
        // Finite inputs whose squares overflow: an error, not a NaN.
        let huge = vec![1e200; n];
        for r in [
            s.inverse_dynamics(&m, &ok, &huge, &ok).map(|_| ()),
            s.bias(&m, &ok, &huge).map(|_| ()),
            s.generalized_forces(&m, &ok, &huge, &ok).map(|_| ()),
            s.forward_dynamics(&m, &ok, &huge, &mt, &tt).map(|_| ()),
        ] {
            assert!(
                matches!(r, Err(Error::State(_)) | Err(Error::Tension(_))),
                "{}: {r:?}",
                m.name()
            );
        }
        // In f32 the same happens far sooner (1e20² overflows).
        let m32 = m.cast_numeric::<f32>();
        let mut s32 = Data::new(&m32);
        let (ok32, huge32) = (vec![0.3f32; n], vec![1e20f32; n]);
        let r = s32.inverse_dynamics(&m32, &ok32, &huge32, &ok32);
        assert!(r.is_err(), "{}: f32 overflow returned {r:?}", m.name());
        let r = s32.bias(&m32, &ok32, &huge32);
        assert!(matches!(r, Err(Error::State(_))), "{}: {r:?}", m.name());
    }
}

#[test]
fn formulation_fixes_keep_well_conditioned_outputs_accurate_when_intermediates_are_huge() {
    // Idlers 1e9 times heavier than the links, spinning: the bias forces do not depend on
    // their mass (it sits on joint axes), and stay accurate (before: 1.1e-5).
    let heavy = measured("pulley_inertia_1e9");
    let bias = heavy.outputs.iter().find(|o| o.name == "bias").unwrap();
    assert!(
        bias.runtime_f64.max < 1e-13,
        "bias {:.2e}",
        bias.runtime_f64.max
    );
    // Drums 1000 times smaller than the idlers: the floors lift some tensions a million
    // times above the others. The tensions are as ill-conditioned as that makes them, but
    // the generalized forces and the base reaction do not depend on them (before: 2.3e-7).
    let tiny = measured("radius_ratio_1e-3");
    for name in ["delivered_forces", "base_reaction"] {
        let o = tiny.outputs.iter().find(|o| o.name == name).unwrap();
        assert!(
            o.runtime_f64.max < 1e-13,
            "{name} {:.2e}",
            o.runtime_f64.max
        );
        assert!(
            o.runtime_f32.max < 1e-5,
            "{name} f32 {:.2e}",
            o.runtime_f32.max
        );
    }
    assert!(tiny.null_spread > 1e5);
}

#[test]
fn passive_forward_dynamics_conserves_energy_to_the_order_of_rk4() {
    // A passive mechanism (no motor torque, no tendon tension) swinging under gravity for
    // 3 s. Energy from the Lagrangian reference (kinetic from body velocities, potential
    // from body heights), not from the solver. RK4's energy error scales as dt⁴: halving
    // the step must shrink it about sixteenfold, and at 1 ms it is within 1e-5 of the
    // largest kinetic energy (measured: 9e-7 and 4e-6).
    for (name, q0) in [
        ("tendon_chain_4", vec![0.4, -0.3, 0.5, 0.2]),
        ("example3_stanford_jpl", vec![0.3, 0.8, 0.5]),
    ] {
        let model = stress::case(name).model().unwrap();
        let qd0 = vec![0.0; model.dof()];
        let coarse = stress::energy_drift(&model, &q0, &qd0, 2e-3, 3.0).unwrap();
        let fine = stress::energy_drift(&model, &q0, &qd0, 1e-3, 3.0).unwrap();
        let scale = fine.max_kinetic;
        println!(
            "{name}: E0 {:.6e} J, max kinetic {:.3e} J, drift {:.2e} J at 2 ms, {:.2e} J at 1 ms",
            fine.initial, scale, coarse.max_drift, fine.max_drift
        );
        assert!(
            scale > 1e-3 * fine.initial.abs().max(1e-6),
            "{name}: it must move"
        );
        assert!(
            fine.max_drift <= 1e-5 * scale,
            "{name}: drift {:.2e} J of {scale:.2e} J",
            fine.max_drift
        );
        let order = (coarse.max_drift / fine.max_drift).log2();
        assert!(order > 3.5, "{name}: drift shrinks as dt^{order:.2}");
    }
}

#[test]
fn double_double_sin_cos_stay_accurate_at_1e4_rad_and_f64_sin_is_within_an_ulp() {
    // The reference's own reduction (five-word π/2) at large arguments: the double-angle
    // identity ties sin at 2x (reduced with a different k) to sin and cos at x, to 1e-30.
    let mut x = 0.7f64;
    for i in 0..400 {
        x = (x * 7919.0 + 0.123).rem_euclid(1e4) * if i % 2 == 0 { 1.0 } else { -1.0 };
        let d = DoubleDouble::from(x);
        let (s, c) = d.sin_cos();
        let s2 = (d * 2.0).sin();
        let defect = (s2 - s * c * 2.0).hi().abs();
        assert!(
            defect <= 1e-30,
            "sin(2x) − 2 sin x cos x = {defect:e} at {x}"
        );
        let pyth = (s * s + c * c - 1.0).hi().abs();
        assert!(pyth <= 1e-31, "sin² + cos² − 1 = {pyth:e} at {x}");
        // f64 (std) against the reference: within one ulp of the true value.
        let ulp = |v: f64| f64::EPSILON * v.abs().max(f64::MIN_POSITIVE);
        let (fs, fc) = x.sin_cos();
        assert!(
            (fs - s.hi()).abs() <= ulp(s.hi()),
            "f64 sin {x}: {fs} vs {s:?}"
        );
        assert!(
            (fc - c.hi()).abs() <= ulp(c.hi()),
            "f64 cos {x}: {fc} vs {c:?}"
        );
        // And Real's sin for f64 is std's.
        assert_eq!(Real::sin(x), fs);
    }
}

/// The measured figures of every case, for reading (`--ignored --nocapture`).
#[test]
#[ignore]
fn print_figures() {
    for (case, f) in figures() {
        match f {
            Err(e) => println!("{:34} rejected: {e}", case.name),
            Ok(f) => {
                println!(
                    "{:34} f64 {:.1e}/{:.1e} f32 {:.1e}/{:.1e} condA {:.1e} condE {:.1e} condM {:.1e}/{:.1e} spread {:.1e} angle {:.1e} well {} {:?}",
                    f.name,
                    f.runtime_f64.max,
                    f.runtime_f64.median,
                    f.runtime_f32.max,
                    f.runtime_f32.median,
                    f.cond_a.unwrap_or(f64::NAN),
                    f.cond_e,
                    f.cond_m.max,
                    f.cond_m_scaled.max,
                    f.null_spread,
                    f.max_angle,
                    f.well_conditioned(),
                    f.outcomes,
                );
                for o in &f.outputs {
                    let b = f.bound(o, U64);
                    println!(
                        "      {:20} f64 {:.1e}/{:.1e} f32 {:.1e} κ {:.1e} bound {:.1e} ratio {:.2}",
                        o.name,
                        o.runtime_f64.max,
                        o.runtime_f64.median,
                        o.runtime_f32.max,
                        o.kappa,
                        b,
                        o.runtime_f64.max / b
                    );
                }
            }
        }
    }
}
