//! The recursion agrees with derivations that share none of its code: Lagrange's
//! equations (mass matrix from the kinetic energy, bias and gravity from the Lagrangian),
//! the power balance, and the momentum balance of the whole mechanism for the base
//! reaction. Agreement is measured as max-norm relative error,
//! `‖a − b‖∞ / ‖b‖∞`, and must be 1e-12 or better in f64.

use nalgebra::{DMatrix, DVector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::affine::MAX_UNKNOWNS;
use tendyn_core::model::{BodyKind, Model, Row};
use tendyn_core::Data;
use tendyn_spec::measure::{max_rel as rel, random_state, routed_random_mechanisms};
use tendyn_spec::{lagrangian, momentum};

const TOL: f64 = 1e-12;

fn examples() -> Vec<Model<f64>> {
    tendyn_spec::examples::all()
}

fn flat(m: &DMatrix<f64>) -> Vec<f64> {
    m.iter().copied().collect()
}

/// Checks every quantity of one mechanism at `states` random states; returns the worst error.
fn check_mechanism(model: &Model<f64>, states: usize, seed: u64) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut solver = Data::new(model);
    let mut worst = 0.0f64;
    let n = model.dof();
    for _ in 0..states {
        let [q, qd, qdd] = random_state(&mut rng, n);
        let m = solver.mass_matrix(model, &q).unwrap();
        let m_flat: Vec<f64> = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| m[i][j])
            .collect();
        let e_m = rel(&m_flat, &flat(&lagrangian::mass_matrix(model, &q)));
        let e_h = rel(
            solver.bias(model, &q, &qd).unwrap(),
            lagrangian::bias(model, &q, &qd).as_slice(),
        );
        let e_g = rel(
            solver.gravity(model, &q).unwrap(),
            lagrangian::gravity_forces(model, &q).as_slice(),
        );
        let q_total = lagrangian::lagrange_generalized_forces(model, &q, &qd, &qdd);
        let q_act: DVector<f64> = &q_total - lagrangian::external_generalized_forces(model, &q);
        let id = solver
            .inverse_dynamics(model, &q, &qd, &qdd)
            .unwrap()
            .clone();
        // (Affine rows carry a bounded number of unknowns; beyond it the power balance
        // below still checks the tensions against the transmission.)
        let rows = if model.system().unknowns.len() <= MAX_UNKNOWNS {
            solver.balance_rows(model, &q, &qd, &qdd).unwrap()
        } else {
            Vec::new()
        };
        let e_q = rel(&id.generalized_forces, q_act.as_slice());
        let e_q2 = rel(
            solver.generalized_forces(model, &q, &qd, &qdd).unwrap(),
            q_act.as_slice(),
        );
        for (what, e) in [
            ("M", e_m),
            ("h", e_h),
            ("g", e_g),
            ("Q from tensions", e_q),
            ("Q expanded", e_q2),
        ] {
            assert!(
                e <= TOL,
                "{}: {what} differs from the Lagrangian by {e:.3e} at q={q:?}",
                model.name()
            );
            worst = worst.max(e);
        }
        // Power balance: what the actuators and the environment put in is what the
        // mechanism's energy gains. Actuator power comes from the solved tensions and
        // torques and the transmission's rates, not from Q.
        let power: f64 =
            lagrangian::power_in(model, &q, &qd, &id.tendon_tensions, &id.motor_torques)
                .iter()
                .sum();
        let de = lagrangian::energy_rate(model, &q, &qd, &qdd);
        let scale = de.abs().max(
            q_total
                .iter()
                .zip(&qd)
                .map(|(a, v)| (a * v).abs())
                .sum::<f64>(),
        );
        let e_p = (power - de).abs() / scale;
        assert!(
            e_p <= TOL,
            "{}: power balance off by {e_p:.3e}",
            model.name()
        );
        worst = worst.max(e_p);
        // Base reaction against the momentum balance.
        if let Some((f, mo)) = id.base_reaction {
            let (rf, rm) = momentum::base_reaction(model, &q, &qd, &qdd);
            let e_f = rel(&[f.x, f.y, f.z], rf.as_slice());
            let e_mo = rel(&[mo.x, mo.y, mo.z], rm.as_slice());
            assert!(
                e_f <= TOL && e_mo <= TOL,
                "{}: base reaction off by {e_f:.3e} / {e_mo:.3e}",
                model.name()
            );
            worst = worst.max(e_f).max(e_mo);
        }
        // The recursion's balance rows carry −E on the strand tensions: the transmission's
        // virtual-work derivation and the recursion's force moments agree.
        for (r, row) in rows.iter().enumerate() {
            if matches!(model.system().rows[r], Row::Pretension(_)) {
                continue;
            }
            for s in 0..model.strands().len() {
                let k = model.strands()[s].unknown;
                let got = -row.coefficients[k];
                let want = model.system().matrix[r][k];
                assert!(
                    (got - want).abs() <= 1e-13,
                    "{}: E[{r}][{k}] is {want} but the recursion gives {got}",
                    model.name()
                );
            }
        }
    }
    worst
}

