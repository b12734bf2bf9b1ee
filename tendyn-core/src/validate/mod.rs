//! RON file → validated [`Model`], or an error that names the item, its line and what
//! would fix it. Nothing is returned unless every check passes.

mod bodies;
mod locate;
mod parameters;
mod ranges;

use crate::error::{Error, ImpliedSystem, Location, Result};
use crate::format::{FrictionSpec, MechanismFile, MotorSite, Objective, Turn};
use crate::model::{
    BearingFriction, Body, BodyKind, Loop, Model, Motor, MotorKind, Parameter, PulleyRole, Row,
    Strand, Tendon, TensionSystem, Unknown, Wrench,
};
use crate::spatial::{Mat3, Vec3};
use crate::transmission::{Rate, Route, RouteEnd, Routing, StrandGeometry};
pub use bodies::dh_post;
use bodies::MassProperties;
use locate::{candidates, syntax_error, NameIndex};
use nalgebra::DMatrix;
use parameters::parameter_slots;
use ranges::{beyond, shown, Range};
pub use ranges::{
    MAX_ACCELERATION, MAX_ANGLE, MAX_FORCE, MAX_FRICTION_TORQUE, MAX_INERTIA, MAX_LENGTH, MAX_MASS,
    MAX_MOMENT, MAX_RATIO, MAX_SMOOTHING, MAX_VISCOUS, MIN_RADIUS, MIN_SMOOTHING,
};

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
    v.model(&file)
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
    v.model(file)
}

struct Validator<'a> {
    text: &'a str,
    /// Where each name is defined and first mentioned, found in one pass over the text.
    names: NameIndex,
    /// Runtime parameters and their nominal values, which validation checks.
    params: Vec<(String, f64)>,
}

