//! Properties that hold whatever the mechanism: the double-double result is the f64 result
//! to f64 precision (and f32 to f32 precision), `M` is symmetric positive definite, and
//! forward dynamics undoes inverse dynamics. Errors are max-norm relative, `‖a − b‖∞ / ‖b‖∞`.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::output::Output;
use tendyn_core::{Data, DoubleDouble, InverseDynamics, Model, Numeric};
use tendyn_spec::measure::{max_rel as rel, random_state as state};
use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

fn examples() -> Vec<Model<f64>> {
    tendyn_spec::examples::all()
}

fn mechanisms() -> Vec<Model<f64>> {
    let mut all = examples();
    for seed in 100..106u64 {
        all.push(
            valid_random_mechanism(
                seed,
                Features {
                    coupled_pulleys: seed % 2 == 0,
                    endless: seed % 3 == 0,
                },
            )
            .1,
        );
    }
    all
}

/// Every number inverse dynamics reports, flattened, as f64: the generalized forces, every
/// unknown (loop sides included), the segment tensions and the bearings.
fn flatten<T: Numeric>(r: &InverseDynamics<T>) -> Vec<f64> {
    let flat = |o| r.flattened(o).unwrap_or_default();
    let parts = [
        flat(Output::GeneralizedForces),
        r.unknowns.clone(),
        flat(Output::SegmentTensions),
        flat(Output::Bearings),
    ];
    parts.concat().into_iter().map(|x| x.to_f64()).collect()
}

fn lift<T: Numeric>(v: &[f64]) -> Vec<T> {
    v.iter().map(|&x| T::from_f64(x)).collect()
}

#[test]
fn double_double_agrees_with_f64_to_f64_precision_and_f32_to_f32_precision() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for m in mechanisms() {
        let m_dd = m.cast_numeric::<DoubleDouble>();
        let m_32 = m.cast_numeric::<f32>();
        let (mut s64, mut sdd, mut s32) = (Data::new(&m), Data::new(&m_dd), Data::new(&m_32));
        let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
        for _ in 0..50 {
            let [q, qd, qdd] = state(&mut rng, m.dof());
            let reference = flatten(
                sdd.inverse_dynamics(&m_dd, &lift(&q), &lift(&qd), &lift(&qdd))
                    .unwrap(),
            );
            let r64 = flatten(s64.inverse_dynamics(&m, &q, &qd, &qdd).unwrap());
            let r32 = flatten(
                s32.inverse_dynamics(&m_32, &lift(&q), &lift(&qd), &lift(&qdd))
                    .unwrap(),
            );
            worst64 = worst64.max(rel(&r64, &reference));
            worst32 = worst32.max(rel(&r32, &reference));
        }
        println!(
            "{}: f64 {worst64:.2e}, f32 {worst32:.2e} (max-norm relative to double-double)",
            m.name()
        );
        assert!(
            worst64 < 1e-12,
            "{}: f64 is {worst64:.3e} from the double-double reference",
            m.name()
        );
        assert!(
            worst32 < 1e-4,
            "{}: f32 is {worst32:.3e} from the double-double reference",
            m.name()
        );
        assert!(
            worst64 > 0.0,
            "the reference must differ from f64 somewhere, else it is not more precise"
        );
    }
}

#[test]
fn mass_matrix_is_symmetric_positive_definite() {
    // `mass_matrix` fills one triangle and copies it, so its symmetry proves nothing. Each
    // column is computed on its own instead, by the recursion with tendons left out:
    // `M e_j = Q(q, 0, e_j) − Q(q, 0, 0)`; `M_ij` and `M_ji` then come from different runs.
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for m in mechanisms() {
        let mut s = Data::new(&m);
        for _ in 0..50 {
            let [q, _, _] = state(&mut rng, m.dof());
            let n = m.dof();
            let rest = vec![0.0; n];
            let q0 = s.generalized_forces(&m, &q, &rest, &rest).unwrap().to_vec();
            let columns: Vec<Vec<f64>> = (0..n)
                .map(|j| {
                    let mut e = rest.clone();
                    e[j] = 1.0;
                    let qj = s.generalized_forces(&m, &q, &rest, &e).unwrap();
                    qj.iter().zip(&q0).map(|(a, b)| a - b).collect()
                })
                .collect();
            let dm = nalgebra::DMatrix::from_fn(n, n, |i, j| columns[j][i]);
            // Each column is a difference of generalized forces that include gravity: its
            // round-off is relative to those, not to M.
            let size = q0.iter().fold(dm.amax(), |a, x| a.max(x.abs()));
            let asym = (&dm - dm.transpose()).amax() / size;
            assert!(asym < 1e-13, "{}: M is asymmetric by {asym:.2e}", m.name());
            let mm = s.mass_matrix(&m, &q).unwrap();
            let e_m = (0..n)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .fold(0.0f64, |e, (i, j)| e.max((mm[i][j] - dm[(i, j)]).abs()));
            assert!(
                e_m / size < 1e-13,
                "{}: mass_matrix differs by {e_m:.2e}",
                m.name()
            );
            let eig = dm.symmetric_eigen().eigenvalues;
            assert!(
                eig.min() > 0.0,
                "{}: M has eigenvalue {}",
                m.name(),
                eig.min()
            );
        }
    }
}

#[test]
fn forward_dynamics_undoes_inverse_dynamics() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    for m in mechanisms() {
        let mut s = Data::new(&m);
        let mut worst = 0.0f64;
        for _ in 0..50 {
            let [q, qd, qdd] = state(&mut rng, m.dof());
            let id = s.inverse_dynamics(&m, &q, &qd, &qdd).unwrap().clone();
            let back = s
                .forward_dynamics(&m, &q, &qd, &id.motor_torques, &id.tendon_tensions)
                .unwrap();
            worst = worst.max(rel(back, &qdd));
        }
        assert!(worst < 1e-10, "{}: round trip off by {worst:.3e}", m.name());
    }
}
