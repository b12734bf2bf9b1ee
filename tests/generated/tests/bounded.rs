//! Generated `actuation` of the seeded random bounded-distribution systems
//! (`tendyn_spec::bounded::SIZES`: null spaces of one to four dimensions, floors and maxima
//! per tendon) and of Example 2 with capstan friction, an antagonist and maxima (two null
//! directions that depend on the state) agrees with the runtime solver at 2,000 random
//! states each, in f64 and f32:
//! `Status::Feasible` exactly where the runtime returns tensions (f64), `MaxExceeded`
//! where it reports that the bounds cannot be met, and the tensions within 1e-12 (f64) and
//! 1e-4 (f32, whose whole recursion runs in f32) of the runtime's, max norm relative. In
//! the best effort the floors still hold.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::distribution::Status;
use tendyn_core::{Data, Error};
use tendyn_generated_tests::BOUNDED;

/// A random state of `n` joints in f32 (q in ±π, q̇ in ±2, q̈ in ±6) and the same in f64,
/// so that both scalars see exactly the same inputs.
fn random_state(rng: &mut ChaCha8Rng, n: usize) -> ([Vec<f32>; 3], [Vec<f64>; 3]) {
    let narrow = [std::f64::consts::PI, 2.0, 6.0].map(|s| {
        (0..n)
            .map(|_| rng.random_range(-s..s) as f32)
            .collect::<Vec<f32>>()
    });
    let wide = narrow
        .clone()
        .map(|x| x.iter().map(|&v| v as f64).collect());
    (narrow, wide)
}

#[test]
fn generated_actuation_agrees_with_the_runtime_on_status_and_tensions() {
    for mech in BOUNDED {
        let model = tendyn_core::parse(mech.ron).unwrap();
        let m32 = model.cast_numeric::<f32>();
        let (mut s64, mut s32) = (Data::new(&model), Data::new(&m32));
        let n = model.dof();
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let (mut feasible, mut exceeded, mut worst64, mut worst32, mut disagree32) =
            (0, 0, 0.0f64, 0.0f64, 0);
        for _ in 0..2000 {
            let ([q, qd, qdd], [q64, qd64, qdd64]) = random_state(&mut rng, n);
            let (t64, status64) = (mech.actuation_f64)(&q64, &qd64, &qdd64);
            let (t32, status32) = (mech.actuation_f32)(&q, &qd, &qdd);
            for (t, f) in t64.iter().zip(model.tendons()) {
                assert!(
                    *t >= f.floor * (1.0 - 1e-12) - 1e-9,
                    "{}: below a floor",
                    mech.name
                );
            }
            match s64.inverse_dynamics(&model, &q64, &qd64, &qdd64) {
                Ok(r) => {
                    feasible += 1;
                    assert_eq!(status64, Status::Feasible, "{} at q={q:?}", mech.name);
                    let scale = r.tendon_tensions.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                    let err = |got: &[f64]| {
                        got.iter()
                            .zip(&r.tendon_tensions)
                            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                            / scale
                    };
                    let e64 = err(&t64);
                    assert!(
                        e64 <= 1e-12,
                        "{}: f64 {t64:?} vs {:?}",
                        mech.name,
                        r.tendon_tensions
                    );
                    worst64 = worst64.max(e64);
                    if status32 == Status::Feasible {
                        let e32 = err(&t32.iter().map(|&x| x as f64).collect::<Vec<_>>());
                        assert!(
                            e32 <= 1e-4,
                            "{}: f32 {t32:?} vs {:?}",
                            mech.name,
                            r.tendon_tensions
                        );
                        worst32 = worst32.max(e32);
                    } else {
                        disagree32 += 1;
                    }
                }
                Err(Error::Tension(_)) => {
                    exceeded += 1;
                    assert_eq!(status64, Status::MaxExceeded, "{} at q={q:?}", mech.name);
                    disagree32 += usize::from(status32 != Status::MaxExceeded);
                }
                Err(e) => panic!("{}: {e}", mech.name),
            }
            // The runtime in f32 decides as generated f32 does, within its round-off of
            // the boundary.
            let runtime32 = s32.inverse_dynamics(&m32, &q, &qd, &qdd).is_ok();
            disagree32 += usize::from(runtime32 != (status32 == Status::Feasible));
        }
        println!(
            "{}: {feasible} feasible, {exceeded} MaxExceeded; worst f64 {worst64:.1e}, f32 \
             {worst32:.1e}; f32 on the other side of the boundary at {disagree32} checks",
            mech.name
        );
        assert!(
            feasible > 100 && exceeded > 20,
            "{}: {feasible}/{exceeded}",
            mech.name
        );
        assert!(disagree32 <= 20, "{}: {disagree32}", mech.name);
    }
}

