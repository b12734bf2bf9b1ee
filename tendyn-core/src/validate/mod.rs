//! RON file → validated [`Model`], or an error that names the item, its line and what
//! would fix it. Nothing is returned unless every check passes.

mod bodies;
mod locate;
mod parameters;
mod ranges;
mod tension_system;

use crate::error::{Error, Location, Result};
use crate::format::{FrictionSpec, MechanismFile, MotorSite, Objective, Turn};
use crate::model::{
    BearingFriction, BodyKind, Loop, Model, Motor, MotorKind, Parameter, PulleyRole, Strand,
    Tendon, Unknown, Wrench,
};
use crate::spatial::{Mat3, Vec3};
use crate::transmission::{Rate, Route, RouteEnd, Routing, StrandGeometry};
pub use bodies::dh_post;
use bodies::MassProperties;
use locate::{candidates, syntax_error, NameIndex};
use parameters::parameter_slots;
use ranges::{beyond, shown, Range};
pub use ranges::{
    MAX_ACCELERATION, MAX_ANGLE, MAX_FORCE, MAX_FRICTION_TORQUE, MAX_INERTIA, MAX_LENGTH, MAX_MASS,
    MAX_MOMENT, MAX_RATIO, MAX_SMOOTHING, MAX_VISCOUS, MIN_RADIUS, MIN_SMOOTHING,
};
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

        let actuators = Actuators {
            strands,
            tendons,
            loops,
            motors,
        };
        let system = self.tension_system(f, &bodies, &actuators, unknowns)?;
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
}

#[derive(Clone, Copy, Debug)]
enum Origin {
    Tendon(usize),
    Loop(usize),
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
