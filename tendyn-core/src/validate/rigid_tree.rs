//! A model built in code rather than read from a file: a tree of rigid bodies without
//! tendons or motors ([`Model::rigid_tree`]), checked for what the recursion relies on.
//! Invariant: a model it returns satisfies the body invariants of a validated file's.

use super::ranges::{beyond, Range, MIN_RADIUS};
use super::{check_gravity_and_wrench, check_mass_properties};
use crate::error::{Error, Location, Result};
use crate::model::{Body, BodyKind, Model, PulleyRole, TensionSystem, Wrench};
use crate::spatial::{Transform, Vec3};

/// How far a body's derived numbers (`axis`, `joint_to_origin`, an orthonormal rotation, an
/// axisymmetric inertia) may be from exact, relative to their size: a few hundred rounding
/// errors of the products that derive them.
const DERIVED: f64 = 1e-12;

impl Model<f64> {
    /// A tree of rigid bodies with no tendons, motors or loops, built in code: for the mass
    /// matrix, bias and gravity of a linkage (and forward dynamics under gravity alone), and
    /// for checks whose reference needs only the bodies.
    ///
    /// Bodies as [`Body`] documents them: at least one joint; the `dof` links first, link
    /// `j` of kind `Link { joint: j }` with coupling `e_j`, then intermediate links (pulleys,
    /// `Fixed` or `Coupled`: an idler or a driving pulley needs a routing) carried by the
    /// base or a link; parents before children; names unique and not empty;
    /// `axis = postᵀ z` and `joint_to_origin = postᵀ t` as validation derives them; a
    /// symmetric inertia; a body that turns without spinning axisymmetric about its axis and
    /// carrying no other body (its frame does not turn, so what it carried would not).
    /// Every violation, and every number not finite or beyond the file format's ranges, is
    /// an [`Error::Invalid`] naming the body.
    pub fn rigid_tree(
        name: &str,
        gravity: [f64; 3],
        dof: usize,
        bodies: Vec<Body<f64>>,
        external_wrench: Option<Wrench<f64>>,
    ) -> Result<Model<f64>> {
        let invalid = |item: &str, problem: String| Error::Invalid {
            item: item.to_string(),
            at: Location::default(),
            problem,
        };
        if dof > super::ranges::MAX_LINKS {
            return Err(invalid(
                name,
                format!(
                    "{dof} joints: at most {} are supported (a position sums every link's \
                     length, whose square must stay far from the scalar's range)",
                    super::ranges::MAX_LINKS
                ),
            ));
        }
        if dof == 0 || bodies.len() < dof {
            return Err(invalid(
                name,
                format!(
                    "{dof} joints and {} bodies: a tree needs at least one joint and a link \
                     for each",
                    bodies.len()
                ),
            ));
        }
        for (index, body) in bodies.iter().enumerate() {
            let named_before = bodies[..index].iter().any(|b| b.name == body.name);
            if body.name.is_empty() || named_before {
                return Err(invalid(
                    &body.name,
                    format!("body {index} needs a name of its own"),
                ));
            }
            check_body(index, body, dof).map_err(|p| invalid(&body.name, p))?;
            check_mass_properties(&body.name, body.mass, body.com, &body.inertia)?;
            // Children are placed in their parent's frame, which for a body turning without
            // spinning stays the housing frame (Eq. 16 without the spin): they would not
            // turn with it.
            if let Some(parent) = body.parent.map(|p| &bodies[p]).filter(|p| p.axisymmetric()) {
                return Err(invalid(
                    &parent.name,
                    format!(
                        "it turns without spinning (`spins: false`) and carries `{}`, which \
                         would not turn with it: let it spin",
                        body.name
                    ),
                ));
            }
        }
        check_gravity_and_wrench(name, Vec3::from_array(gravity), external_wrench.as_ref())?;
        if let Some(w) = external_wrench.as_ref().filter(|w| w.link >= dof) {
            return Err(invalid(
                name,
                format!("the external wrench acts on link {} of {dof}", w.link),
            ));
        }
        let patterns = crate::model::patterns_of(&bodies, &[]);
        Ok(Model {
            name: name.to_string(),
            gravity: Vec3::from_array(gravity),
            parameters: Vec::new(),
            parameter_slots: Vec::new(),
            dof,
            bodies,
            strands: Vec::new(),
            tendons: Vec::new(),
            loops: Vec::new(),
            motors: Vec::new(),
            system: TensionSystem {
                unknowns: Vec::new(),
                rows: Vec::new(),
                matrix: Vec::new(),
                pseudo_inverse: Vec::new(),
                null_space: Vec::new(),
                positive_null: None,
                condition: 1.0,
                eliminated: None,
            },
            objective: Default::default(),
            friction_smoothing: None,
            joint_ranges: vec![None; dof],
            external_wrench,
            routing_incomplete: false,
            idler_behind_capstan: false,
            sliding_check: crate::model::SlidingCheck::Constant,
            patterns,
            trace_record: Default::default(),
            identity: crate::model::new_identity(),
        })
    }
}