#[test]
fn paper_examples_agree_with_lagrange_power_and_momentum() {
    for (i, m) in examples().iter().enumerate() {
        let worst = check_mechanism(m, 200, 7 + i as u64);
        println!("{}: worst relative error {worst:.2e}", m.name());
    }
}

#[test]
fn random_spatial_mechanisms_agree_with_lagrange_power_and_momentum() {
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
    let mut shown = 0;
    for seed in 0..16u64 {
        let features = Features {
            coupled_pulleys: seed % 2 == 1,
            endless: seed % 4 == 2,
        };
        let (_, m) = valid_random_mechanism(seed, features);
        let worst = check_mechanism(&m, 50, seed);
        if shown < 16 {
            println!(
                "{} ({} links, {} pulleys, {} tendons): worst relative error {worst:.2e}",
                m.name(),
                m.dof(),
                m.bodies().len() - m.dof(),
                m.tendons().len()
            );
            shown += 1;
        }
    }
}

/// The mechanisms of the scale benchmarks (`bench/mechanisms`): a planar finger, a random
/// spatial arm with tilted gears, chains of 8 and 12 links with 20 and 30 pulleys (13
/// unknowns in the last), and the generation benchmark's 7-link chain.
fn benchmark_mechanisms() -> Vec<Model<f64>> {
    [
        "bench/mechanisms/finger4",
        "bench/mechanisms/arm6",
        "bench/mechanisms/chain8",
        "bench/mechanisms/chain12",
        "tendyn-codegen/benches/chain7",
    ]
    .iter()
    .map(|path| tendyn_core::load(format!("../{path}.ron")).unwrap())
    .collect()
}

#[test]
fn benchmark_mechanisms_agree_with_lagrange_power_and_momentum() {
    for (i, m) in benchmark_mechanisms().iter().enumerate() {
        let worst = check_mechanism(m, 40, 90 + i as u64);
        println!(
            "{} ({} unknowns): worst relative error {worst:.2e}",
            m.name(),
            m.system().unknowns.len()
        );
        if !m.routing_incomplete() {
            let worst = check_bearings(m, 20, 95 + i as u64);
            println!("{} bearings: worst {worst:.2e}", m.name());
        }
    }
}

