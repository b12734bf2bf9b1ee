//! The transmission as routed: the routes of tendons and loops, the couplings they derive
//! (a fixpoint), the strands, the tendons, loops and pulley roles, and the motors, in the
//! order of the tension system's unknowns. Invariant: every pulley's coupling is known and
//! agrees with any explicit one before a strand or role is built from it.

use super::locate::candidates;
use super::ranges::{shown, Range};
use super::Validator;
use crate::error::Result;
use crate::format::{MechanismFile, MotorSite, Objective, Turn};
use crate::model::{Body, BodyKind, Loop, Motor, MotorKind, PulleyRole, Tendon, Unknown};
use crate::transmission::{PulleyInfo, Rate, Route, RouteEnd, Routing, StrandGeometry};

/// What a route is the route of: a tendon, or one side of a loop (by file index).
#[derive(Clone, Copy, Debug)]
pub(super) enum Origin {
    Tendon(usize),
    Loop(usize),
}

/// What the coupling fixpoint hands on: each pulley's rotation and how the routes use it,
/// and each route's traced geometry.
pub(super) struct Couplings {
    /// Each pulley's rate of turning per joint rate (every one known once checked).
    pub(super) rates: Vec<Option<Rate>>,
    /// Whether a loop's side ends on the pulley (it is a loop's driving pulley).
    pub(super) routed_end: Vec<bool>,
    /// How many routes pass over the pulley after their anchor.
    pub(super) routed_through: Vec<usize>,
    /// Each route's geometry, taken by the strand it becomes.
    pub(super) geometry: Vec<Option<StrandGeometry>>,
    /// The routes in the order they were traced (a route once its start's coupling is known).
    pub(super) order: Vec<usize>,
}

/// The strands with the unknowns of the tension system, which the tendons and motors
/// extend.
pub(super) struct Strands {
    /// Each strand's name and geometry: the tendons' routes first, then the loops' sides.
    pub(super) list: Vec<(String, StrandGeometry)>,
    /// The strand each route became.
    pub(super) of_route: Vec<usize>,
    /// The unknowns, in their columns' order.
    pub(super) unknowns: Vec<Unknown>,
}

impl Strands {
    /// The routes' strands, each an unknown tension: the tendons' before the loops'.
    pub(super) fn of(routes: &[(Route, Origin)], geometry: &mut [Option<StrandGeometry>]) -> Self {
        let mut strands = Vec::new();
        let mut unknowns = Vec::new();
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
        Strands {
            list: strands,
            of_route: strand_of_route,
            unknowns,
        }
    }
}

impl Validator<'_> {
    /// The route of each routed tendon, then the two sides of each loop.
    pub(super) fn routes(&self, f: &MechanismFile) -> Result<Vec<(Route, Origin)>> {
        let pulley_index = |name: &str| f.pulleys.iter().position(|p| p.name == name);
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
                        shown(l.pretension)
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
        Ok(routes)
    }

    /// Every pulley's coupling, and the routes traced, with the checks of each pulley's
    /// role: fixed drums and explicit rows are known; routes derive the rest, each route once
    /// the coupling of the body it starts from is known.
    pub(super) fn couplings(
        &self,
        f: &MechanismFile,
        bodies: &[Body<f64>],
        pulleys: &[PulleyInfo],
        routes: &[(Route, Origin)],
    ) -> Result<Couplings> {
        let n = f.links.len();
        let routing = Routing {
            bodies,
            pulleys,
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
        let mut order = Vec::new();
        loop {
            let mut progressed = false;
            for (i, (route, _)) in routes.iter().enumerate() {
                let start = route.wraps[0].0;
                if geometry[i].is_some() || couplings[start].is_none() {
                    continue;
                }
                geometry[i] = Some(routing.trace(route, &mut couplings, routed_end[start])?);
                order.push(i);
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
        Ok(Couplings {
            rates: couplings,
            routed_end,
            routed_through,
            geometry,
            order,
        })
    }

    /// Each tendon, with its floor, maximum and structure column (from its route or given);
    /// a tendon without a route adds its own unknown.
    pub(super) fn tendons(
        &self,
        f: &MechanismFile,
        floor_default: f64,
        routes: &[(Route, Origin)],
        strands: &mut Strands,
    ) -> Result<Vec<Tendon>> {
        let n = f.links.len();
        let Strands {
            list: strands,
            of_route: strand_of_route,
            unknowns,
        } = strands;
        let mut tendons = Vec::new();
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
                            "`floor` is {} N; the tension floor must not be negative (a tendon \
                             cannot push)",
                            shown(floor)
                        ),
                    ),
                    None => self.invalid_at_key(
                        &f.name,
                        "tension_floor",
                        format!(
                            "`tension_floor` is {} N; the tension floor must not be negative \
                             (a tendon cannot push)",
                            shown(floor)
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
                        format!(
                            "max_tension {} N is below its floor {} N",
                            shown(mx),
                            shown(floor)
                        ),
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
        Ok(tendons)
    }

    /// Each motor, with its column, each an unknown torque after the tensions.
    pub(super) fn motors(
        &self,
        f: &MechanismFile,
        bodies: &[Body<f64>],
        pulleys: &[PulleyInfo],
        unknowns: &mut Vec<Unknown>,
    ) -> Result<Vec<Motor>> {
        let n = f.links.len();
        let link_index = |name: &str| f.links.iter().position(|l| l.name == name);
        let pulley_index = |name: &str| f.pulleys.iter().position(|p| p.name == name);
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
        Ok(motors)
    }
}

/// Each loop with the strands of its two sides and the bodies of its pulleys.
pub(super) fn loops(
    f: &MechanismFile,
    routes: &[(Route, Origin)],
    strand_of_route: &[usize],
    pulleys: &[PulleyInfo],
) -> Vec<Loop> {
    let pulley_index = |name: &str| f.pulleys.iter().position(|p| p.name == name);
    let mut loops = Vec::new();
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
    loops
}

/// Stores the couplings and roles on the pulley bodies.
pub(super) fn pulley_roles(
    bodies: &mut [Body<f64>],
    pulleys: &[PulleyInfo],
    couplings: &Couplings,
    routes: &[(Route, Origin)],
    strand_of_route: &[usize],
) {
    let Couplings {
        rates: couplings,
        routed_end,
        routed_through,
        ..
    } = couplings;
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
}