/// What is wrong with body `index` of a rigid tree, if anything. Every number is checked
/// finite before it is compared (a comparison with NaN is false, and would pass).
fn check_body(index: usize, body: &Body<f64>, dof: usize) -> std::result::Result<(), String> {
    let numbers = [
        body.pre.rotation.rows.concat(),
        body.pre.translation.to_array().to_vec(),
        body.post.rotation.rows.concat(),
        body.post.translation.to_array().to_vec(),
        body.axis.to_array().to_vec(),
        body.joint_to_origin.to_array().to_vec(),
        body.inertia.rows.concat(),
        vec![body.offset],
    ]
    .concat();
    if numbers.iter().any(|x| !x.is_finite()) {
        return Err("every number of its transforms, axis and inertia must be finite".into());
    }
    match (&body.kind, index < dof) {
        (BodyKind::Link { joint }, true) if *joint == index => {}
        (BodyKind::Pulley { role, .. }, false)
            if !matches!(role, PulleyRole::Fixed | PulleyRole::Coupled) =>
        {
            return Err(
                "a pulley of a tree of bodies alone is `Fixed` or `Coupled`: an idler or a \
                 loop's driving pulley needs the strands of a routing, which only a file gives"
                    .into(),
            );
        }
        (BodyKind::Pulley { radius, .. }, false) => {
            let out_of_range = beyond("radius", &[*radius], Range::Length).is_some();
            if !radius.is_finite() || *radius < MIN_RADIUS || out_of_range {
                return Err(format!(
                    "its radius is {radius} m; a pitch radius lies between {MIN_RADIUS:e} and \
                     the range of a length"
                ));
            }
            if body.parent.is_some_and(|p| p >= dof) {
                return Err("a pulley is carried by the base or a link".into());
            }
        }
        _ if index < dof => {
            return Err(format!("body {index} must be `Link {{ joint: {index} }}`"))
        }
        _ => {
            return Err(format!(
                "body {index} comes after the {dof} links: a pulley"
            ))
        }
    }
    if body.parent.is_some_and(|p| p >= index) {
        return Err(format!(
            "its parent is body {:?}; parents come before their children",
            body.parent
        ));
    }
    if body.coupling.len() != dof {
        return Err(format!(
            "its coupling has {} entries for {dof} joints",
            body.coupling.len()
        ));
    }
    if let Some(p) = finite_within("coupling", &body.coupling, Range::Ratio) {
        return Err(p);
    }
    let unit = |j: usize| f64::from(u8::from(j == index));
    if index < dof && body.coupling.iter().enumerate().any(|(j, &c)| c != unit(j)) {
        return Err(format!(
            "link {index}'s coupling must be the unit vector of joint {index}"
        ));
    }
    for (field, t) in [("pre", &body.pre), ("post", &body.post)] {
        check_transform(field, t)?;
    }
    if let Some(p) = beyond("offset", &[body.offset], Range::Angle) {
        return Err(p);
    }
    let axis = body.post.rotation.tr_mul_vec(Vec3::unit_z());
    let joint_to_origin = body.post.rotation.tr_mul_vec(body.post.translation);
    let scale = 1.0 + body.post.translation.dot(body.post.translation).sqrt();
    if distance(body.axis, axis) > DERIVED {
        return Err(format!("`axis` {:?} is not postᵀ z = {axis:?}", body.axis));
    }
    if distance(body.joint_to_origin, joint_to_origin) > DERIVED * scale {
        return Err(format!(
            "`joint_to_origin` {:?} is not postᵀ t = {joint_to_origin:?}",
            body.joint_to_origin
        ));
    }
    let inertia = &body.inertia.rows;
    let size = inertia
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let asymmetry = [(0, 1), (0, 2), (1, 2)]
        .map(|(r, c)| (inertia[r][c] - inertia[c][r]).abs())
        .into_iter()
        .fold(0.0_f64, f64::max);
    if asymmetry > DERIVED * size {
        return Err("its inertia is not symmetric".into());
    }
    if let Some(f) = body.friction {
        let values = [f.coulomb, f.viscous];
        if let Some(p) = finite_within("friction", &values, Range::Torque) {
            return Err(p);
        }
        if values.iter().any(|v| *v < 0.0) {
            return Err("bearing friction coefficients must be non-negative".into());
        }
    }
    let turns = body.coupling.iter().any(|&c| c != 0.0);
    if turns && !body.spins {
        // Its frame stays the housing frame (Eq. 16 without the spin): the recursion is
        // right only for a body whose mass distribution turning does not change.
        let along = axis.dot(body.inertia.mul_vec(axis));
        let across = (inertia[0][0] + inertia[1][1] + inertia[2][2] - along) / 2.0;
        let a = axis.to_array();
        let off = (0..9)
            .map(|k| {
                let (r, c) = (k / 3, k % 3);
                let identity = f64::from(u8::from(r == c));
                let symmetric = a[r] * a[c] * along + (identity - a[r] * a[c]) * across;
                (inertia[r][c] - symmetric).abs()
            })
            .fold(0.0, f64::max);
        let from_axis = body.com + joint_to_origin;
        let radial = from_axis - axis.scale(from_axis.dot(axis));
        if off > DERIVED * (1.0 + size) || radial.dot(radial).sqrt() > DERIVED * scale {
            return Err(
                "it turns without spinning (`spins: false`) but its mass is not axisymmetric \
                 about its axis: let it spin"
                    .into(),
            );
        }
    }
    Ok(())
}