/// Every body's bearing force and moment is what the momentum balance of the subtree it
/// carries requires, given the tendon forces that cross into that subtree (tensions from
/// the solver, geometry from the model, poses and momenta from the reference).
fn check_bearings(model: &Model<f64>, states: usize, seed: u64) -> f64 {
    use nalgebra::{Matrix3, Vector3};
    use tendyn_core::model::MotorKind;
    use tendyn_spec::poses::world_poses;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut solver = Data::new(model);
    let v = |x: tendyn_core::spatial::Vec3<f64>| Vector3::new(x.x, x.y, x.z);
    let mut worst = 0.0f64;
    for _ in 0..states {
        let [q, qd, qdd] = random_state(&mut rng, model.dof());
        let id = solver
            .inverse_dynamics(model, &q, &qd, &qdd)
            .unwrap()
            .clone();
        let (Some(bearings), Some(segments)) = (&id.bearings, &id.segment_tensions) else {
            return worst;
        };
        let poses = world_poses::<f64>(model, &q);
        let frame_rot = |f: Option<usize>| f.map_or(Matrix3::identity(), |l| poses[l].0);
        for root in 0..model.bodies().len() {
            let mut inside = vec![false; model.bodies().len()];
            for (b, body) in model.bodies().iter().enumerate() {
                inside[b] = b == root || body.parent.is_some_and(|p| inside[p]);
            }
            let (mut f_need, mut m_need) = momentum::subtree_reaction(model, &q, &qd, &qdd, root);
            for (strand, tensions) in model.strands().iter().zip(segments) {
                for (seg, t) in strand.segments.iter().zip(tensions) {
                    let rl = frame_rot(seg.frame);
                    let dir = rl * v(seg.dir) * *t;
                    let point = |c: &tendyn_core::model::Contact<f64>| match c.body {
                        Some(b) => poses[b].1 + rl * v(c.rel),
                        None => v(c.rel),
                    };
                    let is_in =
                        |c: &tendyn_core::model::Contact<f64>| c.body.is_some_and(|b| inside[b]);
                    if is_in(&seg.from) && !is_in(&seg.to) {
                        f_need -= dir;
                        m_need -= point(&seg.from).cross(&dir);
                    }
                    if is_in(&seg.to) && !is_in(&seg.from) {
                        f_need += dir;
                        m_need += point(&seg.to).cross(&dir);
                    }
                }
            }
            let body = &model.bodies()[root];
            let (r, origin) = poses[root];
            // A spinning pulley's bearing is reported in its housing frame, the pulley
            // frame at zero spin: `R RotZ(θ)ᵀ` (a pulley's `post` is the identity).
            let r = if body.spins && matches!(body.kind, BodyKind::Pulley { .. }) {
                let angle: f64 = body.coupling.iter().zip(&q).map(|(c, x)| c * x).sum();
                let (s, c) = angle.sin_cos();
                r * Matrix3::new(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0)
            } else {
                r
            };
            let (f, mut n) = bearings[root];
            if let Some(mo) = model
                .motors()
                .iter()
                .find(|mo| mo.kind == MotorKind::Joint(root) || mo.kind == MotorKind::Pulley(root))
            {
                n = n + body.axis.scale(id.unknowns[mo.unknown]);
            }
            let joint_point = origin - r * v(body.joint_to_origin);
            let f_w = r * v(f);
            let m_w = r * v(n) + joint_point.cross(&f_w);
            let scale = f_need.amax().max(1e-300);
            let e = (f_w - f_need).amax() / scale;
            let e_m = (m_w - m_need).amax() / m_need.amax().max(1e-300);
            assert!(
                e <= TOL && e_m <= TOL,
                "{}: bearing of {} off by {e:.3e} (force) / {e_m:.3e} (moment)",
                model.name(),
                body.name
            );
            worst = worst.max(e).max(e_m);
        }
    }
    worst
}

#[test]
fn bearing_forces_balance_the_momentum_of_each_subtree() {
    for (i, m) in examples().iter().enumerate() {
        let worst = check_bearings(m, 100, 40 + i as u64);
        println!("{}: worst {worst:.2e}", m.name());
    }
    for (seed, m) in routed_random_mechanisms(8).iter().enumerate() {
        let worst = check_bearings(m, 20, seed as u64);
        println!("{}: worst {worst:.2e}", m.name());
    }
}

#[test]
fn frictionless_guides_agree_with_lagrange_power_and_momentum() {
    // Example 2 with its two idlers fixed, and twelve random routed mechanisms likewise: a
    // guide has no dynamics of its own, and the recursion's forces at its tangent points
    // must give the structure matrix the sliding kinematics give.
    let example =
        std::fs::read_to_string("../examples/mechanisms/example2_open_ended.ron").unwrap();
    let mut texts = vec![tendyn_spec::guides::idlers_as_guides(&example)];
    for seed in 0..12u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: false,
        };
        let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        texts.push(tendyn_spec::guides::idlers_as_guides(&text));
    }
    let mut guides = 0;
    for (i, text) in texts.iter().enumerate() {
        let model = tendyn_core::parse(text).unwrap();
        let here = model
            .strands()
            .iter()
            .flat_map(|s| &s.idlers)
            .filter(|i| i.guide.is_some())
            .count();
        let idlers = model.strands().iter().flat_map(|s| &s.idlers).count();
        assert_eq!(here, idlers, "{}: every idler is a guide", model.name());
        guides += here;
        let worst = check_mechanism(&model, 100, 40 + i as u64);
        println!(
            "{} with guides: worst relative error {worst:.2e}",
            model.name()
        );
    }
    // (Two in Example 2, six in the random mechanisms.)
    assert!(guides >= 8, "only {guides} guides");
}
