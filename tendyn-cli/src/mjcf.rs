//! `tendyn export --mjcf`: the mechanism as a MuJoCo model (MJCF).
//!
//! What is exported: every link a body with its hinge, every turning pulley with mass a
//! body with a hinge on its carrier (a pulley whose frame does not spin is axisymmetric, so
//! spinning it in MuJoCo changes nothing), a fixed pulley with mass a body without joint,
//! each with its mass, centre of mass and full inertia; gravity; every such pulley's
//! coupling as a fixed tendon `coupling/<pulley>` (coefficient 1 on the pulley's hinge,
//! `−c_j` on the joints) held at zero length by a nearly hard equality; every open-ended
//! tendon as a fixed tendon named after it, its structure-matrix column as the joints'
//! coefficients, driven by a tendon actuator whose force range is `[floor,
//! max_tension]`; motors on a joint as actuators on its hinge, motors on a pulley as
//! actuators on a fixed tendon `motor/<name>` whose coefficients are the pulley's coupling
//! (the generalized force `c τ` it puts on the joints).
//!
//! What is not: the routing's geometry (segments, contact points, idlers, guides and their
//! friction): MuJoCo's fixed tendons carry the kinematics `Q = A T`, not the path; loops
//! (their pretension acts inside the transmission); bearing friction; the external
//! wrench; pulleys without mass (they carry nothing and have no dynamics, and MuJoCo
//! refuses a massless moving body). A turning body that is exported (a link, or a pulley
//! with mass) without positive mass and positive-definite inertia, or a body named
//! `world`, is refused with an error naming it.

use quick_xml::events::{BytesDecl, Event};
use quick_xml::Writer;
use tendyn_core::model::{BodyKind, MotorKind};
use tendyn_core::spatial::{Mat3, Vec3};
use tendyn_core::transmission::body_transform;
use tendyn_core::Model;

/// The impedance of the couplings' equalities (MuJoCo's `solimp`: 0.999 near the
/// constraint, 0.9999 beyond a violation of 1 mrad).
const COUPLING_IMPEDANCE: &str = "0.999 0.9999 0.001";

/// Whether body `b` is exported: links, and pulleys with mass.
fn exported(model: &Model<f64>, b: usize) -> bool {
    b < model.dof() || model.bodies()[b].mass > 0.0
}

/// Whether body `b` turns relative to its carrier (a link, or a pulley with a coupling).
fn turns(model: &Model<f64>, b: usize) -> bool {
    model.bodies()[b].coupling.iter().any(|&c| c != 0.0)
}

