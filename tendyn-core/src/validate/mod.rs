//! RON file → validated [`Model`], or an error that names the item, its line and what
//! would fix it. Nothing is returned unless every check passes.
//!
//! The entry points, the checks every phase uses and the order of the phases are here; each
//! phase lives with its concern: `parameters` (runtime parameters, checked first), `ranges`
//! (ranges of magnitude), `locate` (places in the text), `bodies` (links and pulleys),
//! `routing` (routes, couplings, strands, tendons, loops and motors) and `tension_system`
//! (`E`, its rank, `E⁺` and the positive null vector).

mod bodies;
mod locate;
mod parameters;
mod ranges;
mod rigid_tree;
mod routing;
mod tension_system;

pub use bodies::{axis_and_origin, dh_post, on_own_joint_axis};
pub use ranges::{
    MAX_ACCELERATION, MAX_ANGLE, MAX_FORCE, MAX_FRICTION_TORQUE, MAX_INERTIA, MAX_LENGTH,
    MAX_LINKS, MAX_MASS, MAX_MOMENT, MAX_RATIO, MAX_SMOOTHING, MAX_VISCOUS, MIN_RADIUS,
    MIN_SMOOTHING,
};
pub(crate) use tension_system::Sliding;

use crate::error::{Error, Location, Result};
use crate::format::{FrictionSpec, MechanismFile};
use crate::model::{BearingFriction, BodyKind, Model, Parameter, PulleyRole, Strand, Wrench};
use crate::spatial::{Mat3, Vec3};
use crate::transmission::{column_of, TraceRecord, TracedRoute};
use bodies::MassProperties;
use locate::{candidates, syntax_error, NameIndex};
use parameters::parameter_slots;
use ranges::{beyond, shown, Range};
use routing::Strands;
use tension_system::Actuators;

/// Reads and validates a mechanism file.
pub fn load(path: impl AsRef<std::path::Path>) -> Result<Model<f64>> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    parse(&text)
}

/// Validates a mechanism given as RON text. A leading UTF-8 byte-order mark (which some
/// editors write) is skipped; lines and columns are counted after it.
pub fn parse(text: &str) -> Result<Model<f64>> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let file = read(text)?;
    let mut v = Validator::new(text);
    v.params = v.parameters(&file)?;
    let mut model = v.model(&file)?;
    model.sliding_check =
        tension_system::sliding_directions(&v, &model, file.accept_sampled_sliding)?;
    Ok(model)
}

/// The file as written, read but not validated (RON syntax errors only). A leading
/// byte-order mark is skipped, as [`parse`] does.
pub fn read(text: &str) -> Result<MechanismFile> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    options.from_str(text).map_err(|e| syntax_error(text, &e))
}

/// Validates an already parsed file (no source text: errors carry no line numbers).
pub fn validate(file: &MechanismFile) -> Result<Model<f64>> {
    let mut v = Validator::new("");
    v.params = v.parameters(file)?;
    let mut model = v.model(file)?;
    model.sliding_check =
        tension_system::sliding_directions(&v, &model, file.accept_sampled_sliding)?;
    Ok(model)
}

struct Validator<'a> {
    text: &'a str,
    /// Where each name is defined and first mentioned, found in one pass over the text.
    names: NameIndex,
    /// Runtime parameters and their nominal values, which validation checks.
    params: Vec<(String, f64)>,
}

impl<'a> Validator<'a> {
    fn new(text: &'a str) -> Self {
        Validator {
            text,
            names: NameIndex::of(text),
            params: Vec::new(),
        }
    }

    fn finite(&self, item: &str, field: &str, values: &[f64]) -> Result<()> {
        self.finite_in(item, field, values, false)
    }