/// Generated `actuation_derivatives` over one to four null directions (the minimal-norm
/// tensions' derivatives traced, the optimum differentiated on its active set by
/// `Actuation::bounded_with_tangents`) against the runtime's (`Data::actuation_derivatives`,
/// dual numbers through the whole solve), at 300 random states each:
/// - where the bounds can be met, the value and each Jacobian within 1e-12 of the
///   runtime's in f64, each measured on its own in the max norm; in f32 (the whole trace
///   and the distribution in f32) against the f64 runtime, at states where every tendon is
///   either at a bound or clearly away from both (the active set then cannot change
///   within f32's round-off), within `256 u₃₂` of each block's size;
/// - where they cannot (the runtime refuses; generated code returns the best effort, the
///   floors' optimum, and its derivatives), against central differences of generated
///   `actuation` (steps of 1e-6, f64) away from a change of active set: beyond the
///   differences' round-off, within 1e-6 of each Jacobian's size.
#[test]
fn generated_actuation_derivatives_agree_with_the_runtime_over_any_null_space() {
    let tolerance32 = 256.0 * f32::EPSILON as f64;
    for mech in BOUNDED {
        let model = tendyn_core::parse(mech.ron).unwrap();
        let (n, k) = (model.dof(), model.tendons().len());
        assert!(
            model.motors().is_empty(),
            "the value and rows are the tendons'"
        );
        let mut data = Data::new(&model);
        let mut rng = ChaCha8Rng::seed_from_u64(47);
        let (mut checked, mut checked32, mut worst64, mut worst32) = (0, 0, 0.0f64, 0.0f64);
        let (mut best_efforts, mut worst_best) = (0, 0.0f64);
        for _ in 0..300 {
            let ([q, qd, qdd], [q64, qd64, qdd64]) = random_state(&mut rng, n);
            let Ok(d) = data.actuation_derivatives(&model, &q64, &qd64, &qdd64) else {
                // Beyond the maxima: no derivative at run time.
                if let Some(e) = best_effort_error(mech, [&q64, &qd64, &qdd64], k) {
                    assert!(e <= 1e-6, "{} best effort at q={q:?}: {e:e}", mech.name);
                    worst_best = worst_best.max(e);
                    best_efforts += 1;
                }
                continue;
            };
            let want: Vec<f64> = (d.value.iter())
                .chain(&d.d_q)
                .chain(&d.d_qd)
                .chain(&d.d_qdd)
                .copied()
                .collect();
            let blocks = [k, k * n, k * n, k * n];
            let distance = |got: &[f64]| {
                let mut at = 0;
                blocks.map(|len| {
                    let (got, want) = (&got[at..at + len], &want[at..at + len]);
                    at += len;
                    let scale = want.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
                    let e = got
                        .iter()
                        .zip(want)
                        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                    e / scale
                })
            };
            let e64 = distance(&(mech.actuation_derivatives_f64)(&q64, &qd64, &qdd64));
            for e in e64 {
                assert!(e <= 1e-12, "{} at q={q:?}: {e64:?}", mech.name);
                worst64 = worst64.max(e);
            }
            checked += 1;
            // Each tendon at a bound or clearly away from both, relative to the tensions.
            let size = d.value.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let clear = d.value.iter().zip(model.tendons()).all(|(t, tendon)| {
                let max = tendon.max_tension.unwrap_or(f64::INFINITY);
                let gap = (t - tendon.floor).abs().min((max - t).abs()) / size;
                gap <= 1e-12 || gap >= 1e-3
            });
            if clear {
                let got = (mech.actuation_derivatives_f32)(&q, &qd, &qdd);
                let e32 = distance(&got.iter().map(|&x| x as f64).collect::<Vec<f64>>());
                for e in e32 {
                    assert!(e <= tolerance32, "{} f32 at q={q:?}: {e32:?}", mech.name);
                    worst32 = worst32.max(e);
                }
                checked32 += 1;
            }
        }
        println!(
            "{}: derivatives at {checked} states, worst f64 {worst64:.1e}; f32 at {checked32}, \
             worst {worst32:.1e}; best efforts at {best_efforts}, worst {worst_best:.1e}",
            mech.name
        );
        assert!(checked >= 100 && checked32 >= 50, "{}", mech.name);
        assert!(best_efforts >= 20, "{}: {best_efforts}", mech.name);
    }
}

