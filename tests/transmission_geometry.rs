//! The couplings and structure matrix derived from a routing agree with the tendon's
//! geometry. Each tendon is followed in the world frame (poses from the reference, not the
//! solver) while the joints move along a path: its straight segments must stay tangent to
//! their pitch circles with constant length, the arcs it wraps change, and from those arcs
//! alone (no coupling used) follow how far its ground end is pulled in (which must be
//! `A · Δq`), how far each idler's rim has moved (which must be `r · Δangle` of the derived
//! coupling), and that an endless loop keeps its length.

use nalgebra::{Matrix3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::model::{Contact, Model};
use tendyn_spec::poses::{angle, world_poses, Pose};

fn v(x: tendyn_core::spatial::Vec3<f64>) -> Vector3<f64> {
    Vector3::new(x.x, x.y, x.z)
}

/// World-frame data of one pulley body: centre, axis, and a mark fixed in its carrier
/// (the housing's x direction) and one fixed in the pulley itself.
struct Circle {
    centre: Vector3<f64>,
    axis: Vector3<f64>,
    housing_mark: Vector3<f64>,
    body_mark: Vector3<f64>,
}

fn circle(model: &Model<f64>, poses: &[Pose<f64>], q: &[f64], b: usize) -> Circle {
    let (r, o) = poses[b];
    let body = &model.bodies()[b];
    let phi = angle(body, q);
    let spin = Matrix3::new(
        phi.cos(),
        -phi.sin(),
        0.0,
        phi.sin(),
        phi.cos(),
        0.0,
        0.0,
        0.0,
        1.0,
    );
    // The frame of a spinning body turns with it; otherwise it is the housing frame.
    let (housing, material) = if body.spins {
        (r * spin.transpose(), r)
    } else {
        (r, r * spin)
    };
    Circle {
        centre: o,
        axis: r * Vector3::z(),
        housing_mark: housing * Vector3::x(),
        body_mark: material * Vector3::x(),
    }
}

/// Signed angle from `a` to `b` about `n`, in (−π, π].
fn turn_angle(a: Vector3<f64>, b: Vector3<f64>, n: Vector3<f64>) -> f64 {
    n.dot(&a.cross(&b)).atan2(a.dot(&b))
}

/// The arcs a strand wraps, as angles (radians, positive in the direction of travel), in
/// route order: start (from a mark on the start body to its outgoing contact), each idler
/// (incoming to outgoing contact), the end pulley if any (incoming contact to a mark on
/// it). Also, for each idler, the arc from its incoming contact to its housing mark.
struct Arcs {
    wraps: Vec<(f64, f64)>, // (radius, angle)
    to_housing: Vec<f64>,
}

fn arcs(model: &Model<f64>, q: &[f64], strand: usize) -> Arcs {
    let poses = world_poses::<f64>(model, q);
    let s = &model.strands()[strand];
    let frame_rot = |f: Option<usize>| f.map_or(Matrix3::identity(), |l| poses[l].0);
    let contact = |seg: &tendyn_core::model::Segment<f64>, c: &Contact<f64>| -> Vector3<f64> {
        let rl = frame_rot(seg.frame);
        match c.body {
            Some(b) => poses[b].1 + rl * v(c.rel),
            None => v(c.rel),
        }
    };
    let mut wraps = Vec::new();
    let mut to_housing = Vec::new();
    let radius = |b: usize| match model.bodies()[b].kind {
        tendyn_core::model::BodyKind::Pulley { radius, .. } => radius,
        _ => unreachable!(),
    };
    let travel = |c: &Circle, a: Vector3<f64>, b: Vector3<f64>, turn: f64| {
        turn * turn_angle(a - c.centre, b - c.centre, c.axis)
    };
    // Tangency, in the world frame: contacts on their circles, direction along the segment
    // and perpendicular to the radius and the axis.
    for seg in &s.segments {
        let (a, b) = (contact(seg, &seg.from), contact(seg, &seg.to));
        let d = frame_rot(seg.frame) * v(seg.dir);
        assert!(
            ((b - a).norm() - seg.length).abs() < 1e-12
                && (b - a).normalize().dot(&d) > 1.0 - 1e-12,
            "segment is not straight"
        );
        for (c, p) in [(&seg.from, a), (&seg.to, b)] {
            if let Some(body) = c.body {
                let ci = circle(model, &poses, q, body);
                let rad = p - ci.centre;
                assert!(
                    (rad.norm() - radius(body)).abs() < 1e-12,
                    "contact off the pitch circle"
                );
                assert!(
                    rad.dot(&d).abs() < 1e-12 && ci.axis.dot(&d).abs() < 1e-12,
                    "segment not tangent"
                );
            }
        }
    }
    // Start: from a mark on the start body to the first outgoing contact.
    let first = &s.segments[0];
    let start = first.from.body.unwrap();
    let c = circle(model, &poses, q, start);
    let start_turn = -travel(
        &c,
        c.centre + c.axis.cross(&(frame_rot(first.frame) * v(first.dir))),
        c.centre + c.body_mark,
        1.0,
    )
    .signum();
    let _ = start_turn;
    // The turn at the start is the sign of the moment the first segment exerts (Eq. 17).
    let t0 = c
        .axis
        .dot(
            &(contact(first, &first.from) - c.centre)
                .cross(&(frame_rot(first.frame) * v(first.dir))),
        )
        .signum();
    wraps.push((
        radius(start),
        travel(&c, c.centre + c.body_mark, contact(first, &first.from), t0),
    ));
    for (k, idler) in s.idlers.iter().enumerate() {
        let (inc, out) = (&s.segments[k], &s.segments[k + 1]);
        let c = circle(model, &poses, q, idler.body);
        let a = contact(inc, &inc.to);
        wraps.push((
            idler.radius,
            travel(&c, a, contact(out, &out.from), idler.turn),
        ));
        to_housing.push(travel(&c, a, c.centre + c.housing_mark, idler.turn));
    }
    let last = s.segments.last().unwrap();
    if let Some(e) = last.to.body {
        let c = circle(model, &poses, q, e);
        let d = frame_rot(last.frame) * v(last.dir);
        let te = -c
            .axis
            .dot(&(contact(last, &last.to) - c.centre).cross(&(-d)))
            .signum();
        wraps.push((
            radius(e),
            travel(&c, contact(last, &last.to), c.centre + c.body_mark, te),
        ));
    }
    Arcs { wraps, to_housing }
}

fn wrapped(d: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    d - tau * (d / tau).round()
}

fn check(model: &Model<f64>, seed: u64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = model.dof();
    let q0: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
    let q1: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
    let steps = 400;
    for (s, strand) in model.strands().iter().enumerate() {
        let mut prev = arcs(model, &q0, s);
        let mut pulled = 0.0; // length change of the whole strand
        let mut rim: Vec<f64> = vec![0.0; strand.idlers.len()];
        for k in 1..=steps {
            let t = k as f64 / steps as f64;
            let q: Vec<f64> = q0.iter().zip(&q1).map(|(a, b)| a + t * (b - a)).collect();
            let now = arcs(model, &q, s);
            let mut before = 0.0;
            for (i, ((r, a0), (_, a1))) in prev.wraps.iter().zip(&now.wraps).enumerate() {
                let dl = r * wrapped(a1 - a0);
                if i >= 1 && i <= strand.idlers.len() {
                    // Material passing the idler's housing mark moves its rim (no slip).
                    let j = i - 1;
                    let arc =
                        strand.idlers[j].radius * wrapped(now.to_housing[j] - prev.to_housing[j]);
                    rim[j] += -strand.idlers[j].turn * (before + arc);
                }
                before += dl;
            }
            pulled += before;
            prev = now;
        }
        let dq: Vec<f64> = q0.iter().zip(&q1).map(|(a, b)| b - a).collect();
        if let Some(t) = model.tendons().iter().find(|t| t.strand == Some(s)) {
            let want: f64 = t.structure.iter().zip(&dq).map(|(a, d)| a * d).sum();
            assert!(
                (-pulled - want).abs() < 1e-12,
                "{} {}: ground end pulled in by {} but A·Δq = {want}",
                model.name(),
                strand.name,
                -pulled
            );
        } else {
            assert!(
                pulled.abs() < 1e-12,
                "{} {}: an endless loop changed length by {pulled}",
                model.name(),
                strand.name
            );
        }
        for (j, idler) in strand.idlers.iter().enumerate() {
            let c = &model.bodies()[idler.body].coupling;
            let want: f64 = idler.radius * c.iter().zip(&dq).map(|(a, d)| a * d).sum::<f64>();
            assert!(
                (rim[j] - want).abs() < 1e-12,
                "{} {}: idler {} rim moved {} but its coupling gives {want}",
                model.name(),
                strand.name,
                model.bodies()[idler.body].name,
                rim[j]
            );
        }
    }
}

#[test]
fn tendon_geometry_moves_ground_ends_by_a_dq_and_idlers_by_their_couplings() {
    for m in tendyn_spec::examples::all() {
        for seed in 0..5 {
            check(&m, seed);
        }
    }
    for (seed, m) in tendyn_spec::measure::routed_random_mechanisms(8)
        .iter()
        .enumerate()
    {
        check(m, seed as u64);
    }
}