/// What is wrong with a transform (its numbers checked finite): a rotation that is not
/// orthonormal with determinant 1, or a translation beyond the range of a length.
fn check_transform(field: &str, t: &Transform<f64>) -> std::result::Result<(), String> {
    let r = t.rotation;
    let product = r.transpose() * r;
    let off = (0..9)
        .map(|k| (product.rows[k / 3][k % 3] - f64::from(u8::from(k / 3 == k % 3))).abs())
        .fold(0.0, f64::max);
    let [a, b, c] = r.rows.map(|row| Vec3::new(row[0], row[1], row[2]));
    if off > DERIVED || a.cross(b).dot(c) <= 0.0 {
        return Err(format!(
            "`{field}.rotation` is not a rotation (orthonormal, det 1)"
        ));
    }
    beyond(
        &format!("{field}.translation"),
        &t.translation.to_array(),
        Range::Length,
    )
    .map_or(Ok(()), Err)
}

/// What is wrong with `values`: a number not finite, or beyond `range`.
fn finite_within(field: &str, values: &[f64], range: Range) -> Option<String> {
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Some(format!("`{field}` is {v}; it must be finite"));
    }
    beyond(field, values, range)
}

fn distance(a: Vec3<f64>, b: Vec3<f64>) -> f64 {
    let d = a - b;
    d.dot(d).sqrt()
}