/// Generated `actuation_derivatives` at a state the bounds cannot meet against central
/// differences of generated `actuation` (f64): the worst difference beyond the differences'
/// own round-off over the three Jacobians, each relative to its own max norm, or `None`
/// where a step changes the status or the active set (the one-sided differences part).
fn best_effort_error(
    mech: &tendyn_generated_tests::Bounded,
    x: [&[f64]; 3],
    k: usize,
) -> Option<f64> {
    let n = x[0].len();
    let got = (mech.actuation_derivatives_f64)(x[0], x[1], x[2]);
    let (at, status) = (mech.actuation_f64)(x[0], x[1], x[2]);
    assert_eq!(status, Status::MaxExceeded, "{}", mech.name);
    let h = 1e-6;
    let roundoff = 16.0 * f64::EPSILON * at.iter().fold(0.0f64, |m, t| m.max(t.abs())) / h;
    let mut worst = 0.0f64;
    for (block, input) in x.iter().enumerate() {
        let (mut size, mut error) = (1e-300f64, 0.0f64);
        for c in 0..n {
            let moved = |by: f64| {
                let mut y = [x[0].to_vec(), x[1].to_vec(), x[2].to_vec()];
                y[block][c] = input[c] + by;
                (mech.actuation_f64)(&y[0], &y[1], &y[2])
            };
            let ((up, s_up), (down, s_down)) = (moved(h), moved(-h));
            if s_up != status || s_down != status {
                return None;
            }
            for r in 0..k {
                let (forward, backward) = ((up[r] - at[r]) / h, (at[r] - down[r]) / h);
                if (forward - backward).abs() > 1e-3 * (forward.abs() + backward.abs() + 1.0) {
                    return None;
                }
                let derivative = got[k + block * k * n + r * n + c];
                size = size.max(derivative.abs());
                // Less the differences' own round-off, `16 u max|T| / h`.
                let central = (0.5 * (forward + backward) - derivative).abs();
                error = error.max(central - roundoff).max(0.0);
            }
        }
        worst = worst.max(error / size);
    }
    Some(worst)
}

/// `all` runs the distribution once for both outputs (the tangents' routine returns the
/// value's `Actuation`): its `Actuation` is, bit for bit, what `actuation` returns on its
/// own, best efforts included; its derivatives are `actuation_derivatives`' to round-off.
/// (Not bit for bit: `all` is the cheaper of every function in its own form and every
/// function traced, and `bounded_1x3`'s derivatives are emitted in closed form while its
/// `all` is traced.)
#[test]
fn all_gives_what_actuation_and_its_derivatives_give() {
    let mut exceeded = 0;
    for mech in BOUNDED {
        let n = tendyn_core::parse(mech.ron).unwrap().dof();
        let mut rng = ChaCha8Rng::seed_from_u64(37);
        for _ in 0..300 {
            let (_, [q, qd, qdd]) = random_state(&mut rng, n);
            let (tensions, status, derivatives) = (mech.all_f64)(&q, &qd, &qdd);
            let alone = (mech.actuation_f64)(&q, &qd, &qdd);
            assert_eq!((&tensions, status), (&alone.0, alone.1), "{}", mech.name);
            let alone = (mech.actuation_derivatives_f64)(&q, &qd, &qdd);
            assert_eq!(derivatives.len(), alone.len(), "{}", mech.name);
            assert!(
                derivatives.iter().chain(&alone).all(|x| x.is_finite()),
                "{}",
                mech.name
            );
            // Two roundings of the same expressions, through the same active set: entry by
            // entry, against the largest of its block (the values, then the Jacobian along
            // q, q̇ and q̈: quantities of different units).
            let k = tensions.len();
            let blocks = std::iter::once(0..k)
                .chain((0..3).map(|b| k + b * k * n..k + (b + 1) * k * n))
                .collect::<Vec<_>>();
            assert_eq!(blocks[3].end, alone.len(), "{}", mech.name);
            for block in blocks {
                let size = alone[block.clone()]
                    .iter()
                    .fold(1e-300f64, |m, x| m.max(x.abs()));
                for i in block {
                    let (a, b) = (derivatives[i], alone[i]);
                    assert!(
                        (a - b).abs() <= 64.0 * f64::EPSILON * size,
                        "{}: entry {i}, {a:e} against {b:e} (block's largest {size:e})",
                        mech.name
                    );
                }
            }
            exceeded += usize::from(status == Status::MaxExceeded);
        }
    }
    assert!(exceeded > 100, "{exceeded} best efforts");
}