fn numbers(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| format!("{v:e}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The unit quaternion `(w, x, y, z)` of a rotation matrix (Shepperd's method: the
/// largest of the four squares first, for accuracy).
fn quaternion(r: &Mat3<f64>) -> [f64; 4] {
    let m = &r.rows;
    let trace = m[0][0] + m[1][1] + m[2][2];
    if trace > 0.0 {
        let s = 2.0 * (trace + 1.0).sqrt();
        [
            s / 4.0,
            (m[2][1] - m[1][2]) / s,
            (m[0][2] - m[2][0]) / s,
            (m[1][0] - m[0][1]) / s,
        ]
    } else if m[0][0] > m[1][1] && m[0][0] > m[2][2] {
        let s = 2.0 * (1.0 + m[0][0] - m[1][1] - m[2][2]).sqrt();
        [
            (m[2][1] - m[1][2]) / s,
            s / 4.0,
            (m[0][1] + m[1][0]) / s,
            (m[0][2] + m[2][0]) / s,
        ]
    } else if m[1][1] > m[2][2] {
        let s = 2.0 * (1.0 + m[1][1] - m[0][0] - m[2][2]).sqrt();
        [
            (m[0][2] - m[2][0]) / s,
            (m[0][1] + m[1][0]) / s,
            s / 4.0,
            (m[1][2] + m[2][1]) / s,
        ]
    } else {
        let s = 2.0 * (1.0 + m[2][2] - m[0][0] - m[1][1]).sqrt();
        [
            (m[1][0] - m[0][1]) / s,
            (m[0][2] + m[2][0]) / s,
            (m[1][2] + m[2][1]) / s,
            s / 4.0,
        ]
    }
}

/// The hinge of body `b`: named after the body.
fn hinge(model: &Model<f64>, b: usize) -> String {
    model.bodies()[b].name.clone()
}

type Result<T> = std::io::Result<T>;

fn body(w: &mut Writer<Vec<u8>>, model: &Model<f64>, b: usize) -> Result<()> {
    let body = &model.bodies()[b];
    // The body's frame at q = 0 in its parent's: pre · RotZ(offset) · post.
    let placed = body_transform(body, body.offset);
    let v = |x: Vec3<f64>| numbers(&x.to_array());
    let mass = body.mass;
    let i = &body.inertia.rows;
    let inertia = [i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2]];
    w.create_element("body")
        .with_attributes([
            ("name", body.name.as_str()),
            ("pos", v(placed.translation).as_str()),
            ("quat", numbers(&quaternion(&placed.rotation)).as_str()),
        ])
        .write_inner_content(|w| {
            if mass > 0.0 {
                w.create_element("inertial")
                    .with_attributes([
                        ("pos", v(body.com).as_str()),
                        ("mass", format!("{mass:e}").as_str()),
                        ("fullinertia", numbers(&inertia).as_str()),
                    ])
                    .write_empty()?;
            }
            if turns(model, b) {
                // The joint point is −joint_to_origin in the body's frame, the axis postᵀ z;
                // a link's `range` is its hinge's (MuJoCo's `autolimits` makes it a limit).
                let range = match body.kind {
                    BodyKind::Link { joint } => model.joint_range(joint).map(|r| numbers(&r)),
                    _ => None,
                };
                let (name, pos, axis) = (hinge(model, b), v(-body.joint_to_origin), v(body.axis));
                let mut attributes = vec![
                    ("name", name.as_str()),
                    ("type", "hinge"),
                    ("pos", pos.as_str()),
                    ("axis", axis.as_str()),
                ];
                if let Some(range) = &range {
                    attributes.push(("range", range.as_str()));
                }
                w.create_element("joint")
                    .with_attributes(attributes)
                    .write_empty()?;
            }
            let children = (0..model.bodies().len())
                .filter(|&c| model.bodies()[c].parent == Some(b) && exported(model, c));
            for child in children {
                self::body(w, model, child)?;
            }
            Ok(())
        })?;
    Ok(())
}

/// The MJCF text of `model` (see the module documentation for what it holds); `Err`
/// names a body MuJoCo would refuse.
pub fn mjcf(model: &Model<f64>) -> std::result::Result<String, String> {
    for (b, body) in model.bodies().iter().enumerate() {
        if body.name == "world" {
            return Err("a body named `world` would clash with MuJoCo's world body".into());
        }
        if exported(model, b) && turns(model, b) && !mass_properties_are_positive(body) {
            return Err(format!(
                "`{}` turns but has no positive mass and positive-definite inertia, which \
                 MuJoCo needs on every moving body (a massless link or a point mass cannot \
                 be exported): give it mass properties",
                body.name
            ));
        }
    }
    write(model).map_err(|e| format!("cannot write MJCF: {e}"))
}

/// A positive mass and a positive-definite inertia (Sylvester: positive leading minors).
fn mass_properties_are_positive(body: &tendyn_core::model::Body<f64>) -> bool {
    let i = &body.inertia.rows;
    let minor2 = i[0][0] * i[1][1] - i[0][1] * i[1][0];
    let det = i[0][0] * (i[1][1] * i[2][2] - i[1][2] * i[2][1])
        - i[0][1] * (i[1][0] * i[2][2] - i[1][2] * i[2][0])
        + i[0][2] * (i[1][0] * i[2][1] - i[1][1] * i[2][0]);
    body.mass > 0.0 && i[0][0] > 0.0 && minor2 > 0.0 && det > 0.0
}

fn write(model: &Model<f64>) -> Result<String> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("utf-8"), None)))?;
    let n = model.dof();
    let couplings: Vec<usize> = (n..model.bodies().len())
        .filter(|&b| exported(model, b) && turns(model, b))
        .collect();
    w.create_element("mujoco")
        .with_attribute(("model", model.name()))
        .write_inner_content(|w| {
            w.create_element("compiler")
                .with_attributes([("angle", "radian"), ("autolimits", "true")])
                .write_empty()?;
            w.create_element("option")
                .with_attribute(("gravity", numbers(&model.gravity().to_array()).as_str()))
                .write_empty()?;
            w.create_element("worldbody").write_inner_content(|w| {
                let roots = (0..model.bodies().len())
                    .filter(|&b| model.bodies()[b].parent.is_none() && exported(model, b));
                for b in roots {
                    body(w, model, b)?;
                }
                Ok(())
            })?;
            w.create_element("tendon").write_inner_content(|w| {
                let fixed = |w: &mut Writer<Vec<u8>>, name: &str, terms: Vec<(String, f64)>| {
                    w.create_element("fixed")
                        .with_attribute(("name", name))
                        .write_inner_content(|w| {
                            for (joint, coef) in terms.iter().filter(|t| t.1 != 0.0) {
                                w.create_element("joint")
                                    .with_attributes([
                                        ("joint", joint.as_str()),
                                        ("coef", format!("{coef:e}").as_str()),
                                    ])
                                    .write_empty()?;
                            }
                            Ok::<(), std::io::Error>(())
                        })
                        .map(|_| ())
                };
                for &b in &couplings {
                    let mut terms = vec![(hinge(model, b), 1.0)];
                    terms.extend((0..n).map(|j| (hinge(model, j), -model.bodies()[b].coupling[j])));
                    fixed(w, &format!("coupling/{}", model.bodies()[b].name), terms)?;
                }
                for t in model.tendons() {
                    let terms = (0..n).map(|j| (hinge(model, j), t.structure[j])).collect();
                    fixed(w, &t.name, terms)?;
                }
                for m in model.motors() {
                    if let MotorKind::Pulley(b) = m.kind {
                        let c = &model.bodies()[b].coupling;
                        let terms = (0..n).map(|j| (hinge(model, j), c[j])).collect();
                        fixed(w, &format!("motor/{}", m.name), terms)?;
                    }
                }
                Ok(())
            })?;
            if !couplings.is_empty() {
                w.create_element("equality").write_inner_content(|w| {
                    for &b in &couplings {
                        let name = format!("coupling/{}", model.bodies()[b].name);
                        // Nearly hard: MuJoCo's constraints are soft, and a light pulley
                        // on a default impedance (0.9-0.95) drifts by tenths of a radian.
                        w.create_element("tendon")
                            .with_attributes([
                                ("tendon1", name.as_str()),
                                ("solimp", COUPLING_IMPEDANCE),
                            ])
                            .write_empty()?;
                    }
                    Ok(())
                })?;
            }
            w.create_element("actuator").write_inner_content(|w| {
                for t in model.tendons() {
                    let max = t.max_tension.unwrap_or(f64::MAX);
                    w.create_element("motor")
                        .with_attributes([
                            ("name", t.name.as_str()),
                            ("tendon", t.name.as_str()),
                            ("forcerange", numbers(&[t.floor, max]).as_str()),
                        ])
                        .write_empty()?;
                }
                for m in model.motors() {
                    let (kind, target) = match m.kind {
                        MotorKind::Joint(j) => ("joint", hinge(model, j)),
                        MotorKind::Pulley(_) => ("tendon", format!("motor/{}", m.name)),
                    };
                    w.create_element("motor")
                        .with_attributes([("name", m.name.as_str()), (kind, target.as_str())])
                        .write_empty()?;
                }
                Ok(())
            })?;
            Ok(())
        })?;
    Ok(String::from_utf8(w.into_inner()).expect("UTF-8 names and numbers"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use quick_xml::events::Event;
    use quick_xml::Reader;

    /// Each element's name, in document order.
    fn elements(xml: &str) -> Vec<String> {
        let mut reader = Reader::from_str(xml);
        let mut names = Vec::new();
        loop {
            match reader.read_event().unwrap() {
                Event::Start(e) | Event::Empty(e) => names.push(e.name().as_ref().to_string()),
                Event::Eof => return names,
                _ => {}
            }
        }
    }

    /// A link's `range` becomes its hinge's, in radians (the compiler's `angle`); a link
    /// without one has no `range`.
    #[test]
    fn a_joint_range_is_exported_as_its_hinge_range() {
        let text = tendyn_codegen::report::BUILT_IN[0].1;
        let first_dh = text.find("dh: (").unwrap();
        let ranged = format!(
            "{}range: (-1.5, 2.0), {}",
            &text[..first_dh],
            &text[first_dh..]
        );
        let model = tendyn_core::parse(&ranged).unwrap();
        let xml = mjcf(&model).unwrap();
        assert_eq!(xml.matches("range=").count(), 1, "{xml}");
        let joint = format!("<joint name=\"{}\"", model.bodies()[0].name);
        let hinge = xml.find(&joint).unwrap();
        let line = &xml[hinge..hinge + xml[hinge..].find("/>").unwrap()];
        assert!(line.contains("range=\"-1.5e0 2e0\""), "{line}");
    }

    /// What the module documentation promises, counted for the paper's examples: a body
    /// per link and per pulley with mass, a hinge per turning one, a fixed tendon and an
    /// equality per exported coupling, a fixed tendon and an actuator per open-ended
    /// tendon, an actuator per motor.
    #[test]
    fn the_export_holds_what_its_documentation_says() {
        for (file, text) in tendyn_codegen::report::BUILT_IN {
            let model = tendyn_core::parse(text).unwrap();
            let names = elements(&mjcf(&model).unwrap());
            let count = |name: &str| names.iter().filter(|n| *n == name).count();
            let bodies = (0..model.bodies().len()).filter(|&b| exported(&model, b));
            let hinges = bodies.clone().filter(|&b| turns(&model, b)).count();
            let coupled = hinges - model.dof();
            let pulley_motors = model
                .motors()
                .iter()
                .filter(|m| matches!(m.kind, MotorKind::Pulley(_)))
                .count();
            assert_eq!(count("body"), bodies.count(), "{file}");
            // Hinges, then one `joint` entry per non-zero coefficient of a fixed tendon.
            let nonzero = |row: &[f64]| row.iter().filter(|&&c| c != 0.0).count();
            let terms: usize = (model.dof()..model.bodies().len())
                .filter(|&b| exported(&model, b) && turns(&model, b))
                .map(|b| 1 + nonzero(&model.bodies()[b].coupling))
                .chain(model.tendons().iter().map(|t| nonzero(&t.structure)))
                .chain(model.motors().iter().filter_map(|m| match m.kind {
                    MotorKind::Pulley(b) => Some(nonzero(&model.bodies()[b].coupling)),
                    MotorKind::Joint(_) => None,
                }))
                .sum();
            assert_eq!(count("joint"), hinges + terms, "{file}");
            assert_eq!(
                count("fixed"),
                coupled + model.tendons().len() + pulley_motors,
                "{file}"
            );
            assert_eq!(
                count("tendon"),
                1 + coupled,
                "{file}: the section and the equalities"
            );
            assert_eq!(
                count("motor"),
                model.tendons().len() + model.motors().len(),
                "{file}"
            );
        }
    }
}