/// `x > y`, false when either is NaN (so that `!above(…)` flags NaN as well).
fn above(x: f64, y: f64) -> bool {
    x.partial_cmp(&y) == Some(std::cmp::Ordering::Greater)
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

    /// Every number of `field` is finite; the error is at the item's line, or at the
    /// top-level `field:` line when `top_level` (the mechanism's `gravity`, …).
    fn finite_in(&self, item: &str, field: &str, values: &[f64], top_level: bool) -> Result<()> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => {
                let problem = format!("`{field}` is {v}; every number must be finite");
                Err(if top_level {
                    self.invalid_at_key(item, field, problem)
                } else {
                    self.invalid(item, problem)
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
            Some(problem) => Err(self.invalid(item, problem)),
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
                return Err(self.invalid(
                    item,
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

    fn model(&self, f: &MechanismFile) -> Result<Model<f64>> {
        let gravity = self.nums(&f.gravity);
        self.finite_in(&f.name, "gravity", &gravity, true)?;
        self.within_key(&f.name, "gravity", "gravity", &gravity, Range::Acceleration)?;
        if f.links.is_empty() {
            return Err(self.invalid(&f.name, "a mechanism needs at least one link"));
        }
        // Names are unique across every kind of item, and `base` is the ground.
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
        let n = f.links.len();
        let link_index = |name: &str| f.links.iter().position(|l| l.name == name);

        let (mut bodies, pulleys) = self.bodies(f)?;
        let pulley_index = |name: &str| f.pulleys.iter().position(|p| p.name == name);

        // Routes.
        let mut routes: Vec<(Route, Origin)> = Vec::new();
        for (k, t) in f.tendons.iter().enumerate() {
            self.finite(&t.name, "floor", &[t.floor.unwrap_or(0.0)])?;
            self.within(&t.name, "floor", &[t.floor.unwrap_or(0.0)], Range::Force)?;
            if t.route.is_empty() {
                if t.structure.is_none() {
                    return Err(self.routing(
                        &t.name,
                        "has neither a `route` nor an explicit `structure` column",
                    ));
                }
                if t.exit.is_some() {
                    return Err(self.routing(
                        &t.name,
                        "has an `exit` but no `route`: an exit point only means something at the \
                         end of a route; remove it or give the route",
                    ));
                }
                continue;
            }
            let mut wraps = Vec::new();
            for w in &t.route {
                let p = pulley_index(&w.0).ok_or_else(|| {
                    self.routing(
                        &t.name,
                        format!(
                            "its route names `{}`, which is not a pulley; check the spelling \
                             ({})",
                            w.0,
                            candidates("pulleys", f.pulleys.iter().map(|p| p.name.as_str()))
                        ),
                    )
                })?;
                wraps.push((p, w.1));
            }
            let anchor = &f.pulleys[wraps[0].0];
            if !anchor.fixed {
                return Err(self.routing(
                    &t.name,
                    format!(
                        "its route must start on an anchor (a `fixed: true` drum on a link), \
                         but `{}` turns freely; list the anchor drum first",
                        anchor.name
                    ),
                ));
            }
            let exit = t.exit.ok_or_else(|| {
                self.routing(
                    &t.name,
                    "has a route but no `exit` point where it leaves for its actuator",
                )
            })?;
            self.finite(&t.name, "exit", &exit)?;
            self.within(&t.name, "exit", &exit, Range::Length)?;
            routes.push((
                Route {
                    name: t.name.clone(),
                    at: self.locate(&t.name),
                    wraps,
                    end: RouteEnd::Exit(exit),
                },
                Origin::Tendon(k),
            ));
        }
        for (k, l) in f.loops.iter().enumerate() {
            self.finite(&l.name, "pretension", &[l.pretension])?;
            self.within(&l.name, "pretension", &[l.pretension], Range::Force)?;
            if l.pretension < 0.0 {
                return Err(self.invalid(
                    &l.name,
                    format!(
                        "pretension is {} N; pretension must not be negative (a loop's sides \
                         can only pull)",
                        l.pretension
                    ),
                ));
            }
            let find = |name: &str| {
                pulley_index(name).ok_or_else(|| {
                    self.routing(
                        &l.name,
                        format!(
                            "`{name}` is not a pulley; check the spelling ({})",
                            candidates("pulleys", f.pulleys.iter().map(|p| p.name.as_str()))
                        ),
                    )
                })
            };
            let (driven, driving) = (find(&l.driven)?, find(&l.driving)?);
            if driven == driving {
                return Err(self.routing(
                    &l.name,
                    "drives its own pulley; its `driven` and `driving` pulleys must differ",
                ));
            }
            if f.pulleys[driving].fixed {
                return Err(self.routing(
                    &l.name,
                    format!(
                        "its driving pulley `{}` is fixed to its carrier; a driving pulley turns",
                        l.driving
                    ),
                ));
            }
            let other = |t: Turn| match (t, l.crossed) {
                (t, false) => t,
                (Turn::Ccw, true) => Turn::Cw,
                (Turn::Cw, true) => Turn::Ccw,
            };
            for (side, turn) in [("ccw", Turn::Ccw), ("cw", Turn::Cw)] {
                routes.push((
                    Route {
                        name: format!("{}/{side}", l.name),
                        at: self.locate(&l.name),
                        wraps: vec![(driven, turn)],
                        end: RouteEnd::Pulley(driving, other(turn)),
                    },
                    Origin::Loop(k),
                ));
            }
        }

        // Couplings: fixed drums and explicit rows are known; routes derive the rest,
        // each route once the coupling of the body it starts from is known.
        let routing = Routing {
            bodies: &bodies,
            pulleys: &pulleys,
            dof: n,
        };
        let mut couplings: Vec<Option<Rate>> = f
            .pulleys
            .iter()
            .map(|p| {
                p.fixed.then(|| Rate {
                    joints: vec![0.0; n],
                    pulleys: Vec::new(),
                })
            })
            .collect();
        let mut explicit: Vec<Option<Vec<f64>>> = vec![None; f.pulleys.len()];
        for (i, p) in f.pulleys.iter().enumerate() {
            if let Some(c) = &p.coupling {
                if c.len() != n {
                    return Err(self.invalid(
                        &p.name,
                        format!(
                            "`coupling` has {} ratios but the mechanism has {n} joints",
                            c.len()
                        ),
                    ));
                }
                self.finite(&p.name, "coupling", c)?;
                self.within(&p.name, "coupling", c, Range::Ratio)?;
                if p.fixed && c.iter().any(|&x| x != 0.0) {
                    return Err(self.invalid(
                        &p.name,
                        "a fixed drum cannot have a coupling (it does not turn on its carrier); \
                         remove the coupling or `fixed: true`",
                    ));
                }
                explicit[i] = Some(c.clone());
            }
        }
        let routed_end: Vec<bool> = (0..f.pulleys.len())
            .map(|p| {
                routes
                    .iter()
                    .any(|(r, _)| matches!(r.end, RouteEnd::Pulley(e, _) if e == p))
            })
            .collect();
        let routed_through: Vec<usize> = (0..f.pulleys.len())
            .map(|p| {
                routes
                    .iter()
                    .filter(|(r, _)| r.wraps[1..].iter().any(|&(q, _)| q == p))
                    .count()
            })
            .collect();
        for (i, c) in explicit.iter().enumerate() {
            if c.is_some() && !routed_end[i] && routed_through[i] == 0 && !f.pulleys[i].fixed {
                couplings[i] = c.clone().map(|joints| Rate {
                    joints,
                    pulleys: Vec::new(),
                });
            }
        }
        let mut geometry: Vec<Option<StrandGeometry>> = vec![None; routes.len()];
        loop {
            let mut progressed = false;
            for (i, (route, _)) in routes.iter().enumerate() {
                let start = route.wraps[0].0;
                if geometry[i].is_some() || couplings[start].is_none() {
                    continue;
                }
                geometry[i] = Some(routing.trace(route, &mut couplings, routed_end[start])?);
                progressed = true;
            }
            if !progressed {
                break;
            }
        }
        if let Some(i) = geometry.iter().position(Option::is_none) {
            let (route, _) = &routes[i];
            return Err(self.routing(
                route.name.split('/').next().unwrap_or(&route.name),
                format!(
                    "starts on `{}`, whose rotation nothing determines (loops that drive each \
                     other in a circle, or a driven pulley with no coupling); make it a `fixed` \
                     drum, give it an explicit `coupling`, or drive it from a pulley whose \
                     rotation is known",
                    f.pulleys[route.wraps[0].0].name
                ),
            ));
        }
        for (i, p) in f.pulleys.iter().enumerate() {
            // A fixed pulley after an anchor is a guide: any number of tendons may slide
            // over it, and `mu` means something only there.
            if p.fixed {
                if p.mu.is_some() && routed_through[i] == 0 {
                    return Err(self.invalid(
                        &p.name,
                        "has `mu`, but no tendon slides over it (it is no route's guide: a \
                         guide is a fixed pulley after a route's anchor); remove `mu` or route \
                         a tendon over it",
                    ));
                }
                if let Some(mu) = p.mu.filter(|&mu| mu > 0.0) {
                    return Err(self.invalid(
                        &p.name,
                        format!(
                            "`mu: {mu}`: capstan friction on guides is not implemented yet \
                             (the tension system then depends on the sliding directions); a \
                             guide is frictionless for now: remove `mu` or set it to 0"
                        ),
                    ));
                }
                continue;
            }
            if routed_through[i] > 1 {
                return Err(self.routing(
                    &p.name,
                    "carries more than one tendon: a free idler's balance fixes the tension \
                     difference of one tendon only; give each tendon its own idler",
                ));
            }
            if routed_through[i] == 1 && routed_end[i] {
                return Err(self.routing(
                    &p.name,
                    "is both an idler of one tendon and the driving pulley of a loop; give the \
                     tendon its own idler",
                ));
            }
            let derived = couplings[i].as_ref().ok_or_else(|| {
                self.routing(
                    &p.name,
                    "is turned by nothing: route a tendon over it, make it `fixed`, or give \
                     it an explicit `coupling`",
                )
            })?;
            if derived.joints.iter().any(|x| !x.is_finite()) {
                return Err(self.routing(
                    &p.name,
                    format!(
                        "the routing turns it at a rate that is not finite ({:?} per joint): a \
                         radius along its tendon is too small to compute with; check the radii \
                         and their units",
                        derived.joints
                    ),
                ));
            }
            if let Some(c) = &explicit[i] {
                let agree = c
                    .iter()
                    .zip(&derived.joints)
                    .all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs())));
                if !agree {
                    return Err(self.routing(
                        &p.name,
                        format!(
                            "its explicit coupling {c:?} disagrees with the routing, which turns it \
                             as {:?}; correct the coupling or remove it (the routing defines it)",
                            derived.joints
                        ),
                    ));
                }
            }
        }

        // Strands, pulley roles and the unknowns of the tension system.
        let mut strands = Vec::new();
        let mut unknowns = Vec::new();
        let mut tendons = Vec::new();
        let mut loops = Vec::new();
        let mut strand_of_route = vec![0; routes.len()];
        let mut order: Vec<usize> = (0..routes.len())
            .filter(|&i| matches!(routes[i].1, Origin::Tendon(_)))
            .collect();
        order.extend((0..routes.len()).filter(|&i| matches!(routes[i].1, Origin::Loop(_))));
        for &i in &order {
            let g = geometry[i].take().expect("traced");
            strand_of_route[i] = strands.len();
            unknowns.push(Unknown::Strand(strands.len()));
            strands.push((routes[i].0.name.clone(), g));
        }
        let floor_default = f.tension_floor;
        self.finite_in(&f.name, "tension_floor", &[floor_default], true)?;
        self.within_key(
            &f.name,
            "tension_floor",
            "tension_floor",
            &[floor_default],
            Range::Force,
        )?;
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
        for (k, t) in f.tendons.iter().enumerate() {
            // A negative default is an error even when every tendon overrides it.
            let floor = if floor_default < 0.0 {
                floor_default
            } else {
                t.floor.unwrap_or(floor_default)
            };
            if floor < 0.0 {
                return Err(match t.floor.filter(|_| floor_default >= 0.0) {
                    Some(_) => self.invalid(
                        &t.name,
                        format!(
                            "`floor` is {floor} N; the tension floor must not be negative (a \
                             tendon cannot push)"
                        ),
                    ),
                    None => self.invalid_at_key(
                        &f.name,
                        "tension_floor",
                        format!(
                            "`tension_floor` is {floor} N; the tension floor must not be \
                             negative (a tendon cannot push)"
                        ),
                    ),
                });
            }
            if t.max_tension.is_none() && f.distribution == Objective::Centered {
                return Err(self.invalid(
                    &t.name,
                    "has no `max_tension`, but `distribution: Centered` aims every tension at \
                     the middle of its floor and maximum: give it a `max_tension`, or use the \
                     default `distribution: LeastNorm`"
                        .to_string(),
                ));
            }
            if let Some(mx) = t.max_tension {
                self.finite(&t.name, "max_tension", &[mx])?;
                self.within(&t.name, "max_tension", &[mx], Range::Force)?;
                if mx < floor {
                    return Err(self.invalid(
                        &t.name,
                        format!("max_tension {mx} N is below its floor {floor} N"),
                    ));
                }
            }
            let routed = routes
                .iter()
                .position(|(_, o)| matches!(o, Origin::Tendon(kk) if *kk == k));
            let (strand, unknown, mut column) = match routed {
                Some(i) => {
                    let s = strand_of_route[i];
                    (Some(s), s, strands[s].1.pull_rate.joints.clone())
                }
                None => {
                    unknowns.push(Unknown::Explicit(tendons.len()));
                    (None, unknowns.len() - 1, Vec::new())
                }
            };
            if let Some(col) = &t.structure {
                if col.len() != n {
                    return Err(self.invalid(
                        &t.name,
                        format!(
                            "`structure` has {} entries but the mechanism has {n} joints",
                            col.len()
                        ),
                    ));
                }
                self.finite(&t.name, "structure", col)?;
                // A column entry is a moment arm: a length.
                self.within(&t.name, "structure", col, Range::Length)?;
                if strand.is_some() {
                    let agree = col
                        .iter()
                        .zip(&column)
                        .all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs())));
                    if !agree {
                        return Err(self.routing(
                            &t.name,
                            format!(
                                "its explicit structure column {col:?} disagrees with its route, \
                                 which gives {column:?}; correct the column or remove it (the route \
                                 defines it)"
                            ),
                        ));
                    }
                } else {
                    column = col.clone();
                }
            }
            tendons.push(Tendon {
                name: t.name.clone(),
                strand,
                unknown,
                floor,
                max_tension: t.max_tension,
                structure: column,
            });
        }
        for (k, l) in f.loops.iter().enumerate() {
            let mut s = [0; 2];
            let mut side = 0;
            for (i, (_, o)) in routes.iter().enumerate() {
                if matches!(o, Origin::Loop(kk) if *kk == k) {
                    s[side] = strand_of_route[i];
                    side += 1;
                }
            }
            loops.push(Loop {
                name: l.name.clone(),
                driven: pulleys[pulley_index(&l.driven).expect("checked")].body,
                driving: pulleys[pulley_index(&l.driving).expect("checked")].body,
                crossed: l.crossed,
                pretension: l.pretension,
                strands: s,
            });
        }
        // Store couplings and roles on the pulley bodies.
        for (i, info) in pulleys.iter().enumerate() {
            let body = &mut bodies[info.body];
            body.coupling = couplings[i].as_ref().expect("checked").joints.clone();
            let role = if info.fixed {
                PulleyRole::Fixed
            } else if routed_end[i] {
                PulleyRole::Driving
            } else if routed_through[i] == 1 {
                let s = routes
                    .iter()
                    .position(|(r, _)| r.wraps[1..].iter().any(|&(q, _)| q == i))
                    .expect("counted");
                PulleyRole::Idler {
                    strand: strand_of_route[s],
                }
            } else {
                PulleyRole::Coupled
            };
            body.kind = BodyKind::Pulley {
                radius: info.radius,
                role,
            };
        }

        // Motors.
        let mut motors = Vec::new();
        for m in &f.motors {
            let (kind, column) = match &m.on {
                MotorSite::Joint(name) => {
                    let j = link_index(name).ok_or_else(|| {
                        self.invalid(
                            &m.name,
                            format!(
                                "`{name}` is not a link; a `Joint` motor names the link its joint \
                                 moves ({})",
                                candidates("links", f.links.iter().map(|l| l.name.as_str()))
                            ),
                        )
                    })?;
                    let mut c = vec![0.0; n];
                    c[j] = 1.0;
                    (MotorKind::Joint(j), c)
                }
                MotorSite::Pulley(name) => {
                    let p = pulley_index(name).ok_or_else(|| {
                        self.invalid(
                            &m.name,
                            format!(
                                "`{name}` is not a pulley; check the spelling ({})",
                                candidates("pulleys", f.pulleys.iter().map(|p| p.name.as_str()))
                            ),
                        )
                    })?;
                    let b = pulleys[p].body;
                    match &bodies[b].kind {
                        BodyKind::Pulley {
                            role: PulleyRole::Driving | PulleyRole::Coupled,
                            ..
                        } => {}
                        _ => {
                            return Err(self.invalid(
                                &m.name,
                                format!(
                                    "drives `{name}`, which is neither the driving pulley of a \
                                     loop nor explicitly coupled; a motor on a fixed drum or a \
                                     free idler has nothing to act against"
                                ),
                            ))
                        }
                    }
                    (MotorKind::Pulley(b), bodies[b].coupling.clone())
                }
            };
            if motors.iter().any(|o: &Motor| o.kind == kind) {
                return Err(self.invalid(
                    &m.name,
                    "a second motor on the same joint or pulley; remove one of them",
                ));
            }
            unknowns.push(Unknown::Motor(motors.len()));
            motors.push(Motor {
                name: m.name.clone(),
                kind,
                unknown: unknowns.len() - 1,
                column,
            });
        }
        if unknowns.len() > crate::affine::MAX_UNKNOWNS {
            return Err(self.invalid(
                &f.name,
                format!(
                    "{} tendon strands and motors exceed the supported {}",
                    unknowns.len(),
                    crate::affine::MAX_UNKNOWNS
                ),
            ));
        }

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

        let system =
            self.tension_system(f, n, &bodies, &strands, &tendons, &loops, &motors, unknowns)?;
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
            parameter_slots: parameter_slots(f),
            dof: n,
            bodies,
            strands: strands
                .into_iter()
                .enumerate()
                .map(|(i, (name, g))| Strand {
                    name,
                    segments: g.segments,
                    idlers: g.idlers,
                    unknown: i,
                })
                .collect(),
            tendons,
            objective: f.distribution,
            friction_smoothing: f.friction_smoothing,
            loops,
            motors,
            system,
            external_wrench,
            routing_incomplete,
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn tension_system(
        &self,
        f: &MechanismFile,
        n: usize,
        bodies: &[Body<f64>],
        strands: &[(String, StrandGeometry)],
        tendons: &[Tendon],
        loops: &[Loop],
        motors: &[Motor],
        unknowns: Vec<Unknown>,
    ) -> Result<TensionSystem<f64>> {
        let mut rows: Vec<Row> = (0..n).map(Row::Joint).collect();
        let driving: Vec<usize> = (0..bodies.len())
            .filter(|&b| {
                matches!(
                    bodies[b].kind,
                    BodyKind::Pulley {
                        role: PulleyRole::Driving,
                        ..
                    }
                )
            })
            .collect();
        rows.extend(driving.iter().map(|&b| Row::Pulley(b)));
        rows.extend((0..loops.len()).map(Row::Pretension));
        let body_of_pulley = |p: usize| bodies.iter().position(|b| b.name == f.pulleys[p].name);
        let m = unknowns.len();
        let mut e = vec![vec![0.0; m]; rows.len()];
        for (col, u) in unknowns.iter().enumerate() {
            match u {
                Unknown::Strand(s) => {
                    let rate = &strands[*s].1.pull_rate;
                    for (row, &x) in e.iter_mut().zip(&rate.joints[..n]) {
                        row[col] = x;
                    }
                    for &(p, c) in &rate.pulleys {
                        let b = body_of_pulley(p).expect("pulley body");
                        let row = rows
                            .iter()
                            .position(|r| *r == Row::Pulley(b))
                            .expect("driving row");
                        e[row][col] = c;
                    }
                }
                Unknown::Explicit(k) => {
                    for (row, &x) in e.iter_mut().zip(&tendons[*k].structure[..n]) {
                        row[col] = x;
                    }
                }
                Unknown::Motor(k) => match motors[*k].kind {
                    MotorKind::Joint(j) => e[j][col] = 1.0,
                    MotorKind::Pulley(b) => {
                        if let Some(row) = rows.iter().position(|r| *r == Row::Pulley(b)) {
                            e[row][col] = 1.0;
                        } else {
                            for (row, &x) in e.iter_mut().zip(&motors[*k].column[..n]) {
                                row[col] = x;
                            }
                        }
                    }
                },
            }
        }
        for (k, l) in loops.iter().enumerate() {
            let row = n + driving.len() + k;
            for s in l.strands {
                let col = unknowns
                    .iter()
                    .position(|u| *u == Unknown::Strand(s))
                    .expect("strand");
                e[row][col] = 0.5;
            }
        }
        // A routing that fails the checks below is reported with the system it implies, so
        // that `check` can show what the routing does (the closure holds the checks).
        let strand_names: Vec<&str> = strands.iter().map(|(name, _)| name.as_str()).collect();
        let implied = ImpliedSystem {
            rows: rows.iter().map(|r| r.label(bodies, loops)).collect(),
            unknowns: unknowns
                .iter()
                .map(|u| u.label(&strand_names, tendons, motors))
                .collect(),
            matrix: e.clone(),
            joints: n,
            tendons: tendons
                .iter()
                .map(|t| (t.name.clone(), t.unknown))
                .collect(),
        };
        let checked = || -> Result<TensionSystem<f64>> {
            let what = |u: &Unknown| match u {
                Unknown::Strand(s) => format!("tension `{}`", strands[*s].0),
                Unknown::Explicit(k) => format!("tension `{}`", tendons[*k].name),
                Unknown::Motor(k) => format!("motor `{}`", motors[*k].name),
            };
            let rows_len = rows.len();
            if m < rows_len {
                return Err(self.routing(
                    &f.name,
                    format!(
                        "under-actuated: {rows_len} balances (one per joint, driving pulley and loop) \
                         but only {m} tensions and motor torques to satisfy them; add motors or tendons"
                    ),
                ));
            }
            // The item an unknown belongs to: its tendon, loop or motor.
            let item_of = |u: &Unknown| -> String {
                match u {
                    Unknown::Strand(s) => strands[*s].0.split('/').next().unwrap_or("").to_string(),
                    Unknown::Explicit(k) => tendons[*k].name.clone(),
                    Unknown::Motor(k) => motors[*k].name.clone(),
                }
            };
            // Numbers too large for the geometry overflow here; the SVD must not see them.
            if let Some(col) = (0..m).find(|&c| e.iter().any(|row| !row[c].is_finite())) {
                return Err(self.routing(
                    &item_of(&unknowns[col]),
                    format!(
                        "the structure matrix column of {} is not finite ({:?}): its geometry \
                         overflows; check the sizes and units of the numbers along it",
                        what(&unknowns[col]),
                        e.iter().map(|row| row[col]).collect::<Vec<_>>()
                    ),
                ));
            }
            let dm = DMatrix::from_fn(rows_len, m, |i, j| e[i][j]);
            let svd = dm.clone().svd(false, false);
            let sv = &svd.singular_values;
            let smax = sv.iter().cloned().fold(0.0, f64::max);
            let smin = sv.iter().cloned().fold(f64::INFINITY, f64::min);
            // What a row balances, and the item that names it.
            let row_item = |r: &Row| -> (String, &str) {
                match *r {
                    Row::Joint(j) => (format!("joint `{}`", f.links[j].name), &f.links[j].name),
                    Row::Pulley(b) => (
                        format!("driving pulley `{}`", bodies[b].name),
                        &bodies[b].name,
                    ),
                    Row::Pretension(k) => (
                        format!("the pretension of loop `{}`", loops[k].name),
                        &loops[k].name,
                    ),
                }
            };
            if !above(smin, 1e-10 * smax) {
                let values = sv.as_slice();
                let row_norm = |i: usize| e[i].iter().map(|x| x * x).sum::<f64>().sqrt();
                // A row nothing acts on (structure entries are radii in metres, motor and
                // pretension entries are of order one: 1e-12 is nothing).
                if let Some(i) = (0..rows_len).find(|&i| !above(row_norm(i), 1e-12)) {
                    let (what, item) = row_item(&rows[i]);
                    return Err(self.routing(
                        item,
                        format!(
                            "the structure matrix does not have full row rank: {what} is acted on by \
                             no tendon or motor (its row is zero), so nothing can balance it; route a \
                             tendon across it or add a motor on it"
                        ),
                    ));
                }
                // Rows that combine to (numerically) zero: the left singular vectors of the
                // vanishing singular values.
                let full = dm.clone().svd(true, false);
                let fsv = &full.singular_values;
                let involved: Vec<usize> = match &full.u {
                    Some(u) => (0..rows_len)
                        .filter(|&i| {
                            (0..fsv.len())
                                .any(|k| !above(fsv[k], 1e-10 * smax) && u[(i, k)].abs() > 1e-6)
                        })
                        .collect(),
                    None => Vec::new(),
                };
                match involved.as_slice() {
                    [i] => {
                        let (what, item) = row_item(&rows[*i]);
                        return Err(self.routing(
                            item,
                            format!(
                                "the structure matrix does not have full row rank (singular values \
                                 {values:?}): {what} is acted on so much more weakly than the others \
                                 (its row has norm {:.3e}, the matrix {smax:.3e}) that it is \
                                 numerically not acted on; check the sizes and units of the radii and \
                                 structure entries",
                                row_norm(*i)
                            ),
                        ));
                    }
                    [first, ..] => {
                        let names: Vec<String> =
                            involved.iter().map(|&i| row_item(&rows[i]).0).collect();
                        return Err(self.routing(
                            row_item(&rows[*first]).1,
                            format!(
                                "the structure matrix does not have full row rank (singular values \
                                 {values:?}): the balances of {} are not independent (every tendon \
                                 and motor acts on them in the same proportions), so they cannot be \
                                 driven separately; route a tendon over one of them with a different \
                                 radius or turn, or add a motor",
                                names.join(" and ")
                            ),
                        ));
                    }
                    [] => {}
                }
                return Err(self.routing(
                    &f.name,
                    format!(
                        "the structure matrix does not have full row rank (singular values {values:?}): \
                         some joint or driving pulley cannot be balanced independently of the others; \
                         route a tendon over it with a different radius or turn, or add a motor"
                    ),
                ));
            }
            let (pseudo_inverse, null_space) =
                crate::linalg::pseudo_inverse_and_null_space_of_rows(&e);
            // Only open-ended tendons may be redundant: motors and loop sides are determined.
            let is_tendon = |u: &Unknown| {
                matches!(u, Unknown::Explicit(_))
                    || matches!(u, Unknown::Strand(s) if tendons.iter().any(|t| t.strand == Some(*s)))
            };
            for v in &null_space {
                let scale = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                for (u, x) in unknowns.iter().zip(v) {
                    if !is_tendon(u) && x.abs() > 1e-9 * scale {
                        return Err(self.routing(
                            &item_of(u),
                            format!(
                                "{} is not determined by the dynamics (it can trade against the \
                                 tendons' tensions); a motor or loop must not share its joint with \
                                 redundant tendons this way",
                                what(u)
                            ),
                        ));
                    }
                }
            }
            let tendon_cols: Vec<usize> = (0..m).filter(|&c| is_tendon(&unknowns[c])).collect();
            let positive_null = if tendon_cols.is_empty() {
                None
            } else if null_space.is_empty() {
                return Err(self.routing(
                    &f.name,
                    "not controllable by tendons: as many tendon tensions as balances, so the \
                     dynamics fixes every tension and some must push; an open-ended routing needs at \
                     least one tendon more than it has joints to drive",
                ));
            } else if let Some(v) = positive_null_vector(&null_space, &tendon_cols) {
                Some(v)
            } else {
                // A balance that every tendon acting on it pulls the same way: the other unknowns
                // are fixed by the dynamics (checked above), so no taut tensions can meet it.
                let one_sided = (0..rows_len).find_map(|i| {
                    let scale = tendon_cols
                        .iter()
                        .fold(0.0f64, |a, &c| a.max(e[i][c].abs()));
                    let acting: Vec<usize> = tendon_cols
                        .iter()
                        .copied()
                        .filter(|&c| e[i][c].abs() > 1e-9 * scale)
                        .collect();
                    let sign = acting.first().map(|&c| e[i][c].signum())?;
                    acting
                        .iter()
                        .all(|&c| e[i][c].signum() == sign)
                        .then_some((i, sign, acting))
                });
                return Err(match one_sided {
                    Some((i, sign, acting)) => {
                        let (what, item) = row_item(&rows[i]);
                        let names: Vec<String> = acting
                            .iter()
                            .map(|&c| format!("`{}`", item_of(&unknowns[c])))
                            .collect();
                        self.routing(
                            item,
                            format!(
                                "not controllable by tendons: every tendon acting on {what} ({}) \
                                 pulls it the same way ({} generalized force per newton), so \
                                 balancing it needs one of them to push (the structure matrix has no \
                                 strictly positive null vector); reverse the turn of one of them \
                                 round it, or route another tendon round it the other way",
                                names.join(", "),
                                if sign > 0.0 { "positive" } else { "negative" }
                            ),
                        )
                    }
                    None => {
                        let other_cols: Vec<usize> =
                            (0..m).filter(|c| !tendon_cols.contains(c)).collect();
                        match one_sided_combination(&e, &tendon_cols, &other_cols) {
                            Some(y) => {
                                // Named at the balance that weighs most in the combination.
                                let lead = (0..rows_len).fold(0, |b, r| {
                                    if y[r].abs() > y[b].abs() {
                                        r
                                    } else {
                                        b
                                    }
                                });
                                let scale = y[lead].abs();
                                let combination: Vec<String> = (0..rows_len)
                                    .filter(|&r| y[r].abs() > 1e-9 * scale)
                                    .map(|r| {
                                        format!("{:+.3}·{}", y[r] / scale, row_item(&rows[r]).0)
                                    })
                                    .collect();
                                let force =
                                    |c: usize| (0..rows_len).map(|r| y[r] * e[r][c]).sum::<f64>();
                                let largest = tendon_cols
                                    .iter()
                                    .fold(0.0f64, |a, &c| a.max(force(c).abs()));
                                let (pulling, idle): (Vec<usize>, Vec<usize>) = tendon_cols
                                    .iter()
                                    .partition(|&&c| force(c) > 1e-9 * largest);
                                let names = |cols: &[usize]| {
                                    cols.iter()
                                        .map(|&c| format!("`{}`", item_of(&unknowns[c])))
                                        .collect::<Vec<_>>()
                                        .join(", ")
                                };
                                let idle = match idle.len() {
                                    0 => String::new(),
                                    1 => format!("; {} does not act on it", names(&idle)),
                                    _ => format!("; {} do not act on it", names(&idle)),
                                };
                                self.routing(
                                    row_item(&rows[lead]).1,
                                    format!(
                                        "not controllable by tendons: on the combination {} of \
                                         balances every tendon pulls the same way ({}{idle}), so \
                                         no taut tensions balance it in the other direction (the \
                                         structure matrix has no strictly positive null vector); \
                                         route a tendon that pulls the other way on it, e.g. \
                                         reverse the turn of one of them round {}",
                                        combination.join(" "),
                                        names(&pulling),
                                        row_item(&rows[lead]).0
                                    ),
                                )
                            }
                            None => self.routing(
                                &f.name,
                                "not controllable by tendons: no combination of tensions that \
                                 leaves every joint balanced keeps all tendons taut (the \
                                 structure matrix has no strictly positive null vector); reverse \
                                 the turn of a tendon on a joint where all tendons pull the same \
                                 way",
                            ),
                        }
                    }
                });
            };
            Ok(TensionSystem {
                unknowns,
                rows,
                matrix: e,
                pseudo_inverse,
                null_space,
                positive_null,
                condition: smax / smin,
            })
        };
        checked().map_err(|err| match err {
            Error::Routing {
                item, at, problem, ..
            } => Error::Routing {
                item,
                at,
                problem,
                implied: Some(Box::new(implied)),
            },
            other => other,
        })
    }
}