    /// Every number of `field` is finite; the error is at the field's line in the item
    /// (at the item's name, should it not be found), or at the top-level `field:` line when
    /// `top_level` (the mechanism's `gravity`, …).
    fn finite_in(&self, item: &str, field: &str, values: &[f64], top_level: bool) -> Result<()> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => {
                let problem = format!("`{field}` is {v}; every number must be finite");
                Err(if top_level {
                    self.invalid_at_key(item, field, problem)
                } else {
                    self.invalid_field(item, field, problem)
                })
            }
            None => Ok(()),
        }
    }

    /// Every number of `field` (finite already) is at most `max` in size; the error names
    /// the item, the number and the range, and says what would fix it.
    fn within(&self, item: &str, field: &str, values: &[f64], range: Range) -> Result<()> {
        match beyond(field, values, range) {
            None => Ok(()),
            Some(problem) => Err(self.invalid_field(item, field, problem)),
        }
    }

    /// [`Validator::within`] for a number of the top-level field `key` (`gravity`, …): the
    /// error is at that field's line.
    fn within_key(
        &self,
        item: &str,
        key: &str,
        field: &str,
        values: &[f64],
        range: Range,
    ) -> Result<()> {
        match beyond(field, values, range) {
            None => Ok(()),
            Some(problem) => Err(self.invalid_at_key(item, key, problem)),
        }
    }

    /// A bearing's friction: finite, non-negative coefficients within their ranges
    /// (format.md §4a); `None` when absent or all zero.
    fn friction(&self, item: &str, spec: Option<&FrictionSpec>) -> Result<Option<BearingFriction>> {
        let Some(f) = spec else { return Ok(None) };
        for (field, v, range) in [
            ("friction.coulomb", f.coulomb, Range::Torque),
            ("friction.viscous", f.viscous, Range::Damping),
        ] {
            self.finite(item, field, &[v])?;
            if v < 0.0 {
                let (_, unit, _) = range.described();
                return Err(self.invalid_field(
                    item,
                    field,
                    format!(
                        "`{field}` is {} {unit}; friction opposes motion, so give its size, a \
                         number >= 0",
                        shown(v)
                    ),
                ));
            }
            self.within(item, field, &[v], range)?;
        }
        Ok(
            (f.coulomb > 0.0 || f.viscous > 0.0).then_some(BearingFriction {
                coulomb: f.coulomb,
                viscous: f.viscous,
            }),
        )
    }

    /// The model, phase by phase in the order of the checks: each phase checks what it
    /// reads and hands its results on, so the error reported is the first one found.
    fn model(&self, f: &MechanismFile) -> Result<Model<f64>> {
        let gravity = self.nums(&f.gravity);
        self.finite_in(&f.name, "gravity", &gravity, true)?;
        self.within_key(&f.name, "gravity", "gravity", &gravity, Range::Acceleration)?;
        if f.links.is_empty() {
            return Err(self.invalid(&f.name, "a mechanism needs at least one link"));
        }
        if f.links.len() > ranges::MAX_LINKS {
            return Err(self.invalid(
                &f.name,
                format!(
                    "{} links: at most {} are supported (a position sums every link's length, \
                     whose square must stay far from the scalar's range)",
                    f.links.len(),
                    ranges::MAX_LINKS
                ),
            ));
        }
        self.unique_names(f)?;
        let n = f.links.len();
        let (mut bodies, pulleys) = self.bodies(f)?;
        let routes = self.routes(f)?;
        let mut couplings = self.couplings(f, &bodies, &pulleys, &routes)?;
        let mut strands = Strands::of(&routes, &mut couplings.geometry);
        let floor_default = self.tension_floor(f)?;
        self.friction_smoothing(f)?;
        let tendons = self.tendons(f, floor_default, &routes, &mut strands)?;
        let loops = routing::loops(f, &routes, &strands.of_route, &pulleys);
        routing::pulley_roles(
            &mut bodies,
            &pulleys,
            &couplings,
            &routes,
            &strands.of_route,
        );
        let motors = self.motors(f, &bodies, &pulleys, &mut strands.unknowns)?;
        let external_wrench = self.external_wrench(f)?;
        let strands_of_route = strands.of_route.clone();
        let actuators = Actuators {
            strands: strands.list,
            tendons,
            loops,
            motors,
        };
        let system = self.tension_system(f, &bodies, &pulleys, &actuators, strands.unknowns)?;
        let Actuators {
            strands,
            tendons,
            loops,
            motors,
        } = actuators;
        let routing_incomplete = tendons.iter().any(|t| t.strand.is_none())
            || bodies.iter().any(|b| {
                matches!(
                    b.kind,
                    BodyKind::Pulley {
                        role: PulleyRole::Coupled,
                        ..
                    }
                )
            });
        let strands: Vec<_> = (strands.into_iter().enumerate())
            .map(|(i, (name, g))| Strand {
                name,
                shares: (g.segment_rates.iter())
                    .map(|rate| column_of(&system.rows, rate, &pulleys))
                    .collect(),
                segments: g.segments,
                idlers: g.idlers,
                unknown: i,
            })
            .collect();
        let trace_record = TraceRecord {
            routes: (couplings.order.iter())
                .map(|&i| {
                    let route = routes[i].0.clone();
                    let start_is_coordinate = couplings.routed_end[route.wraps[0].0];
                    TracedRoute {
                        route,
                        strand: strands_of_route[i],
                        start_is_coordinate,
                    }
                })
                .collect(),
            pulleys,
        };
        let parameter_slots = parameter_slots(f);
        let patterns = crate::model::patterns_of(&bodies, &parameter_slots);
        let idler_behind_capstan = crate::model::capstan_before_an_idler(&strands);
        Ok(Model {
            name: f.name.clone(),
            gravity: Vec3::from_array(gravity),
            parameters: f
                .parameters
                .iter()
                .map(|p| Parameter {
                    name: p.name.clone(),
                    value: p.value,
                })
                .collect(),
            parameter_slots,
            dof: n,
            bodies,
            strands,
            tendons,
            objective: f.distribution,
            friction_smoothing: f.friction_smoothing,
            joint_ranges: f.links.iter().map(|l| l.range).collect(),
            loops,
            motors,
            system,
            external_wrench,
            routing_incomplete,
            idler_behind_capstan,
            sliding_check: crate::model::SlidingCheck::Constant,
            trace_record,
            patterns,
            identity: crate::model::new_identity(),
        })
    }

    /// Names are unique across every kind of item, and `base` is the ground.
    fn unique_names(&self, f: &MechanismFile) -> Result<()> {
        let mut seen: std::collections::HashSet<&str> = std::collections::HashSet::from(["base"]);
        let names = f
            .links
            .iter()
            .map(|l| &l.name)
            .chain(f.pulleys.iter().map(|p| &p.name))
            .chain(f.tendons.iter().map(|t| &t.name))
            .chain(f.loops.iter().map(|l| &l.name))
            .chain(f.motors.iter().map(|m| &m.name));
        for name in names {
            if name.is_empty() {
                return Err(Error::Invalid {
                    item: "an item".into(),
                    at: self.locate(name),
                    problem: "its `name` is empty; every link, pulley, tendon, loop and motor \
                              needs a name of its own"
                        .into(),
                });
            }
            if name.contains('/') {
                return Err(self.invalid(
                    name,
                    format!(
                        "the name `{name}` cannot be used: names must not contain `/` (it \
                         separates a loop's name from its sides, `loop/ccw`)"
                    ),
                ));
            }
            if seen.contains(&name.as_str()) {
                if name == "base" {
                    return Err(self.invalid(
                        name,
                        "`base` is the ground and cannot name an item; rename it",
                    ));
                }
                // Point at the second definition; the first is where the name is taken.
                let first = self.locate_nth(name, 0);
                let taken = if first.line == 0 {
                    String::new()
                } else {
                    format!(" (first at line {})", first.line)
                };
                return Err(Error::Invalid {
                    item: name.to_string(),
                    at: self.locate_nth(name, 1),
                    problem: format!(
                        "the name `{name}` is used twice{taken}; every item needs its own name, \
                         rename one of them"
                    ),
                });
            }
            seen.insert(name);
        }
        Ok(())
    }

    /// The default tension floor, finite and within the range of a force (its sign is
    /// checked with each tendon's floor).
    fn tension_floor(&self, f: &MechanismFile) -> Result<f64> {
        let floor_default = f.tension_floor;
        self.finite_in(&f.name, "tension_floor", &[floor_default], true)?;
        self.within_key(
            &f.name,
            "tension_floor",
            "tension_floor",
            &[floor_default],
            Range::Force,
        )?;
        Ok(floor_default)
    }

    /// `friction_smoothing`, if given, within its range.
    fn friction_smoothing(&self, f: &MechanismFile) -> Result<()> {
        if let Some(v) = f.friction_smoothing {
            self.finite_in(&f.name, "friction_smoothing", &[v], true)?;
            // Below 1e-9 rad/s `ω / v` overflows f32 for ordinary rates (and `0 / 0` at rest
            // is NaN once `v` rounds to zero); above 1e6 rad/s friction would never reach
            // its Coulomb value at any speed a mechanism turns.
            if !(MIN_SMOOTHING..=MAX_SMOOTHING).contains(&v) {
                return Err(self.invalid_at_key(
                    &f.name,
                    "friction_smoothing",
                    format!(
                        "`friction_smoothing` is {} rad/s; it is the speed over which friction \
                         turns smoothly from one direction to the other, a number from \
                         {MIN_SMOOTHING:e} to {MAX_SMOOTHING:e} rad/s (leave it out for the \
                         exact law)",
                        shown(v)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The external wrench, if any: on a link, finite, within the ranges of a length, a
    /// force and a moment.
    fn external_wrench(&self, f: &MechanismFile) -> Result<Option<Wrench<f64>>> {
        let link_index = |name: &str| f.links.iter().position(|l| l.name == name);
        let external_wrench = match &f.external_wrench {
            None => None,
            Some(w) => {
                let at = self.locate_key("external_wrench");
                let link = link_index(&w.link).ok_or_else(|| Error::Invalid {
                    item: f.name.clone(),
                    at,
                    problem: format!(
                        "external_wrench names `{}`, which is not a link ({})",
                        w.link,
                        candidates("links", f.links.iter().map(|l| l.name.as_str()))
                    ),
                })?;
                let (point, force, moment) = (
                    self.nums(&w.point),
                    self.nums(&w.force),
                    self.nums(&w.moment),
                );
                let values = [point, force, moment].concat();
                if let Some(v) = values.iter().find(|v| !v.is_finite()) {
                    return Err(Error::Invalid {
                        item: f.name.clone(),
                        at,
                        problem: format!(
                            "`external_wrench` on `{}` has {v} in it; every number must be finite",
                            w.link
                        ),
                    });
                }
                if let Some(&v) = point.iter().find(|v| v.abs() > MAX_LENGTH) {
                    let (_, _, fix) = Range::Length.described();
                    return Err(Error::Invalid {
                        item: f.name.clone(),
                        at,
                        problem: format!(
                            "the `point` of `external_wrench` on `{}` has {} m, beyond the range \
                             of a length (at most {MAX_LENGTH:e} m in size; format.md §12, ranges \
                             of magnitude): {fix}",
                            w.link,
                            shown(v)
                        ),
                    });
                }
                for (field, values, range) in [
                    ("external_wrench.force", &force, Range::Force),
                    ("external_wrench.moment", &moment, Range::Moment),
                ] {
                    self.within_key(&f.name, "external_wrench", field, values, range)?;
                }
                Some(Wrench {
                    link,
                    point: Vec3::from_array(point),
                    force: Vec3::from_array(force),
                    moment: Vec3::from_array(moment),
                })
            }
        };
        Ok(external_wrench)
    }
}

/// The mass, centre-of-mass and inertia checks of validation (ranges of magnitude
/// included), for parameter values set at run time.
pub fn check_mass_properties(
    item: &str,
    mass: f64,
    com: Vec3<f64>,
    inertia: &Mat3<f64>,
) -> Result<()> {
    let r = &inertia.rows;
    let mp = MassProperties {
        mass,
        com: com.to_array(),
        inertia: [r[0][0], r[1][1], r[2][2], r[0][1], r[0][2], r[1][2]],
    };
    Validator::new("").mass_properties(item, &mp)
}

/// The checks of validation for the numbers a runtime parameter may set besides mass
/// properties: gravity and the external wrench, finite and within their ranges of
/// magnitude (format.md §12). `mechanism` names the item, as in a file.
pub fn check_gravity_and_wrench(
    mechanism: &str,
    gravity: Vec3<f64>,
    wrench: Option<&Wrench<f64>>,
) -> Result<()> {
    let mut fields = vec![("gravity", gravity, Range::Acceleration)];
    if let Some(w) = wrench {
        fields.extend([
            ("external_wrench.point", w.point, Range::Length),
            ("external_wrench.force", w.force, Range::Force),
            ("external_wrench.moment", w.moment, Range::Moment),
        ]);
    }
    for (field, v, range) in fields {
        let values = v.to_array();
        let problem = match values.iter().find(|x| !x.is_finite()) {
            Some(x) => Some(format!("`{field}` has {x}; every component must be finite")),
            None => beyond(field, &values, range),
        };
        if let Some(problem) = problem {
            return Err(Error::Invalid {
                item: mechanism.to_string(),
                at: Location::default(),
                problem,
            });
        }
    }
    Ok(())
}
