//! Generated `actuation` of the seeded random bounded-distribution systems
//! (`tendyn_spec::bounded::SIZES`: null spaces of one to four dimensions, floors and maxima
//! per tendon) agrees with the runtime solver at 2,000 random states each, in f64 and f32:
//! `Status::Feasible` exactly where the runtime returns tensions (f64), `MaxExceeded`
//! where it reports that the bounds cannot be met, and the tensions within 1e-12 (f64) and
//! 1e-4 (f32, whose whole recursion runs in f32) of the runtime's, max norm relative. In
//! the best effort the floors still hold.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::distribution::Status;
use tendyn_core::{Data, Error};
use tendyn_generated_tests::BOUNDED;

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
            let mut v = |s: f64| {
                (0..n)
                    .map(|_| rng.random_range(-s..s) as f32)
                    .collect::<Vec<f32>>()
            };
            let (q, qd, qdd) = (v(std::f64::consts::PI), v(2.0), v(6.0));
            let wide = |x: &[f32]| x.iter().map(|&v| v as f64).collect::<Vec<f64>>();
            let (q64, qd64, qdd64) = (wide(&q), wide(&qd), wide(&qdd));
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