#[derive(Clone, Copy, Debug)]
enum Origin {
    Tendon(usize),
    Loop(usize),
}

/// Why no null vector of `E` is positive on the tendon columns, by Gordan's alternative: a
/// combination `y` of the balances with `yᵀE = 0` on the `other` columns (motors and loop
/// sides, which the dynamics fixes), `yᵀE ≥ 0` on the `tendons` and `Σ_tendons yᵀE = 1`.
/// Exactly one of the two exists; on `y`, every tendon pulls one way or not at all. Solved
/// as a linear program (simplex, `microlp`); `None` if it finds none (round-off at the edge
/// of controllability).
fn one_sided_combination(e: &[Vec<f64>], tendons: &[usize], other: &[usize]) -> Option<Vec<f64>> {
    use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome};
    let rows = e.len();
    let mut lp = Problem::new(OptimizationDirection::Minimize);
    let y: Vec<_> = (0..rows)
        .map(|_| lp.add_var(0.0, (f64::NEG_INFINITY, f64::INFINITY)))
        .collect();
    let column = |c: usize| -> Vec<_> { y.iter().zip(e).map(|(&v, row)| (v, row[c])).collect() };
    for &c in other {
        lp.add_constraint(column(c).as_slice(), ComparisonOp::Eq, 0.0);
    }
    for &c in tendons {
        lp.add_constraint(column(c).as_slice(), ComparisonOp::Ge, 0.0);
    }
    let total: Vec<_> = y
        .iter()
        .enumerate()
        .map(|(r, &v)| (v, tendons.iter().map(|&c| e[r][c]).sum::<f64>()))
        .collect();
    lp.add_constraint(total.as_slice(), ComparisonOp::Eq, 1.0);
    match lp.solve() {
        Ok(SolveOutcome::Solution(s)) => Some(y.iter().map(|&v| s.var_value(v)).collect()),
        _ => None,
    }
}

