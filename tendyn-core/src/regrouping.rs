//! Regrouping: the part of a body's mass that moves with its carrier whatever the body's
//! angle is moved onto the carrier (Khalil and Kleinfinger's grouping of inertial
//! parameters, 1987, for the turning bodies tendyn adds), so that the recursion walks
//! less for the same generalized forces.
//!
//! A pulley turns about its axis `z` (its body frame's, through its origin) relative to
//! its carrier. Part of its mass distribution is unchanged by that turn:
//!
//! - **a mass on the axis**: its position, and so its acceleration, does not depend on the
//!   angle;
//! - **an inertia `A (1 − z zᵀ)`**, axisymmetric with no moment about the axis: turning
//!   does not change it, and with `ω = ω_c + θ̇ z`, `ω̇ = ω̇_c + θ̈ z + θ̇ ω_c × z` (Eqs. 11-12)
//!   its moment `J ω̇ + ω × J ω` equals `J ω̇_c + ω_c × J ω_c`, the carrier's rigid part's:
//!   the difference is `θ̇ (J (ω_c × z) + z × J ω_c) = θ̇ A (ω_c × z + z × ω_c) = 0`
//!   (`J z = 0`, `ω_c × z ⟂ z`);
//! - **everything** of a fixed drum, which never turns relative to its carrier.
//!
//! Such a part exerts the same force and moment on the carrier whether the pulley or the
//! carrier holds it, and has no moment about the pulley's axis (`z · J ω̇ = 0`,
//! `z · (ω × J ω) = 0` for that `J`, `z · (h z × a) = 0` for a mass on the axis), so moved
//! onto the carrier it changes no body's torque about its own axis (but a fixed drum's,
//! which nothing reads: its coupling is zero and it has no balance row): not
//! `Q = Σ cᵀ τ`, `M`, `h`, `g`, the tension system's right-hand side (every idler's and
//! driving pulley's axial balance), the tensions, segment tensions or motor torques. It
//! changes the body's own bearing force, and, where the carrier is the base, the base
//! reaction (the part is dropped: the base does not move): the regrouped model is for
//! the former outputs only. A body that turns without spinning
//! ([`crate::model::Body::axisymmetric`]) carries nothing (validation and
//! [`Model::rigid_tree`] see to it), so no part ever spoils its axisymmetry.
//!
//! A link turns about its joint axis too, so the inertia part moves from a link as well,
//! where its axis is an axis `e_k` of its frame (a DH link without twist, or a twist of a
//! right angle): `A (1 − e_k e_kᵀ)` then zeroes one of its diagonal entries. A link's mass
//! is never moved (it could move only from the axis, which a link's centre of mass is
//! seldom on).
//!
//! The bodies are taken from the last to the first (pulleys, then links from the tip), so
//! what a pulley gives its link moves on with the link's own part where that goes further
//! (to the base, for the first link). The axis part moved has `A` the diagonal entry after
//! `k`'s (of the inertia about the centre of mass: `I_xx` about a pulley's `z`), which leaves an
//! axisymmetric pulley with its `zz` alone; a pulley's mass moves when its centre of mass
//! is on the axis exactly. An inertia part moves only where it fills no zero entry of the
//! carrier's mass, centre of mass or inertia (a new term in the carrier's equations can
//! cost more than the body saves), a part with mass always: it leaves the body no mass,
//! whose acceleration and force are then not needed. To the base, always. A body whose
//! mass properties a runtime parameter sets keeps them, and hands nothing to, or takes
//! nothing from, its neighbours.

use crate::composite::{congruence, point_shift};
use crate::model::{new_identity, parametric, patterns_of, Body, BodyKind, Model, PulleyRole};
use crate::spatial::{Mat3, Vec3};