/// A null vector whose components on `cols` (the open-ended tendons) are all strictly
/// positive, scaled so that its smallest tendon component is 1; `None` if there is none.
///
/// Each tendon's row of the orthonormal null basis, normalised, is the direction in which
/// null-space coordinates `λ` lift that tendon. With one null direction the rows are `±1`
/// and their sum orients the line. With more, the linear program
/// `max s` over `λ ∈ [−1, 1]^d` with `r_k · λ ≥ s` for every tendon's row `r_k` (simplex,
/// `microlp`) finds the `λ` whose least lift, relative to each tendon's freedom, is
/// largest: exact and finite, so a thin cone of positive vectors (a controllable routing
/// with a small margin) is found as surely as a wide one. Either way the vector counts as
/// positive only when its least lift exceeds `1e-9 ‖λ‖`.
fn positive_null_vector(null: &[Vec<f64>], cols: &[usize]) -> Option<Vec<f64>> {
    let d = null.len();
    if d == 0 {
        return None;
    }
    // A row that is zero up to rounding means the dynamics fixes that tension: no null
    // vector can lift it, and normalising the rounding noise would only fake one.
    let mut rows: Vec<Vec<f64>> = Vec::with_capacity(cols.len());
    for &c in cols {
        let r: Vec<f64> = null.iter().map(|v| v[c]).collect();
        let nr = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        if nr <= 1e-9 {
            return None;
        }
        rows.push(r.iter().map(|x| x / nr).collect());
    }
    let lambda = if d == 1 {
        vec![rows.iter().map(|r| r[0]).sum::<f64>()]
    } else {
        largest_least_lift(&rows)?
    };
    let lift = |r: &Vec<f64>| r.iter().zip(&lambda).map(|(a, b)| a * b).sum::<f64>();
    let least = rows.iter().map(lift).fold(f64::INFINITY, f64::min);
    let lnorm = lambda.iter().map(|x| x * x).sum::<f64>().sqrt();
    let positive = least.is_finite() && least > 1e-9 * lnorm;
    if !positive {
        return None;
    }
    let v: Vec<f64> = (0..null[0].len())
        .map(|i| null.iter().zip(&lambda).map(|(b, l)| b[i] * l).sum())
        .collect();
    let min = cols.iter().map(|&c| v[c]).fold(f64::INFINITY, f64::min);
    Some(v.iter().map(|x| x / min).collect())
}