impl Model<f64> {
    /// The model with every body's mass that moves with its carrier moved onto it (see
    /// [`crate::regrouping`]): the same torque about every body's axis at every state, so
    /// the same `Q`, `M`, `h`, `g`, forward dynamics and actuation, for less work; not the
    /// same bearing forces or base reaction. `None` where nothing moves.
    pub fn regrouped(&self) -> Option<Model<f64>> {
        let set_by_parameter = |i: usize| parametric(&self.parameter_slots, i);
        let mut m = self.clone();
        let mut moved = 0;
        for i in (0..m.bodies.len()).rev() {
            let pattern = &self.patterns[i];
            let body = &m.bodies[i];
            // The axis `e_k` of the body's frame its joint turns it about, if it is one.
            let along = body.axis.to_array();
            let Some(k) = (0..3).find(|&k| along[k].abs() == 1.0) else {
                continue;
            };
            if (0..3).any(|j| j != k && along[j] != 0.0) {
                continue;
            }
            if set_by_parameter(i) || body.parent.is_some_and(set_by_parameter) {
                continue;
            }
            // `A (1 − e_k e_kᵀ)` with `A` the diagonal entry after `k`'s, which it zeroes
            // (`xx` about a pulley's `z`).
            let a = body.inertia.rows[(k + 1) % 3][(k + 1) % 3];
            let axial: [[f64; 3]; 3] = core::array::from_fn(|r| {
                core::array::from_fn(|c| if r == c && r != k { a } else { 0.0 })
            });
            // A pulley's origin is on its axis (its frame is `pre` turned about `z`): its
            // mass moves too, where it is on the axis, and all of a fixed drum, which never
            // turns and whose own torque nothing reads (no coupling, no balance row: an idler
            // or driving pulley's is read even where its coupling is zero).
            let own =
                matches!(body.kind, BodyKind::Pulley { .. }) && pattern.origin_at_joint && k == 2;
            let fixed = matches!(
                body.kind,
                BodyKind::Pulley {
                    role: PulleyRole::Fixed,
                    ..
                }
            );
            let rigid = own && fixed && pattern.joints.is_empty() && body.offset == 0.0;
            let on_axis = own && body.com.x == 0.0 && body.com.y == 0.0;
            // What may move: everything of a body that does not turn; else its mass where it
            // is on the axis, and its inertia `A (1 − e_k e_kᵀ)`. A part with mass leaves
            // the body none, so its acceleration and force are no longer needed, which pays
            // for the terms the part may add to its carrier's equations (measured on the
            // benchmarks: never more operations); an inertia part alone saves a term or two,
            // and moves only where the carrier already has a number at every place it adds
            // one. To the base, always.
            let parts: &[(f64, [[f64; 3]; 3])] = if rigid {
                &[(body.mass, body.inertia.rows)]
            } else if on_axis {
                &[(body.mass, [[0.0; 3]; 3]), (0.0, axial)]
            } else {
                &[(0.0, axial)]
            };
            // In the carrier's frame: the body's frame is `pre · RotZ(θ) · post`. The turn
            // leaves a part axisymmetric about the axis as it is, and a point on the axis
            // where it is (the `post` of a pulley whose origin is on its joint keeps z on z:
            // a file's pulley has none, a rigid tree's may turn about z); a fixed drum's θ
            // is 0.
            let rotation = body.pre.rotation * body.post.rotation;
            let at = body.pre.apply(body.post.apply(body.com));
            for &(mass, inertia) in parts {
                if mass == 0.0 && inertia.iter().flatten().all(|&x| x == 0.0) {
                    continue;
                }
                let turned = congruence(&rotation, &Mat3 { rows: inertia }).rows;
                if let Some(parent) = m.bodies[i].parent {
                    let mut taken = m.bodies[parent].clone();
                    take_on(&mut taken, mass, at, turned);
                    if mass == 0.0 && fills(&m.bodies[parent], &taken) {
                        continue;
                    }
                    m.bodies[parent] = taken;
                }
                moved += 1;
                let body = &mut m.bodies[i];
                for (row, part) in body.inertia.rows.iter_mut().zip(&inertia) {
                    for (x, y) in row.iter_mut().zip(part) {
                        *x -= y;
                    }
                }
                if mass != 0.0 && mass == body.mass {
                    body.mass = 0.0;
                    body.com = Vec3::zero();
                }
            }
        }
        if moved == 0 {
            return None;
        }
        m.patterns = patterns_of(&m.bodies, &m.parameter_slots);
        m.identity = new_identity();
        Some(m)
    }
}

/// Whether `after` has a nonzero mass, centre of mass or inertia entry where `before` has
/// a zero.
fn fills(before: &Body<f64>, after: &Body<f64>) -> bool {
    let numbers = |b: &Body<f64>| {
        let mut v = vec![b.mass];
        v.extend(b.com.to_array());
        v.extend(b.inertia.rows.iter().flatten());
        v
    };
    numbers(before)
        .iter()
        .zip(numbers(after))
        .any(|(&x, y)| x == 0.0 && y != 0.0)
}

/// Adds to `body` a part of mass `mass` centred at `at` with inertia `inertia` about `at`
/// (its frame, its axes): mass, centre of mass and inertia about the new centre combined
/// by the parallel-axis theorem.
fn take_on(body: &mut Body<f64>, mass: f64, at: Vec3<f64>, inertia: [[f64; 3]; 3]) {
    let total = body.mass + mass;
    let com = if mass != 0.0 && total > 0.0 {
        (body.com.scale(body.mass) + at.scale(mass)).scale(1.0 / total)
    } else {
        body.com
    };
    // `point_shift(d, m, 0)` is `m (|d|² 1 − d dᵀ)`: a point mass `m` at `d`.
    let own = point_shift(body.com - com, body.mass, Vec3::zero()).rows;
    let part = point_shift(at - com, mass, Vec3::zero()).rows;
    for r in 0..3 {
        for c in 0..3 {
            body.inertia.rows[r][c] += own[r][c] + inertia[r][c] + part[r][c];
        }
    }
    body.mass = total;
    body.com = com;
}