/// `argmax_λ min_k r_k · λ` over `λ ∈ [−1, 1]^d` (the box keeps the program bounded), as a
/// linear program in `(λ, s)`; `None` if the solver finds no optimum.
fn largest_least_lift(rows: &[Vec<f64>]) -> Option<Vec<f64>> {
    use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome};
    let d = rows.first()?.len();
    let mut lp = Problem::new(OptimizationDirection::Maximize);
    let lambda: Vec<_> = (0..d).map(|_| lp.add_var(0.0, (-1.0, 1.0))).collect();
    let s = lp.add_var(1.0, (f64::NEG_INFINITY, f64::INFINITY));
    for r in rows {
        let mut terms: Vec<_> = lambda.iter().zip(r).map(|(&v, &x)| (v, x)).collect();
        terms.push((s, -1.0));
        lp.add_constraint(terms.as_slice(), ComparisonOp::Ge, 0.0);
    }
    match lp.solve() {
        Ok(SolveOutcome::Solution(solution)) => {
            Some(lambda.iter().map(|&v| solution.var_value(v)).collect())
        }
        _ => None,
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

/// The range check of validation for the external wrench's point, for parameter values set
/// at run time (`mechanism` names the item, as in a file).
pub fn check_wrench_point(mechanism: &str, point: Vec3<f64>) -> Result<()> {
    match point.to_array().into_iter().find(|v| v.abs() > MAX_LENGTH) {
        None => Ok(()),
        Some(v) => Err(Error::Invalid {
            item: mechanism.to_string(),
            at: Location::default(),
            problem: format!(
                "the `point` of `external_wrench` has {} m, beyond the range of a length (at \
                 most {MAX_LENGTH:e} m in size; format.md §12, ranges of magnitude)",
                shown(v)
            ),
        }),
    }
}
