//! The tension system `E x = b` (paper Eqs. 33, 35): `E` built column by column from the
//! strands, tendons and motors, its rank diagnosed by the SVD, `E⁺`, `null(E)` and a
//! strictly positive null vector. Invariant: a system is returned only with `E` of full
//! row rank, every motor and loop side determined, and the tendons kept taut by a strictly
//! positive null vector when the routing has open-ended tendons (with capstan friction,
//! whichever way the tendons slide, or, where the file sets `accept_sampled_sliding`, at
//! the sampled ways validation could check: [`sliding_directions`]); a failing routing is
//! reported with the system it implies.

use super::Validator;
use crate::error::{Error, ImpliedSystem, Result};
use crate::format::MechanismFile;
use crate::model::{
    Body, BodyKind, Loop, Model, Motor, PulleyRole, Row, SlidingCheck, Tendon, TensionSystem,
    Unknown,
};
use crate::transmission::{tension_matrix, Columns, PulleyInfo, Rate, StrandGeometry};
use nalgebra::DMatrix;

mod factor_boxes;
mod sign_pattern;
mod slack_tendon;

/// What the tension system's unknowns belong to.
pub(super) struct Actuators {
    /// Each strand's name and geometry: the tendons' routes first, then the loops' sides.
    pub(super) strands: Vec<(String, StrandGeometry)>,
    pub(super) tendons: Vec<Tendon>,
    pub(super) loops: Vec<Loop>,
    pub(super) motors: Vec<Motor>,
}

impl Validator<'_> {
    /// `E`, checked: the balances of the joints, the driving pulleys and the loops'
    /// pretensions (rows) against the unknowns (columns).
    pub(super) fn tension_system(
        &self,
        f: &MechanismFile,
        bodies: &[Body<f64>],
        pulleys: &[PulleyInfo],
        actuators: &Actuators,
        unknowns: Vec<Unknown>,
    ) -> Result<TensionSystem<f64>> {
        let n = f.links.len();
        let Actuators {
            strands,
            tendons,
            loops,
            motors,
        } = actuators;
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
        let m = unknowns.len();
        let pull_rates: Vec<Rate> = strands.iter().map(|(_, g)| g.pull_rate.clone()).collect();
        let columns = Columns {
            pull_rates: &pull_rates,
            pulleys,
            bodies,
            tendons,
            loops,
            motors,
        };
        let e = tension_matrix(&rows, &unknowns, &columns);
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
                if let Some(c) = undetermined(v, |c| is_tendon(&unknowns[c])) {
                    let u = &unknowns[c];
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
                eliminated: None,
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

/// `x > y`, false when either is NaN (so that `!above(…)` flags NaN as well).
fn above(x: f64, y: f64) -> bool {
    x.partial_cmp(&y) == Some(std::cmp::Ordering::Greater)
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

/// Whether some `x` meets `lower ≤ a · x ≤ upper` for every row `(a, lower, upper)` (a
/// linear program, `microlp`); true without rows.
fn feasible(rows: &[(Vec<f64>, f64, f64)]) -> bool {
    use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome};
    let Some(n) = rows.first().map(|r| r.0.len()) else {
        return true;
    };
    let mut lp = Problem::new(OptimizationDirection::Minimize);
    let x: Vec<_> = (0..n)
        .map(|_| lp.add_var(0.0, (f64::NEG_INFINITY, f64::INFINITY)))
        .collect();
    for (a, lower, upper) in rows {
        let terms: Vec<_> = x.iter().zip(a).map(|(&v, &c)| (v, c)).collect();
        if lower.is_finite() {
            lp.add_constraint(terms.as_slice(), ComparisonOp::Ge, *lower);
        }
        if upper.is_finite() {
            lp.add_constraint(terms.as_slice(), ComparisonOp::Le, *upper);
        }
    }
    matches!(lp.solve(), Ok(SolveOutcome::Solution(_)))
}

/// A guide with friction over which something slides: its strand and idler, its class
/// (guides whose speeds are equal or opposite: they slide and rest together), the sign
/// relating its speed to its group's, and its largest wrap angle over the joints' ranges
/// ([`crate::model::Guide::wrap_over`]).
struct Slider {
    strand: usize,
    idler: usize,
    class: usize,
    sign: f64,
    wrap: f64,
    /// Its capstan factor takes values between rest and sliding: with the smoothed law, or
    /// with a wrap angle that changes with `q`.
    variable: bool,
}

/// Guides whose sliding speeds are equal or opposite: `|v| = speed |u_g · q̇|`, `u_g` the
/// speed of their group (guides whose speeds are proportional) per joint velocity.
struct Class {
    group: usize,
    speed: f64,
}

/// The most systems for which every way the guides can move is checked (`3⁸ · 2²`: eight
/// classes, or four with two guides whose factor varies, …); beyond, those where every
/// guide slides.
const EVERY_WAY_UP_TO: usize = 26_244;

/// The most guides whose wrap angle varies over a box of joint angles that
/// [`Sliding::state_that_fails`] takes at every combination of their ends (`2¹⁰`).
const ENDS_UP_TO: usize = 10;

/// The most boxes of joint angles [`Sliding::state_that_fails`] searches before it gives
/// up finding the state where a routing fails, and refuses it all the same.
const UNSETTLED_AFTER: usize = 4096;

/// The most boxes of capstan factors tried where the points are every way
/// ([`factor_boxes::every_factor`]), which then settle what the boxes leave.
const BOXES_BEFORE_EVERY_WAY: usize = 64;

/// With capstan friction on guides `E` depends on the direction each tendon slides over
/// its guides: the routing must be controllable (full row rank, a null vector that lifts
/// every tendon, motors and loop sides determined) for every direction it can take. Boxes
/// of capstan factors may show that for every factor the guides can take at once
/// ([`every_factor_lifts`] with one null direction, [`every_factor_held`] with more); what
/// they leave, the systems taken at the points [`Sliding::points`] gives settle, each
/// guide at its largest wrap angle over the joints' ranges (at `q = 0` where a joint has
/// none), and a failing point refuses the routing only if some motion produces it
/// ([`Sliding::reachable`]) and, over ranges, at a state ([`Sliding::state_that_fails`]).
///
/// With one null direction each tendon's component of the null vector, as the signed
/// maximal minor of `E` without that tendon's column, must keep the sign it has without
/// friction while the motors' and loop sides' stay zero ([`Minors::compare`]); with more,
/// the state's system is solved and checked as the model's was.
///
/// Up to [`EVERY_WAY_UP_TO`] points, they are every way the exact law moves the guides,
/// and, for guides whose capstan factor varies, each also at rest. That covers every state
/// in between as well: a strand's column is `Σ_k f_k shares[k]` with each `f_k` a product
/// of distinct capstan factors (`tension::state_matrix`), and each pass of a strand over
/// a guide has its own factor, so every minor is affine in each factor `w = e^{−σμβ}`
/// taken alone. On the box of factors between rest (`w = 1`) and a pattern's directions,
/// such a function is a convex combination of its values at the box's corners, which are
/// the points where any subset of the varying guides is at rest: the smoothed law's
/// `|σ| < 1`, and every state whose wrap angles are no larger than those taken, lie in
/// such boxes. With no null direction or two or more, where such states occur, a fixed
/// basis carries the points' systems between them ([`held_between`]; past 26,244 choices
/// of free tendons, where one a pivoted QR picks holds), or `E`'s signs show every factor
/// ([`sign_pattern`]).
///
/// Beyond, the points are a sample of those where every guide slides (each group one way,
/// all the ways of up to 12 groups, past that the two where every group slides one way and
/// those with one group flipped), to which, with one null direction, a descent from them
/// adds a pattern that fails if it finds one ([`least_lifting_way`]), unless `E`'s signs
/// show a routing of open-ended tendons alone controllable at every factor
/// ([`sign_pattern`]), whatever the friction: the points then check that floating point
/// still resolves the tensions it needs. Returns how far the routing was shown
/// controllable.
///
/// Where it could show the routing only at sampled states (`AllSliding`, or
/// `EveryWayNotBetween`), the routing is refused unless `accept_sampled` (the file's
/// `accept_sampled_sliding`).
pub(super) fn sliding_directions(
    v: &Validator,
    model: &Model<f64>,
    accept_sampled: bool,
) -> Result<SlidingCheck> {
    let sliding = Sliding::of(model);
    if sliding.sliders.is_empty() {
        return Ok(SlidingCheck::Constant);
    }
    let tendons: Vec<usize> = model.tendons.iter().map(|t| t.unknown).collect();
    let frictionless =
        (model.system.null_space.len() == 1).then(|| Minors::of(&model.system.matrix, &tendons));
    let (mut points, every_way) = sliding.points_and_whether_every_way();
    let fails = |e: Vec<Vec<f64>>| -> Option<String> {
        match &frictionless {
            Some(without) => without.compare(&without.at(&e), &tendons).err(),
            None => match crate::tension::system_at(model, e) {
                Ok(system) => lifts_every_tendon(&system.null_space, &tendons).err(),
                Err(Error::Tension(why)) => Some(why),
                Err(other) => Some(other.to_string()),
            },
        }
    };
    // Boxes of factors first: one box often settles every state at once. Where the points
    // are every way, they settle what the boxes leave, so few boxes are tried.
    let budget = if every_way {
        BOXES_BEFORE_EVERY_WAY
    } else {
        UNSETTLED_AFTER
    };
    // A routing of open-ended tendons may be shown at every factor by E's signs alone,
    // whatever the friction. Past the points every way that takes the boxes' place, and
    // the points where every guide slides then check that floating point still resolves
    // the tensions it needs there; up to them, it carries their systems between them.
    let runs = factor_boxes::Columns::of(model, &sliding);
    let by_signs = sign_pattern::controllable_at_every_factor(model, &runs);
    let shown = match (!every_way && by_signs, &frictionless) {
        (true, _) => None,
        (false, Some(_)) => every_factor_lifts(model, &sliding, &runs, &tendons, &fails, budget),
        (false, None) => {
            every_factor_held(model, &sliding, &runs, &points, &tendons, &fails, budget)
        }
    };
    if let Some(boxes) = shown {
        return Ok(SlidingCheck::EveryFactor { boxes });
    }
    // Past the points every way, those where every guide slides are a sample: a search
    // among the others may find one that fails, which then refuses as any point does.
    if let (false, false, Some(minors)) = (every_way, by_signs, &frictionless) {
        if let Some(point) = least_lifting_way(model, &sliding, minors, &tendons, &points) {
            points.insert(0, point);
        }
    }
    let ranged = sliding.ranged(model);
    for point in &points {
        // Over the joints' ranges each guide's wrap angle lies in an interval, which guides
        // on one joint may not span together: the boxes of joint angles are searched for a
        // state ([`Sliding::state_that_fails`]).
        let failure = if ranged {
            sliding.state_that_fails(model, point, &fails)
        } else {
            fails(sliding.matrix(model, point)).map(|why| (Some(vec![0.0; model.dof]), why))
        };
        let Some((state, why)) = failure else {
            continue;
        };
        // A point no motion produces (groups whose speeds are tied by the joints they
        // share) cannot fail in use: only a reachable one refuses (over ranges, the
        // search has asked already).
        if !ranged && !sliding.reachable(point) {
            continue;
        }
        let described = sliding.described(model, &sliding.sigma(model, point));
        let at = match &state {
            Some(q) if q.iter().all(|&x| x == 0.0) => "(at q = 0)".to_string(),
            Some(q) => format!("(at q = {q:?} rad)"),
            None => "within the joints' ranges".to_string(),
        };
        let problem = match (by_signs, state) {
            // Controllable in exact arithmetic: what fails is floating point.
            (true, _) => format!(
                "with capstan friction the routing must be controllable whichever way the \
                 tendons slide; E's signs show it is, in exact arithmetic, but sliding \
                 {described} {at} the tensions that would keep every tendon taut differ by \
                 capstan factors up to e^{:.1} along one tendon, more than floating point \
                 resolves; lower `mu`",
                sliding.largest_exponent(model)
            ),
            (false, Some(_)) => format!(
                "with capstan friction the routing must be controllable whichever way the \
                 tendons slide, but sliding {described} {at} it is not: {why}; lower `mu` or \
                 route the tendon differently"
            ),
            (false, None) => format!(
                "with capstan friction the routing must be controllable whichever way the \
                 tendons slide, and validation could not show it is sliding {described} \
                 {at}: {why}; narrow the ranges, lower `mu` or route the tendon differently"
            ),
        };
        return Err(v.routing(&sliding.first_guide(model), problem));
    }
    // Between the points: with one null direction the minors settle it; with none or
    // more, a fixed basis does where some state lies between them.
    let between = sliding.sliders.iter().any(|s| s.variable);
    let d = model.system.null_space.len();
    let mut between_shown = true;
    if d != 1 && between && every_way && !by_signs {
        match held_between(model, &sliding, &points, &tendons) {
            Ok(shown) => between_shown = shown,
            Err(point) => return Err(not_held_between(v, model, &sliding, point)),
        }
    }
    let (systems, groups) = (points.len(), sliding.groups.len());
    let sampled = match (every_way, by_signs) {
        (true, _) if !between_shown => format!(
            "with capstan friction and {}, the routing must stay controllable between rest \
             and every direction of sliding; validation showed it at every way the guides \
             slide and rest ({systems} tension systems) but not at the states between: with \
             a {d}-dimensional null space there are too many choices of free tendons to take \
             one by one, and none of those a pivoted QR picks keeps the others taut in one \
             proportion at every way",
            sliding.between_comes_from()
        ),
        (true, _) => return Ok(SlidingCheck::EveryWay { systems }),
        (false, true) => return Ok(SlidingCheck::EveryFactor { boxes: 1 }),
        (false, false) => format!(
            "with capstan friction the routing must be controllable whichever way the \
             tendons slide; with {groups} groups of guides there are too many ways to take \
             one by one, neither boxes of factors nor E's signs settled it, and validation \
             checked only {}, none of which fails",
            if groups <= 12 {
                format!(
                    "the {systems} ways where every guide slides, each group one way (not \
                     those where some rest)"
                )
            } else {
                format!(
                    "{systems} of the ways every guide slides (the two where every group \
                     slides one way, those with one group flipped{})",
                    if d == 1 {
                        ", and those a search for a failing one passed"
                    } else {
                        ""
                    }
                )
            }
        ),
    };
    if !accept_sampled {
        return Err(v.routing(
            &sliding.first_guide(model),
            format!(
                "{sampled}; lower `mu` or route the tendons differently, or set the \
                 top-level field `accept_sampled_sliding: true` to accept it, inverse and \
                 forward dynamics then refusing any state that fails"
            ),
        ));
    }
    Ok(if every_way {
        SlidingCheck::EveryWayNotBetween { systems }
    } else {
        SlidingCheck::AllSliding { systems }
    })
}

/// The refusal where no fixed basis carries the points' systems between them
/// ([`held_between`]), at a reachable `point` where the last choice that held at rest
/// fails, if there is one.
fn not_held_between(
    v: &Validator,
    model: &Model<f64>,
    sliding: &Sliding,
    point: Option<Vec<f64>>,
) -> Error {
    let d = model.system.null_space.len();
    let blocked = match point {
        Some(point) => format!(
            "up to sliding {} ({})",
            sliding.described(model, &sliding.sigma(model, &point)),
            sliding.wraps_checked(model)
        ),
        None => "in one proportion for every direction of sliding".into(),
    };
    v.routing(
        &sliding.first_guide(model),
        format!(
            "with capstan friction and {}, the routing must stay controllable between rest \
             and every direction of sliding; with a {d}-dimensional null space validation \
             shows that by {d} tendons whose tensions, in one proportion for every state, \
             keep the others taut and the motors and loop sides determined, and no {d} \
             tendons do {blocked}; lower `mu` or route the tendons differently",
            sliding.between_comes_from(),
        ),
    )
}

/// The most steps [`least_lifting_way`] takes per group of guides.
const STEPS_PER_GROUP: usize = 4;

/// With one null direction, a way every guide slides (each group one way, some motion
/// producing it: [`Sliding::slides_every_guide`]) at which the tendons' least lift
/// ([`Minors::least_lift`], each guide at its largest wrap angle) falls to validation's
/// margin, if a descent finds one: from the lowest of the `sampled` ways some motion
/// produces, flip the group whose flip lowers the least lift most among those some motion
/// still produces, while it falls. A sufficient search, not an exhaustive one: where it
/// finds none the routing is still checked only at the sampled ways.
fn least_lifting_way(
    model: &Model<f64>,
    sliding: &Sliding,
    minors: &Minors,
    tendons: &[usize],
    sampled: &[Vec<f64>],
) -> Option<Vec<f64>> {
    let groups = sliding.groups.len();
    let point = |by_group: &[f64]| -> Vec<f64> {
        (sliding.sliders.iter())
            .map(|s| by_group[sliding.classes[s.class].group])
            .collect()
    };
    let lift = |by_group: &[f64]| {
        let e = sliding.matrix(model, &point(by_group));
        minors.least_lift(&minors.at(&e), tendons)
    };
    let by_group = |p: &Vec<f64>| -> Vec<f64> {
        let mut g = vec![0.0; groups];
        for (s, &way) in sliding.sliders.iter().zip(p) {
            g[sliding.classes[s.class].group] = way;
        }
        g
    };
    let mut starts: Vec<(f64, Vec<f64>)> = (sampled.iter())
        .map(by_group)
        .map(|g| (lift(&g), g))
        .collect();
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut least, mut way) = starts
        .into_iter()
        .find(|(_, g)| sliding.slides_every_guide(&point(g)))?;
    for _ in 0..STEPS_PER_GROUP * groups {
        if least <= LIFT_MARGIN {
            return Some(point(&way));
        }
        let mut flips: Vec<(f64, usize)> = (0..groups)
            .map(|i| {
                way[i] = -way[i];
                let l = lift(&way);
                way[i] = -way[i];
                (l, i)
            })
            .filter(|&(l, _)| l < least)
            .collect();
        flips.sort_by(|a, b| a.0.total_cmp(&b.0));
        let produced = flips.into_iter().find(|&(_, i)| {
            way[i] = -way[i];
            let moves = sliding.slides_every_guide(&point(&way));
            way[i] = -way[i];
            moves
        });
        let (l, i) = produced?;
        way[i] = -way[i];
        least = l;
    }
    None
}

/// With one null direction, the number of boxes of capstan factors on which every factor
/// the guides can take is shown to keep each tendon's minor the sign it has without
/// friction ([`factor_boxes::every_factor`]), or 1 where no factor of the whole box lets a
/// tendon go slack ([`slack_tendon::never_slack`]), while the motors' and loop sides'
/// vanish with the pattern of `E` ([`factor_boxes::Columns::always_singular`]); `None`
/// where that is not shown.
fn every_factor_lifts(
    model: &Model<f64>,
    sliding: &Sliding,
    runs: &factor_boxes::Columns,
    tendons: &[usize],
    fails: &dyn Fn(Vec<Vec<f64>>) -> Option<String>,
    budget: usize,
) -> Option<usize> {
    let rows: Vec<usize> = (0..model.system.matrix.len()).collect();
    let columns = model.system.matrix.first().map_or(0, Vec::len);
    let without = |k: usize| {
        let kept: Vec<usize> = (0..columns).filter(|&c| c != k).collect();
        factor_boxes::Square::of(&rows, &kept)
    };
    let determined = (0..columns)
        .filter(|k| !tendons.contains(k))
        .all(|k| runs.always_singular(&without(k)));
    if !determined {
        return None;
    }
    let squares: Vec<factor_boxes::Square> = tendons.iter().map(|&k| without(k)).collect();
    // A few boxes settle most routings and cost a factorisation per tendon each; the
    // slack-tendon programs settle nearly all the rest, long tendons over many guides
    // whose factors multiply up included; more boxes take what the programs' tolerance
    // leaves.
    let boxes = |budget| factor_boxes::every_factor(model, sliding, runs, &squares, fails, budget);
    if let Ok(few) = boxes(FIRST_BOXES) {
        return Some(few);
    }
    if slack_tendon::never_slack(model, sliding, runs, tendons, &[]).is_ok() {
        return Some(1);
    }
    boxes(budget).ok()
}

/// With two or more null directions, the number of boxes of capstan factors on which
/// every factor the guides can take is shown to keep `E` controllable
/// ([`factor_boxes::every_factor`]), or 1 where the slack-tendon programs show it on the
/// whole box ([`slack_tendon::never_slack`]); `None` where neither does. With `d`, a
/// fixed basis as [`held_between`] takes it: `d` free tendons `N` in one proportion `x_N`
/// (from rest and the `points`), the others `B` solved from `E_B x_B = −E_N x_N`. By
/// Cramer `x_B,i det E_B = det(E_B with column i replaced by −E_N x_N)`, so where `det E_B`
/// and each such determinant of a tendon's keep their signs (checked positive at each
/// box's centre), every tendon stays taut; the motors' and loop sides' components of every
/// null vector, `det(E_B with their column replaced by one of N's) / det E_B`, must vanish
/// by `E`'s pattern ([`factor_boxes::Columns::always_singular`]).
///
/// The first [`BASES_TRIED`] choices of `N` that hold at rest and at the points are
/// tried, first each on [`FIRST_BOXES`] boxes and by the programs, which may add up to
/// [`CUTS`] factors they find loosening a tendon to the systems the proportion is chosen
/// from (cutting planes); then each on at most a quarter of `budget` boxes and all on at
/// most `budget`. Past [`EVERY_WAY_UP_TO`] choices, those of [`pivoted_free_tendons`],
/// on the first boxes and the programs only.
fn every_factor_held(
    model: &Model<f64>,
    sliding: &Sliding,
    runs: &factor_boxes::Columns,
    points: &[Vec<f64>],
    tendons: &[usize],
    fails: &dyn Fn(Vec<Vec<f64>>) -> Option<String>,
    budget: usize,
) -> Option<usize> {
    let d = model.system.null_space.len();
    let rows: Vec<usize> = (0..model.system.matrix.len()).collect();
    let columns = model.system.matrix.first().map_or(0, Vec::len);
    // Guides are only ever on open-ended tendons, which validation keeps with a null
    // direction at least: none is not met here.
    if d == 0 {
        return None;
    }
    // Every choice of free tendons while they are few; past that, the one a column-pivoted
    // QR of the tendons' columns leaves last (the others are the most independent: a well
    // conditioned `E_B`), then each with one free tendon swapped for a basic one.
    let pivoted = choose(tendons.len(), d) > EVERY_WAY_UP_TO;
    let choices = match pivoted {
        false => combinations(tendons, d),
        true => pivoted_free_tendons(&model.system.matrix, tendons, d),
    };
    let matrices: Vec<Vec<Vec<f64>>> = points.iter().map(|p| sliding.matrix(model, p)).collect();
    // A fixed basis: free tendons, the other columns, `det E_B`'s sign at rest, and the
    // proportion of the free tendons.
    struct Held {
        free: Vec<usize>,
        basic: Vec<usize>,
        sign: f64,
        x: Vec<f64>,
    }
    let replaced = |basic: &[usize], i: usize, by: Vec<(usize, f64)>| {
        let mut square = factor_boxes::Square::of(&rows, basic);
        square.columns[i] = by;
        square
    };
    // The boxes: `det E_B`, and each tendon's with its column replaced by the free
    // tendons' pull; at each box's centre the basis as at rest and every tendon taut in the
    // proportion (the determinants' signs then hold on the box).
    let boxes = |h: &Held, share: usize| {
        let pulled: Vec<(usize, f64)> = h.free.iter().zip(&h.x).map(|(&n, &x)| (n, -x)).collect();
        let mut squares = vec![factor_boxes::Square::of(&rows, &h.basic)];
        squares.extend(
            (0..h.basic.len())
                .filter(|&i| tendons.contains(&h.basic[i]))
                .map(|i| replaced(&h.basic, i, pulled.clone())),
        );
        let taut = |e: Vec<Vec<f64>>| -> Option<String> {
            let Some((_, held)) = basis(&e, &h.basic, &h.free, tendons, Some(h.sign)) else {
                return Some("the fixed basis turns singular or moves a motor".into());
            };
            let tension = |a: &Vec<f64>| a.iter().zip(&h.x).map(|(a, x)| a * x).sum::<f64>();
            if held.iter().any(|a| tension(a) <= 1e-9) {
                return Some("the fixed proportion loosens a tendon".into());
            }
            fails(e)
        };
        factor_boxes::every_factor(model, sliding, runs, &squares, &taut, share)
    };
    let mut candidates: Vec<Held> = Vec::new();
    for free in choices {
        let basic: Vec<usize> = (0..columns).filter(|c| !free.contains(c)).collect();
        let Some((sign, mut held)) = basis(&model.system.matrix, &basic, &free, tendons, None)
        else {
            continue;
        };
        let at_points: Option<Vec<_>> = (matrices.iter())
            .map(|e| basis(e, &basic, &free, tendons, Some(sign)).map(|b| b.1))
            .collect();
        let Some(at_points) = at_points else {
            continue;
        };
        held.extend(at_points.into_iter().flatten());
        let Some(x) = proportion(&held, d) else {
            continue;
        };
        let determined = (0..basic.len())
            .filter(|&i| !tendons.contains(&basic[i]))
            .all(|i| {
                (free.iter()).all(|&n| runs.always_singular(&replaced(&basic, i, vec![(n, 1.0)])))
            });
        if !determined {
            continue;
        }
        let mut choice = Held {
            free,
            basic,
            sign,
            x,
        };
        if let Ok(few) = boxes(&choice, FIRST_BOXES) {
            return Some(few);
        }
        // Cutting planes: where a program finds a factor at which this proportion loosens
        // a tendon, that factor's system joins those the proportion is chosen from.
        for _ in 0..CUTS {
            let x_free: Vec<(usize, f64)> = (choice.free.iter().copied())
                .zip(choice.x.iter().copied())
                .collect();
            let lambda = match slack_tendon::never_slack(model, sliding, runs, tendons, &x_free) {
                Ok(()) => return Some(1),
                Err(None) => break,
                Err(Some(lambda)) => lambda,
            };
            let e = sliding.matrix_with_factors(model, &lambda);
            let Some((_, loosened)) = basis(&e, &choice.basic, &choice.free, tendons, Some(sign))
            else {
                break;
            };
            held.extend(loosened);
            let Some(better) = proportion(&held, d) else {
                break;
            };
            choice.x = better;
        }
        candidates.push(choice);
        if candidates.len() == BASES_TRIED {
            break;
        }
    }
    // Past the choices taken one by one, the pivoted ones are not given the boxes' budget:
    // they are more, and larger, and what the programs leave the boxes rarely settle.
    if pivoted {
        return None;
    }
    let mut left = budget;
    for held in &candidates {
        match boxes(held, left.min(budget / 4)) {
            Ok(boxes) => return Some(boxes),
            Err(taken) => left -= taken.min(left),
        }
        if left == 0 {
            break;
        }
    }
    None
}

/// The `d` free tendons a column-pivoted QR of `E`'s tendon columns picks last, then each
/// set with one of them swapped for one of the others: `1 + d (K − d)` choices of `K`
/// tendons, each increasing.
fn pivoted_free_tendons(e: &[Vec<f64>], tendons: &[usize], d: usize) -> Vec<Vec<usize>> {
    let m = DMatrix::from_fn(e.len(), tendons.len(), |i, j| e[i][tendons[j]]);
    let mut order = DMatrix::from_fn(1, tendons.len(), |_, j| j as f64);
    m.col_piv_qr().p().permute_columns(&mut order);
    let pivoted: Vec<usize> = order.iter().map(|&j| tendons[j as usize]).collect();
    let (basic, free) = pivoted.split_at(tendons.len() - d);
    let sorted = |mut set: Vec<usize>| {
        set.sort_unstable();
        set
    };
    let mut choices = vec![sorted(free.to_vec())];
    for &b in basic.iter().rev() {
        for f in 0..d {
            let mut swapped = free.to_vec();
            swapped[f] = b;
            choices.push(sorted(swapped));
        }
    }
    choices
}

/// The most choices of free tendons [`every_factor_held`] tries on boxes of factors.
const BASES_TRIED: usize = 16;

/// The boxes of factors tried before the slack-tendon programs (for each choice of free
/// tendons): enough for a routing a few guides fixed at their ends settle, which costs
/// less than the programs.
const FIRST_BOXES: usize = 8;

/// The most factors the slack-tendon programs may add, for one choice of free tendons, to
/// the systems its proportion is chosen from ([`every_factor_held`]).
const CUTS: usize = 8;

/// The first column of null vector `v` that is not a tendon's (a motor torque or loop side)
/// and that `v` moves beyond round-off (`1e-9` of its largest component): one the dynamics
/// does not determine.
fn undetermined(v: &[f64], tendon: impl Fn(usize) -> bool) -> Option<usize> {
    let scale = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    (0..v.len()).find(|&c| !tendon(c) && v[c].abs() > 1e-9 * scale)
}

/// What `tension::system_at` leaves unchecked with two or more null directions (it checks
/// the rank; with one, the null vector's signs): that the state's null space still leaves
/// the motors and loop sides determined and holds a vector that lifts every tendon
/// ([`positive_null_vector`], as for the model's `E`). Without open-ended tendons, or
/// without a null direction, there is nothing to lift.
fn lifts_every_tendon(
    null_space: &[Vec<f64>],
    tendons: &[usize],
) -> std::result::Result<(), String> {
    if null_space.len() < 2 || tendons.is_empty() {
        return Ok(());
    }
    for v in null_space {
        if undetermined(v, |c| tendons.contains(&c)).is_some() {
            return Err(
                "at this state the guides' friction lets a motor torque or loop side \
                 trade against the tendons' tensions: the dynamics no longer determines it"
                    .into(),
            );
        }
    }
    match positive_null_vector(null_space, tendons) {
        Some(_) => Ok(()),
        None => Err(
            "at this state the guides' friction leaves no tensions that raise every \
             tendon together (no null vector of the tension system lifts them all): the \
             routing is not controllable in this direction of sliding"
                .into(),
        ),
    }
}

/// With no null direction or two or more, the state's system is checked at the points
/// alone, and the minors of one null direction do not settle the states between them (the
/// smoothed law's `|σ| < 1`, wrap angles smaller than those taken). A fixed basis does: `d`
/// tendons `N` whose tensions `x_N > 0` are held in one proportion, the other columns `B`
/// (every motor and loop side among them) solved from `E_B x_B = −E_N x_N`. By Cramer,
/// `det E_B` and `det E_B · x_B` are minors of `E`, affine in each capstan factor taken
/// alone like the null vector's ([`sliding_directions`]): where `det E_B` keeps its sign,
/// the motors' and loop sides' components of `E_B⁻¹ E_N` vanish and every tendon stays
/// above `1e-9 Σ x_N` at every point ([`proportion`]), so they do on every box between
/// rest and a point, and the state's `E` has full rank, determines its motors and loop
/// sides and lifts every tendon (with no null direction, `det E_B` alone).
///
/// Every choice of `N` is tried, over every point, then over the reachable ones: `Ok(true)`
/// where one holds, `Err` where none does, with a reachable point where the last choice
/// that held at rest fails, `None` where each fails only for want of one proportion. Past
/// [`EVERY_WAY_UP_TO`] choices, those of [`pivoted_free_tendons`] over every point, and
/// `Ok(false)` where none holds: not all were tried, and the states between the points
/// are not shown ([`sliding_directions`] refuses the routing unless the file accepts it).
fn held_between(
    model: &Model<f64>,
    sliding: &Sliding,
    points: &[Vec<f64>],
    tendons: &[usize],
) -> std::result::Result<bool, Option<Vec<f64>>> {
    let d = model.system.null_space.len();
    // The choices are C(tendons, d): past the limit of systems the points obey (26,244),
    // those a pivoted QR picks, as for the boxes (C(40, 20) is 1e11).
    let every_choice = choose(tendons.len(), d) <= EVERY_WAY_UP_TO;
    let choices = match every_choice {
        true => combinations(tendons, d),
        false => pivoted_free_tendons(&model.system.matrix, tendons, d),
    };
    let columns = model.system.matrix.first().map_or(0, Vec::len);
    let matrices: Vec<Vec<Vec<f64>>> = points.iter().map(|p| sliding.matrix(model, p)).collect();
    let holds = |free: &[usize], taken: &dyn Fn(usize) -> bool| -> std::result::Result<(), usize> {
        let basic: Vec<usize> = (0..columns).filter(|c| !free.contains(c)).collect();
        // Rest (the frictionless `E`) is a corner of every box.
        let (sign, mut rows) =
            basis(&model.system.matrix, &basic, free, tendons, None).ok_or(usize::MAX)?;
        for (i, e) in matrices.iter().enumerate().filter(|&(i, _)| taken(i)) {
            rows.extend(basis(e, &basic, free, tendons, Some(sign)).ok_or(i)?.1);
        }
        if d == 0 {
            return Ok(());
        }
        proportion(&rows, d).map(|_| ()).ok_or(usize::MAX)
    };
    let all = |_: usize| true;
    if choices.iter().any(|free| holds(free, &all).is_ok()) {
        return Ok(true);
    }
    if !every_choice {
        return Ok(false);
    }
    let reachable: Vec<bool> = points.iter().map(|p| sliding.reachable(p)).collect();
    let mut failing = None;
    for free in &choices {
        match holds(free, &|i| reachable[i]) {
            Ok(()) => return Ok(true),
            Err(i) if i != usize::MAX => failing = Some(i),
            Err(_) => {}
        }
    }
    Err(failing.map(|i| points[i].clone()))
}

/// `E_B` and `E_B⁻¹ E_N` at one point ([`held_between`]): `det E_B`'s sign (`None` where
/// `E_B` is singular within `1e-12` of its rows' sizes, or where the sign is not `sign`)
/// and, for each tendon of `B`, the row `a = −(E_B⁻¹ E_N)_i` giving its tension `a · x_N`;
/// `None` too where a motor's or loop side's component of
/// `E_B⁻¹ E_N` exceeds `1e-9` of the largest.
fn basis(
    e: &[Vec<f64>],
    basic: &[usize],
    free: &[usize],
    tendons: &[usize],
    sign: Option<f64>,
) -> Option<(f64, Vec<Vec<f64>>)> {
    let r = e.len();
    let square = DMatrix::from_fn(r, r, |i, j| e[i][basic[j]]);
    let hadamard: f64 = (square.row_iter()).map(|row| row.norm()).product();
    let lu = square.lu();
    let det = lu.determinant();
    let singular = det.is_nan() || det.abs() <= 1e-12 * hadamard;
    if singular || sign.is_some_and(|s| s != det.signum()) {
        return None;
    }
    let z = lu.solve(&DMatrix::from_fn(r, free.len(), |i, j| e[i][free[j]]))?;
    let size = z.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let mut rows = Vec::new();
    for (i, &c) in basic.iter().enumerate() {
        let row: Vec<f64> = z.row(i).iter().copied().collect();
        if tendons.contains(&c) {
            rows.push(row.iter().map(|z| -z).collect());
        } else if row.iter().any(|z| z.abs() > 1e-9 * size) {
            return None;
        }
    }
    Some((det.signum(), rows))
}

/// A proportion `x` (`Σ x = 1`) whose least of `x_j` and `a · x` over the rows `a` is
/// largest, if that exceeds `1e-9`: a linear program in `(x, t)`, `max t` with `x_j ≥ t`
/// and `a · x ≥ t`, over the rows the current optimum falls short of, added round by
/// round until none is (finite: each round adds one). The margin is then taken over every
/// row, not from the program.
fn proportion(rows: &[Vec<f64>], d: usize) -> Option<Vec<f64>> {
    use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome};
    let mut active = vec![false; rows.len()];
    loop {
        let mut lp = Problem::new(OptimizationDirection::Maximize);
        let x: Vec<_> = (0..d).map(|_| lp.add_var(0.0, (0.0, 1.0))).collect();
        let t = lp.add_var(1.0, (-1.0, 1.0));
        let sum: Vec<_> = x.iter().map(|&v| (v, 1.0)).collect();
        lp.add_constraint(sum.as_slice(), ComparisonOp::Eq, 1.0);
        for &v in &x {
            lp.add_constraint([(v, 1.0), (t, -1.0)], ComparisonOp::Ge, 0.0);
        }
        for (a, _) in rows.iter().zip(&active).filter(|(_, &on)| on) {
            let mut terms: Vec<_> = x.iter().zip(a).map(|(&v, &c)| (v, c)).collect();
            terms.push((t, -1.0));
            lp.add_constraint(terms.as_slice(), ComparisonOp::Ge, 0.0);
        }
        let (x, t) = match lp.solve() {
            Ok(SolveOutcome::Solution(s)) => (
                x.iter().map(|&v| s.var_value(v)).collect::<Vec<f64>>(),
                s.var_value(t),
            ),
            _ => return None,
        };
        let value = |a: &Vec<f64>| a.iter().zip(&x).map(|(a, x)| a * x).sum::<f64>();
        let mut added = false;
        for (a, on) in rows.iter().zip(active.iter_mut()) {
            if !*on && value(a) < t - 1e-12 {
                *on = true;
                added = true;
            }
        }
        if !added {
            let least = rows
                .iter()
                .map(value)
                .chain(x.iter().copied())
                .fold(f64::INFINITY, f64::min);
            return (least > 1e-9).then_some(x);
        }
    }
}

/// `C(n, k)`, saturating.
fn choose(n: usize, k: usize) -> usize {
    if k > n {
        return 0;
    }
    let k = k.min(n - k);
    // C(n, i + 1) = C(n, i) (n − i) / (i + 1), an integer at every step.
    let mut c: usize = 1;
    for i in 0..k {
        match c.checked_mul(n - i) {
            Some(product) => c = product / (i + 1),
            None => return usize::MAX,
        }
    }
    c
}

/// Every set of `k` of `items`, in increasing order of position.
fn combinations(items: &[usize], k: usize) -> Vec<Vec<usize>> {
    if k == 0 {
        return vec![Vec::new()];
    }
    (0..items.len())
        .flat_map(|i| {
            combinations(&items[i + 1..], k - 1)
                .into_iter()
                .map(move |mut rest| {
                    rest.insert(0, items[i]);
                    rest
                })
        })
        .collect()
}

/// The directions of sliding that [`sliding_directions`] checks, for it and for the code
/// generator's order of elimination (`tension::Elimination::holds_while_sliding`).
pub(crate) struct Sliding {
    /// Each group's sliding speed per joint velocity, its largest coefficient 1.
    groups: Vec<Vec<f64>>,
    classes: Vec<Class>,
    sliders: Vec<Slider>,
    /// With `friction_smoothing` there is no band of rest: a guide slides the way its
    /// speed says, or is at rest where that is zero.
    smoothed: bool,
}

impl Sliding {
    pub(crate) fn of(model: &Model<f64>) -> Sliding {
        let (groups, classes, sliders) = sliders_by_group(model);
        Sliding {
            groups,
            classes,
            sliders,
            smoothed: model.friction_smoothing.is_some(),
        }
    }

    /// The points checked, a direction per guide with friction relative to its group's
    /// (`±1`, or `0` at rest); none without such guides. Where there are at most
    /// [`EVERY_WAY_UP_TO`]: every way the exact law moves the classes
    /// ([`Sliding::law_moves`]), and, where a guide's factor varies (`Slider::variable`),
    /// each such guide of a moving class also at rest (the corners of the box of factors
    /// between rest and sliding); those where every guide slides first. Beyond: every
    /// guide slides, each group one way, in every pattern of up to 12 groups, past that in
    /// the two uniform patterns and those with one group flipped.
    pub(crate) fn points(&self) -> Vec<Vec<f64>> {
        self.points_and_whether_every_way().0
    }

    /// [`Sliding::points`], and whether they are every way ([`Sliding::every_way`]).
    fn points_and_whether_every_way(&self) -> (Vec<Vec<f64>>, bool) {
        if self.sliders.is_empty() {
            return (Vec::new(), true);
        }
        if let Some(points) = self.every_way() {
            return (points, true);
        }
        let groups = self.groups.len();
        let patterns: Vec<Vec<f64>> = if groups <= 12 {
            (0..1usize << groups)
                .map(|bits| {
                    (0..groups)
                        .map(|i| if bits >> i & 1 == 1 { -1.0 } else { 1.0 })
                        .collect()
                })
                .collect()
        } else {
            let mut p = vec![vec![1.0; groups], vec![-1.0; groups]];
            for i in 0..groups {
                for base in [1.0, -1.0] {
                    let mut one = vec![base; groups];
                    one[i] = -base;
                    p.push(one);
                }
            }
            p
        };
        let points = (patterns.into_iter())
            .map(|p| {
                (self.sliders.iter())
                    .map(|s| p[self.classes[s.class].group])
                    .collect()
            })
            .collect();
        (points, false)
    }

    /// [`Sliding::points`] where they are at most [`EVERY_WAY_UP_TO`].
    fn every_way(&self) -> Option<Vec<Vec<f64>>> {
        let classes = self.classes.len();
        if 3f64.powi(classes as i32) > EVERY_WAY_UP_TO as f64 {
            return None;
        }
        let mut points = Vec::new();
        for mut code in 1..3usize.pow(classes as u32) {
            let by_class: Vec<f64> = (0..classes)
                .map(|_| {
                    let digit = code % 3;
                    code /= 3;
                    [0.0, 1.0, -1.0][digit]
                })
                .collect();
            if !self.law_moves(&by_class) {
                continue;
            }
            let point: Vec<f64> = self.sliders.iter().map(|s| by_class[s.class]).collect();
            let free: Vec<usize> = (0..point.len())
                .filter(|&i| point[i] != 0.0 && self.sliders[i].variable)
                .collect();
            // Each guide free to rest doubles the corners: past the limit's count they are
            // not enumerated (and `rest >> k` stays within the word).
            if free.len() >= usize::BITS as usize || 1usize << free.len() > EVERY_WAY_UP_TO {
                return None;
            }
            for rest in 0..1usize << free.len() {
                let mut corner = point.clone();
                for (k, &i) in free.iter().enumerate() {
                    if rest >> k & 1 == 1 {
                        corner[i] = 0.0;
                    }
                }
                if corner.iter().any(|&d| d != 0.0) {
                    points.push(corner);
                }
                if points.len() > EVERY_WAY_UP_TO {
                    return None;
                }
            }
        }
        let zeros = |p: &Vec<f64>| p.iter().filter(|&&d| d == 0.0).count();
        points.sort_by(|a, b| {
            zeros(a)
                .cmp(&zeros(b))
                .then(a.partial_cmp(b).expect("±1 or 0"))
        });
        points.dedup();
        Some(points)
    }

    /// Whether the exact law moves the classes as `by_class` says (`±1` relative to the
    /// group, `0` at rest), from one group to the next: within a group, fastest first, the
    /// classes at rest come last (a class within the band for both `q̇` and `q̈` leaves every
    /// slower one there too) and the directions of the others switch at most once (within
    /// the band, slower classes take `q̈`'s way, [`Sliding::ways`]). With the smoothed law,
    /// a group moves one way or rests.
    fn law_moves(&self, by_class: &[f64]) -> bool {
        self.by_group(by_class).iter().all(|ways| {
            let rest_last = ways.windows(2).all(|p| p[0].1 != 0.0 || p[1].1 == 0.0);
            let switches = ways
                .windows(2)
                .filter(|p| p[1].1 != 0.0 && p[0].1 != p[1].1)
                .count();
            if self.smoothed {
                ways.iter().all(|w| w.1 == ways[0].1)
            } else {
                rest_last && switches <= 1
            }
        })
    }

    /// Each group's classes as `(speed, direction)` of `by_class`, fastest first.
    fn by_group(&self, by_class: &[f64]) -> Vec<Vec<(f64, f64)>> {
        let mut groups = vec![Vec::new(); self.groups.len()];
        for (class, &way) in self.classes.iter().zip(by_class) {
            groups[class.group].push((class.speed, way));
        }
        for g in &mut groups {
            g.sort_by(|a: &(f64, f64), b| b.0.total_cmp(&a.0));
        }
        groups
    }

    /// Each guide with friction, its tendon and the way `sigma` moves it, for a message.
    fn described(&self, model: &Model<f64>, sigma: &[Vec<f64>]) -> String {
        let described: Vec<String> = (self.sliders.iter())
            .map(|slider| {
                let strand = &model.strands[slider.strand];
                let guide = &model.bodies[strand.idlers[slider.idler].body].name;
                match sigma[slider.strand][slider.idler] {
                    0.0 => format!("`{}` at rest on `{guide}`", strand.name),
                    x if x > 0.0 => format!("`{}` over `{guide}` towards its exit", strand.name),
                    _ => format!("`{}` over `{guide}` towards its anchor", strand.name),
                }
            })
            .collect();
        described.join(", ")
    }

    /// Where the systems were taken, for a message: `at q = 0`, or the wrap angles the
    /// joints' ranges reach where they are larger ([`crate::model::Guide::wrap_over`]).
    fn wraps_checked(&self, model: &Model<f64>) -> String {
        let larger: Vec<String> = (self.sliders.iter())
            .filter_map(|slider| {
                let idler = &model.strands[slider.strand].idlers[slider.idler];
                let at_rest = idler.guide.as_ref().map_or(0.0, |g| g.wrap.max(0.0));
                (slider.wrap > at_rest).then(|| {
                    let name = &model.bodies[idler.body].name;
                    format!("`{name}` {:.1}°", slider.wrap.to_degrees())
                })
            })
            .collect();
        if larger.is_empty() {
            return "at q = 0".into();
        }
        format!(
            "with the wrap angles the joints' ranges reach: {}",
            larger.join(", ")
        )
    }

    /// What gives the guides' capstan factors values between rest and sliding.
    fn between_comes_from(&self) -> &'static str {
        if self.smoothed {
            "`friction_smoothing`"
        } else {
            "wrap angles that change with the joints"
        }
    }

    /// The first guide with friction's name, where a refusal is reported.
    fn first_guide(&self, model: &Model<f64>) -> String {
        let first = &self.sliders[0];
        model.bodies[model.strands[first.strand].idlers[first.idler].body]
            .name
            .clone()
    }

    /// The largest `Σ μ β` over the guides with friction one strand passes, each at its
    /// largest wrap angle: the log of the most its capstan factors can multiply up to.
    fn largest_exponent(&self, model: &Model<f64>) -> f64 {
        let mut sums = vec![0.0f64; model.strands.len()];
        for s in &self.sliders {
            let mu = model.strands[s.strand].idlers[s.idler]
                .capstan()
                .map_or(0.0, |g| g.mu);
            sums[s.strand] += mu * s.wrap;
        }
        sums.into_iter().fold(0.0, f64::max)
    }

    /// `E` at `point`: each guide with friction at its largest wrap angle over the joints'
    /// ranges ([`crate::model::Guide::wrap_over`]), its capstan factor `e^{−σμβ}`
    /// (`tension::state_matrix`).
    pub(crate) fn matrix(&self, model: &Model<f64>, point: &[f64]) -> Vec<Vec<f64>> {
        let wraps: Vec<f64> = self.sliders.iter().map(|s| s.wrap).collect();
        self.matrix_at(model, point, &wraps)
    }

    /// `E` at `point` with each guide with friction at the wrap angle `wraps` gives it.
    fn matrix_at(&self, model: &Model<f64>, point: &[f64], wraps: &[f64]) -> Vec<Vec<f64>> {
        let lambda: Vec<f64> = (self.sliders.iter().zip(point).zip(wraps))
            .map(|((slider, &way), &wrap)| {
                let mu = self.guide(model, slider).mu;
                crate::friction::capstan_log_factor(-slider.sign * way * mu, wrap)
            })
            .collect();
        self.matrix_with_factors(model, &lambda)
    }

    /// `E` with each slider's log capstan factor `λ_g` (one of the box `|λ_g| ≤ μ β_g`,
    /// [`Sliding::reach`], holds every state's).
    fn matrix_with_factors(&self, model: &Model<f64>, lambda: &[f64]) -> Vec<Vec<f64>> {
        let mut capstan: Vec<Vec<f64>> = (model.strands.iter())
            .map(|s| vec![1.0; s.idlers.len()])
            .collect();
        for (slider, l) in self.sliders.iter().zip(lambda) {
            capstan[slider.strand][slider.idler] = l.exp();
        }
        crate::tension::state_matrix(model, &capstan)
    }

    fn guide<'m>(&self, model: &'m Model<f64>, slider: &Slider) -> &'m crate::model::Guide {
        let idler = &model.strands[slider.strand].idlers[slider.idler];
        idler.capstan().expect("a slider is a guide with friction")
    }

    /// Each slider's `μ β_g`, `β_g` its largest wrap angle: the box of every log capstan
    /// factor it can take is `|λ_g| ≤ μ β_g`.
    fn reach(&self, model: &Model<f64>) -> Vec<f64> {
        (self.sliders.iter())
            .map(|s| self.guide(model, s).mu * s.wrap.max(0.0))
            .collect()
    }

    /// The number of boxes of capstan factors on which every factor the guides can take is
    /// shown to pass `fails` (at each box's centre) and to keep the sign of each of
    /// `squares`' determinants (rows, columns of `E`), within `budget` boxes
    /// ([`factor_boxes::every_factor`]); `None` where that is not shown.
    pub(crate) fn on_every_factor(
        &self,
        model: &Model<f64>,
        squares: &[(Vec<usize>, Vec<usize>)],
        fails: &dyn Fn(Vec<Vec<f64>>) -> Option<String>,
        budget: usize,
    ) -> Option<usize> {
        let squares: Vec<factor_boxes::Square> = (squares.iter())
            .map(|(rows, columns)| factor_boxes::Square::of(rows, columns))
            .collect();
        let runs = factor_boxes::Columns::of(model, self);
        factor_boxes::every_factor(model, self, &runs, &squares, fails, budget).ok()
    }

    /// Whether some guide's wrap angle changes over the joints' ranges.
    pub(crate) fn ranged(&self, model: &Model<f64>) -> bool {
        let joints = model.range_box();
        (self.sliders.iter()).any(|s| {
            let rates = &self.guide(model, s).wrap_rate;
            (rates.iter().zip(&joints)).any(|(&k, r)| k != 0.0 && r[1] > r[0])
        })
    }

    /// A state within the joints' ranges where the system fails at `point`, found by
    /// bisecting the ranges. On a box of joint angles each guide's wrap angle lies in an
    /// interval, and the system's minors, affine in each capstan factor, pass on the whole
    /// box where they pass at the intervals' ends taken every way (with the smoothed law,
    /// whose `|σ| < 1` reaches every factor between rest and these, also with any of the
    /// moving guides at rest). A failing combination of ends that one corner of the box
    /// gives every guide is a state, `Some(q)`; one that no corner does splits the box at
    /// its widest joint. `None` where every box passes; past [`UNSETTLED_AFTER`] boxes, or
    /// a box narrower than `1e-9` rad, the state is not settled (`Some(None)`).
    pub(crate) fn state_that_fails(
        &self,
        model: &Model<f64>,
        point: &[f64],
        fails: &dyn Fn(Vec<Vec<f64>>) -> Option<String>,
    ) -> Option<(Option<Vec<f64>>, String)> {
        let moving: Vec<usize> = (0..self.sliders.len())
            .filter(|&i| point[i] != 0.0)
            .collect();
        // The patterns a box must pass: `point`, and with the smoothed law every one with
        // some of its moving guides at rest.
        let subsets = match self.smoothed {
            true if moving.len() > ENDS_UP_TO => {
                let why = format!("{} guides move, more than {ENDS_UP_TO}", moving.len());
                return Some((None, why));
            }
            true => 1usize << moving.len(),
            false => 1,
        };
        let patterns: Vec<Vec<f64>> = (0..subsets)
            .map(|rest| {
                let mut p = point.to_vec();
                for (k, &i) in moving.iter().enumerate() {
                    if rest >> k & 1 == 1 {
                        p[i] = 0.0;
                    }
                }
                p
            })
            .collect();
        let mut boxes = vec![model.range_box()];
        let mut explored = 0;
        while let Some(b) = boxes.pop() {
            explored += 1;
            let ends: Vec<[f64; 2]> = (self.sliders.iter())
                .map(|s| self.guide(model, s).wrap_over(&b))
                .collect();
            let mut failing = None;
            for pattern in &patterns {
                let varying: Vec<usize> = (0..self.sliders.len())
                    .filter(|&i| pattern[i] != 0.0 && ends[i][1] > ends[i][0])
                    .collect();
                if varying.len() > ENDS_UP_TO {
                    let why = format!(
                        "{} guides wrap differently across the ranges, more than {ENDS_UP_TO}",
                        varying.len()
                    );
                    return Some((None, why));
                }
                let mut wraps: Vec<f64> = ends.iter().map(|e| e[1]).collect();
                failing = (0..1usize << varying.len()).find_map(|bits| {
                    for (k, &i) in varying.iter().enumerate() {
                        wraps[i] = ends[i][bits >> k & 1];
                    }
                    let why = fails(self.matrix_at(model, pattern, &wraps))?;
                    Some((varying.clone(), bits, why))
                });
                if failing.is_some() {
                    break;
                }
            }
            let Some((varying, bits, why)) = failing else {
                continue;
            };
            // Only a point some motion produces can fail in use (checked once, and only
            // here: it takes linear programs).
            if explored == 1 && !self.reachable(point) {
                return None;
            }
            // The corner of `b` where each varying guide has the end it was taken at.
            let mut corner: Vec<Option<f64>> = vec![None; b.len()];
            let mut one_corner = true;
            for (k, &i) in varying.iter().enumerate() {
                let upper = bits >> k & 1 == 1;
                let rates = &self.guide(model, &self.sliders[i]).wrap_rate;
                for (j, &rate) in rates.iter().enumerate() {
                    if rate == 0.0 || b[j][1] == b[j][0] {
                        continue;
                    }
                    let want = if (rate > 0.0) == upper {
                        b[j][1]
                    } else {
                        b[j][0]
                    };
                    one_corner &= corner[j].is_none_or(|q| q == want);
                    corner[j] = Some(want);
                }
            }
            if one_corner {
                let q = (corner.iter().zip(&b))
                    .map(|(c, r)| c.unwrap_or(0.0f64.clamp(r[0], r[1])))
                    .collect();
                return Some((Some(q), why));
            }
            // No corner gives every guide its end; a state of the box may fail all the
            // same: its vertices in the joints that move these guides' wraps.
            let joints: Vec<usize> = (0..b.len()).filter(|&j| corner[j].is_some()).collect();
            for code in 0..1usize << joints.len().min(8) {
                let mut q: Vec<f64> = b.iter().map(|r| 0.0f64.clamp(r[0], r[1])).collect();
                for (k, &j) in joints.iter().enumerate().take(8) {
                    q[j] = b[j][code >> k & 1];
                }
                let wraps: Vec<f64> = (self.sliders.iter())
                    .map(|s| self.guide(model, s).wrap_at(&q).max(0.0))
                    .collect();
                for pattern in &patterns {
                    if let Some(why) = fails(self.matrix_at(model, pattern, &wraps)) {
                        return Some((Some(q), why));
                    }
                }
            }
            // Split the widest joint among those that move the failing guides' wraps (the
            // others would split it into two boxes that fail alike).
            let width = |j: &usize| b[*j][1] - b[*j][0];
            let widest = (joints.iter().copied()).max_by(|x, y| width(x).total_cmp(&width(y)));
            match widest.filter(|j| width(j) > 1e-9) {
                Some(j) if explored < UNSETTLED_AFTER => {
                    let middle = 0.5 * (b[j][0] + b[j][1]);
                    let (mut lower, mut upper) = (b.clone(), b);
                    lower[j][1] = middle;
                    upper[j][0] = middle;
                    boxes.push(lower);
                    boxes.push(upper);
                }
                _ => {
                    let why = format!(
                        "after {explored} boxes of joint angles (at most {UNSETTLED_AFTER}, \
                         none narrower than 1e-9 rad) the system still failed where no state \
                         was found ({why})"
                    );
                    return Some((None, why));
                }
            }
        }
        None
    }

    /// `σ[strand][idler]` at `point` (0 where no guide slides).
    pub(crate) fn sigma(&self, model: &Model<f64>, point: &[f64]) -> Vec<Vec<f64>> {
        let mut sigma: Vec<Vec<f64>> = (model.strands.iter())
            .map(|s| vec![0.0; s.idlers.len()])
            .collect();
        for (slider, &way) in self.sliders.iter().zip(point) {
            sigma[slider.strand][slider.idler] = slider.sign * way;
        }
        sigma
    }

    /// Each group's classes that move at `point`, as `(speed, direction)`, fastest first;
    /// `None` where the exact law cannot produce it: two guides of a class (equal speeds)
    /// moving different ways, or a group whose directions switch more than once (with the
    /// smoothed law, at all). A group's faster classes slide the way `q̇` moves it; where
    /// that is within the band of rest (`friction::REST`) for its slower ones, those take
    /// the way `q̈` moves it, which may be the other.
    fn ways(&self, point: &[f64]) -> Option<Vec<Vec<(f64, f64)>>> {
        let mut by_class = vec![0.0; self.classes.len()];
        for (slider, &way) in self.sliders.iter().zip(point) {
            let w = &mut by_class[slider.class];
            if way != 0.0 && *w != 0.0 && *w != way {
                return None;
            }
            if way != 0.0 {
                *w = way;
            }
        }
        let mut ways = self.by_group(&by_class);
        let most = if self.smoothed { 0 } else { 1 };
        for w in &mut ways {
            w.retain(|c| c.1 != 0.0);
            if w.windows(2).filter(|p| p[0].1 != p[1].1).count() > most {
                return None;
            }
        }
        Some(ways)
    }

    /// Whether some `q̇` slides every guide the way `point` says (`±1` each, every group
    /// one way) beyond any band of rest: `way_g (u_g · q̇) > 0` for every group, an open
    /// cone (one linear program). Such a point is [`Sliding::reachable`].
    fn slides_every_guide(&self, point: &[f64]) -> bool {
        let Some(ways) = self.ways(point).filter(|_| point.iter().all(|&d| d != 0.0)) else {
            return false;
        };
        let rows: Option<Vec<_>> = (ways.iter().zip(&self.groups))
            .map(|(w, u)| {
                let &(_, way) = w.first()?;
                let one_way = w.iter().all(|c| c.1 == way);
                one_way.then(|| (u.iter().map(|x| way * x).collect(), 1.0, f64::INFINITY))
            })
            .collect();
        rows.is_some_and(|rows| feasible(&rows))
    }

    /// Whether some motion makes the guides take the directions of `point` (a guide at
    /// rest there is left free: it stands for the corner of a box, [`sliding_directions`]).
    /// With the smoothed law: some `q̇` with `way_g (u_g · q̇) > 0` for every group that
    /// moves. With the exact law each group is split where its directions switch (or, where
    /// they do not, anywhere): its classes before the split slide, `|v| > REST`, the way
    /// `q̇` moves the group; those after are within the band, `|v| ≤ REST`, and take the
    /// way `q̈` moves it. Some split of every group must be met by one `q̇` and one `q̈`
    /// (two linear programs; a group whose classes are all within the band is a `q̇` that
    /// nearly stops it, so the band's width matters and is kept).
    pub(crate) fn reachable(&self, point: &[f64]) -> bool {
        let Some(ways) = self.ways(point) else {
            return false;
        };
        let scaled = |u: &[f64], k: f64| u.iter().map(|x| k * x).collect::<Vec<f64>>();
        if self.smoothed {
            let rows: Vec<_> = (ways.iter().zip(&self.groups))
                .filter_map(|(w, u)| {
                    w.first()
                        .map(|&(_, way)| (scaled(u, way), 1.0, f64::INFINITY))
                })
                .collect();
            return feasible(&rows);
        }
        let splits: Vec<Vec<usize>> = (ways.iter())
            .map(|w| match w.windows(2).position(|p| p[0].1 != p[1].1) {
                Some(i) => vec![i + 1],
                None => (0..=w.len()).collect(),
            })
            .collect();
        // Every combination of splits, as an odometer over the groups.
        let mut at = vec![0usize; splits.len()];
        loop {
            // `q̇` in units of the band: sliding is `≥ 1`, within the band `|·| ≤ 1`.
            let (mut velocity, mut acceleration) = (Vec::new(), Vec::new());
            for (g, (w, u)) in ways.iter().zip(&self.groups).enumerate() {
                let k = splits[g][at[g]];
                if k > 0 {
                    let (speed, way) = w[k - 1];
                    velocity.push((scaled(u, way * speed), 1.0, f64::INFINITY));
                }
                if k < w.len() {
                    let (speed, way) = w[k];
                    velocity.push((scaled(u, speed), -1.0, 1.0));
                    acceleration.push((scaled(u, way), 1.0, f64::INFINITY));
                }
            }
            if feasible(&velocity) && feasible(&acceleration) {
                return true;
            }
            let mut g = 0;
            loop {
                if g == at.len() {
                    return false;
                }
                at[g] += 1;
                if at[g] < splits[g].len() {
                    break;
                }
                at[g] = 0;
                g += 1;
            }
        }
    }
}

/// The guides with friction over which something slides; the groups of their sliding
/// speeds per joint velocity (each normalised to a largest coefficient of 1); and the
/// classes of equal or opposite speeds.
fn sliders_by_group(model: &Model<f64>) -> (Vec<Vec<f64>>, Vec<Class>, Vec<Slider>) {
    let joints = model.range_box();
    let mut groups: Vec<Vec<f64>> = Vec::new();
    let mut speeds: Vec<(Vec<f64>, Class)> = Vec::new();
    let mut sliders = Vec::new();
    for (s, strand) in model.strands.iter().enumerate() {
        for (k, idler) in strand.idlers.iter().enumerate() {
            let Some(g) = idler.capstan() else {
                continue;
            };
            let size = g.slide.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            if size == 0.0 {
                continue; // nothing slides over it: no friction, whatever the motion
            }
            let unit: Vec<f64> = g.slide.iter().map(|x| x / size).collect();
            let same = |a: &[f64], sign: f64| {
                a.iter()
                    .zip(&unit)
                    .all(|(x, y)| (x - sign * y).abs() <= 1e-12)
            };
            let found = groups.iter().enumerate().find_map(|(i, u)| {
                [1.0, -1.0]
                    .into_iter()
                    .find(|&sign| same(u, sign))
                    .map(|sign| (i, sign))
            });
            let (group, sign) = found.unwrap_or_else(|| {
                groups.push(unit.clone());
                (groups.len() - 1, 1.0)
            });
            let twin = |(speed, class): &(Vec<f64>, Class)| {
                class.group == group
                    && (speed.iter().zip(&g.slide))
                        .all(|(x, y)| (x.abs() - y.abs()).abs() <= 1e-12 * size)
            };
            let class = speeds.iter().position(twin).unwrap_or_else(|| {
                speeds.push((g.slide.clone(), Class { group, speed: size }));
                speeds.len() - 1
            });
            sliders.push(Slider {
                strand: s,
                idler: k,
                class,
                sign,
                wrap: g.wrap_over(&joints)[1],
                variable: model.friction_smoothing.is_some() || !g.wrap_is_constant(),
            });
        }
    }
    let classes = speeds.into_iter().map(|(_, class)| class).collect();
    (groups, classes, sliders)
}

/// The null vector of an `r × (r + 1)` matrix `E` by its signed maximal minors,
/// `n_k = (−1)^k det(E without column k)` (Cramer): nonzero exactly where `E` has full row
/// rank, with no normalisation that could flip it. Taken as `n = n_f z` from one `L U` of
/// `E` without column `f` (a tendon's, chosen where the model's minor is largest) and the
/// null vector `z` with `z_f = 1`, and by every minor where that one vanishes.
struct Minors {
    free: usize,
    n: Vec<f64>,
}

impl Minors {
    /// The model's minors (every one), and the tendon column to free at other states.
    fn of(e: &[Vec<f64>], tendons: &[usize]) -> Minors {
        let columns = e.first().map_or(0, Vec::len);
        let n: Vec<f64> = (0..columns).map(|k| minor(e, k)).collect();
        let free = (tendons.iter().copied())
            .reduce(|a, b| if n[b].abs() > n[a].abs() { b } else { a })
            .unwrap_or(0);
        Minors { free, n }
    }

    /// The minors of `e`, a state's matrix of the same shape.
    fn at(&self, e: &[Vec<f64>]) -> Vec<f64> {
        let (rows, columns, f) = (e.len(), self.n.len(), self.free);
        let kept: Vec<usize> = (0..columns).filter(|&c| c != f).collect();
        let lu = DMatrix::from_fn(rows, rows, |i, j| e[i][kept[j]]).lu();
        let n_f = alternating(f) * lu.determinant();
        let rhs = nalgebra::DVector::from_fn(rows, |i, _| -e[i][f]);
        match lu.solve(&rhs).filter(|_| n_f != 0.0 && n_f.is_finite()) {
            Some(z) => {
                let mut n = vec![n_f; columns];
                for (&c, z) in kept.iter().zip(z.iter()) {
                    n[c] = n_f * z;
                }
                n
            }
            None => (0..columns).map(|k| minor(e, k)).collect(),
        }
    }

    /// The least of the tendons' minors in `n`, taken the way the model's lift them,
    /// relative to `|n|`: at most `0` where some tendon is slack or pushed, `−∞` where `n`
    /// vanishes (`E` loses rank) or is not finite.
    fn least_lift(&self, n: &[f64], tendons: &[usize]) -> f64 {
        let size = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(size.is_finite() && size > 0.0) {
            return f64::NEG_INFINITY;
        }
        let way = (tendons.iter()).fold(0.0, |s, &k| s + self.n[k]).signum();
        (tendons.iter()).fold(f64::INFINITY, |least, &k| least.min(way * n[k] / size))
    }

    /// Whether the minors `n` lift every tendon as the model's do: each tendon's of the
    /// same sign and larger than `1e-9` of `|n|` (the margin [`positive_null_vector`] asks
    /// of a unit null vector), and the others, which vanish in the model (every motor and
    /// loop side determined), within `1e-9` of `|n|` still.
    fn compare(&self, n: &[f64], tendons: &[usize]) -> std::result::Result<(), String> {
        let size = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(size.is_finite() && size > 0.0) {
            return Err("the tension system loses full rank".into());
        }
        let least = self.least_lift(n, tendons);
        if least <= 0.0 {
            return Err(
                "the null vector of the tension system no longer lifts every tendon \
                        together"
                    .into(),
            );
        }
        if least <= LIFT_MARGIN {
            return Err(format!(
                "the null vector of the tension system lifts one tendon by only {least:.1e} \
                 of its size, within round-off of slack (validation asks at least \
                 {LIFT_MARGIN:e}): the largest tension would be about {:.0e} times that tendon's",
                1.0 / least
            ));
        }
        let other = (0..n.len()).filter(|k| !tendons.contains(k));
        if other.clone().any(|k| n[k].abs() > LIFT_MARGIN * size) {
            return Err(
                "the tendons' co-contraction would then move a motor torque or a loop \
                        side, which the routing must determine"
                    .into(),
            );
        }
        Ok(())
    }
}

/// The least tendon component of a null vector, relative to its size, that validation
/// asks for (`1e-9`, the margin [`positive_null_vector`] asks of a unit null vector).
const LIFT_MARGIN: f64 = 1e-9;

/// `(−1)^k det(E without column k)`.
fn minor(e: &[Vec<f64>], k: usize) -> f64 {
    let rows = e.len();
    let m = DMatrix::from_fn(rows, rows, |i, j| e[i][if j < k { j } else { j + 1 }]);
    alternating(k) * m.determinant()
}

/// `(−1)^k`.
fn alternating(k: usize) -> f64 {
    if k.is_multiple_of(2) {
        1.0
    } else {
        -1.0
    }
}

#[cfg(test)]
mod tests {
    use super::{basis, choose, pivoted_free_tendons, proportion, Class, Minors, Slider, Sliding};

    /// Past the choices taken one by one, the free tendons are those a pivoted QR takes
    /// last (here the two small columns; the two unit ones make a well-conditioned `E_B`),
    /// then each with one swapped for a basic tendon: `1 + d (K − d)` sets of `d`.
    #[test]
    fn the_pivoted_free_tendons_leave_the_most_independent_columns_basic() {
        let e = vec![vec![1.0, 0.0, 1e-3, 0.0], vec![0.0, 1.0, 0.0, 2e-3]];
        let choices = pivoted_free_tendons(&e, &[0, 1, 2, 3], 2);
        assert_eq!(choices[0], vec![2, 3]);
        assert_eq!(choices.len(), 1 + 2 * 2);
        for set in &choices[1..] {
            assert_eq!(set.len(), 2);
            assert!(set.windows(2).all(|p| p[0] < p[1]), "{set:?}");
            assert_eq!(
                set.iter().filter(|t| [2, 3].contains(t)).count(),
                1,
                "{set:?}"
            );
        }
    }

    /// The count of fixed bases `held_between` would try, which decides whether it builds
    /// them: exact while it fits, past any limit where it does not.
    #[test]
    fn choose_counts_subsets_and_saturates() {
        assert_eq!(choose(4, 2), 6);
        assert_eq!(choose(30, 15), 155_117_520);
        assert_eq!(choose(3, 5), 0);
        assert_eq!(choose(7, 0), 1);
        assert!(choose(200, 100) > 1 << 60);
    }

    /// Guides with friction by `(group, speed)` of their class, each on its own strand;
    /// `groups` the groups' speeds per joint velocity; `variable` the guides whose capstan
    /// factor varies (all of them with the smoothed law).
    fn sliding(
        groups: Vec<Vec<f64>>,
        classes: &[(usize, f64)],
        of: &[usize],
        smoothed: bool,
        variable: &[usize],
    ) -> Sliding {
        Sliding {
            groups,
            classes: (classes.iter())
                .map(|&(group, speed)| Class { group, speed })
                .collect(),
            sliders: (of.iter().enumerate())
                .map(|(strand, &class)| Slider {
                    strand,
                    idler: 0,
                    class,
                    sign: 1.0,
                    wrap: 0.0,
                    variable: smoothed || variable.contains(&strand),
                })
                .collect(),
            smoothed,
        }
    }

    /// Two guides of one class (equal speeds), a slower class of the same group and a
    /// guide alone in a second group. By the exact law the guides of a class move
    /// together, a group's classes at rest are its slowest, and a slower class may move
    /// against the faster one (within the band of rest it takes `q̈`'s way); those where
    /// every guide slides come first. A guide whose factor varies is also taken at rest
    /// alone (a corner of the box of factors); with the smoothed law every guide's does,
    /// and a group moves one way or rests.
    #[test]
    fn the_points_checked_are_every_way_the_law_moves_the_guides_and_the_boxes_corners() {
        let groups = vec![vec![1.0, 0.0], vec![0.0, 1.0]];
        let classes = [(0, 2.0), (0, 1.0), (1, 1.0)];
        let exact = sliding(groups.clone(), &classes, &[0, 0, 1, 2], false, &[]).points();
        // The first group: at rest, or the faster class either way and the slower at rest
        // or either way (7); the second: at rest or either way (3); less all at rest.
        assert_eq!(exact.len(), 7 * 3 - 1);
        assert!(exact.iter().all(|p| p[0] == p[1]));
        assert!(exact.contains(&vec![1.0, 1.0, -1.0, 0.0]));
        assert!(!exact.contains(&vec![0.0, 0.0, 1.0, 0.0]));
        let sliding_first: Vec<_> = exact.iter().take_while(|p| !p.contains(&0.0)).collect();
        assert_eq!(sliding_first.len(), 4 * 2);
        // The first guide's wrap angle varies: it may also rest while its twin slides.
        let varying = sliding(groups.clone(), &classes, &[0, 0, 1, 2], false, &[0]).points();
        assert!(varying.contains(&vec![0.0, 1.0, -1.0, 0.0]));
        assert!(!varying.contains(&vec![1.0, 0.0, -1.0, 0.0]));
        let smoothed = sliding(groups, &classes, &[0, 0, 1, 2], true, &[]).points();
        // The first group at rest, or one way with any of its three guides moving (2 × 7);
        // the second at rest or either way (3); less all at rest.
        assert_eq!(smoothed.len(), (1 + 2 * 7) * 3 - 1);
        assert!(!smoothed.contains(&vec![1.0, 1.0, -1.0, 0.0]));
        assert!(smoothed.contains(&vec![0.0, 1.0, 0.0, -1.0]));
        // Three classes in one group: the directions, fastest first, switch at most once.
        let three = |p: &[f64]| {
            let s = sliding(
                vec![vec![1.0]],
                &[(0, 3.0), (0, 2.0), (0, 1.0)],
                &[0, 1, 2],
                false,
                &[],
            );
            s.points().contains(&p.to_vec())
        };
        assert!(three(&[1.0, 1.0, -1.0]) && three(&[1.0, -1.0, -1.0]));
        assert!(!three(&[1.0, -1.0, 1.0]) && !three(&[0.0, 1.0, 1.0]));
    }

    /// Three groups sliding at `q̇₁`, `q̇₂` and `q̇₁ + q̇₂`, at 0.03 m/s per rad/s each. By
    /// `q̇` alone (the smoothed law) the third cannot slide backwards while the first two
    /// slide forwards. By the exact law it can: at `q̇ = −(2, 2)·10⁻⁵` rad/s the first two
    /// move 0.6 µm/s, within the band of rest, and take the way of `q̈ = (1, 1)`, while the
    /// third slides back at 1.2 µm/s. Within one group, a slower class moves against a
    /// faster one only by the band too.
    #[test]
    fn a_pattern_of_sliding_directions_is_reachable_only_where_some_motion_gives_it() {
        let groups = vec![vec![1.0, 0.0], vec![0.0, 1.0], vec![1.0, 1.0]];
        let with = |smoothed: bool| {
            sliding(
                groups.clone(),
                &[(0, 0.03), (1, 0.03), (2, 0.03)],
                &[0, 1, 2],
                smoothed,
                &[],
            )
        };
        let smoothed = with(true);
        assert!(!smoothed.reachable(&[1.0, 1.0, -1.0]));
        assert!(!smoothed.reachable(&[-1.0, -1.0, 1.0]));
        for point in [
            [1.0, 1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, -1.0, -1.0],
            [1.0, 1.0, 0.0],
        ] {
            assert!(smoothed.reachable(&point) && with(false).reachable(&point));
        }
        assert!(with(false).reachable(&[1.0, 1.0, -1.0]));
        let two = |smoothed| {
            sliding(
                vec![vec![1.0]],
                &[(0, 2.0), (0, 1.0)],
                &[0, 1],
                smoothed,
                &[],
            )
        };
        assert!(two(false).reachable(&[1.0, -1.0]) && two(false).reachable(&[-1.0, 1.0]));
        assert!(!two(true).reachable(&[1.0, -1.0]));
        // Switching twice (fastest first) is no motion's: the band holds only slower classes.
        let three = sliding(
            vec![vec![1.0]],
            &[(0, 3.0), (0, 2.0), (0, 1.0)],
            &[0, 1, 2],
            false,
            &[],
        );
        assert!(three.reachable(&[1.0, 1.0, -1.0]) && !three.reachable(&[1.0, -1.0, 1.0]));
    }

    /// `E = [a, −1, 1]` (one joint; a tendon whose moment arm friction turns from 2 to −1
    /// N·m/N, against two fixed ones): controllable wherever `a` is, as the other two
    /// pull opposite ways, but no one null direction lifts every tendon throughout (the
    /// first tendon's minor changes sign). Freeing the first and the third (`B` the second)
    /// holds them in one proportion that keeps the second, `a x₁ + x₃`, taut at every `a`.
    /// A motor's column that the free tendons would move refuses the basis.
    #[test]
    fn a_fixed_proportion_of_free_tendons_keeps_the_others_taut_at_every_point() {
        let e = |a: f64| vec![vec![a, -1.0, 1.0]];
        let tendons = [0, 1, 2];
        let rows: Vec<Vec<f64>> = [2.0, 0.5, -1.0]
            .iter()
            .flat_map(|&a| basis(&e(a), &[1], &[0, 2], &tendons, Some(-1.0)).unwrap().1)
            .collect();
        let x = proportion(&rows, 2).unwrap();
        assert!((x[0] + x[1] - 1.0).abs() < 1e-12 && x[0] > 1e-9 && x[1] > 1e-9);
        for a in [2.0, 0.5, -1.0] {
            // The second tendon, solved from the balance: `x₂ = a x₁ + x₃`.
            assert!(a * x[0] + x[1] > 1e-9, "{x:?} at a = {a}");
        }
        // The sign of `det E_B` must be the frictionless one.
        assert!(basis(&e(2.0), &[1], &[0, 2], &tendons, Some(1.0)).is_none());
        // `x₁ ≥ x₂` and `x₁ ≤ x₂ / 2` hold for no positive `x`.
        assert!(proportion(&[vec![1.0, -1.0], vec![-1.0, 0.5]], 2).is_none());
        // The least of `x₁`, `x₂` and `2x₁ − x₂` is largest, 1/2, at `x = (1/2, 1/2)`.
        let x = proportion(&[vec![2.0, -1.0]], 2).unwrap();
        assert!(
            (x[0] - 0.5).abs() < 1e-9 && (x[1] - 0.5).abs() < 1e-9,
            "{x:?}"
        );
        // A motor (column 1 not a tendon) that the free tendons would move.
        assert!(basis(&e(1.0), &[1], &[0, 2], &[0, 2], None).is_none());
        let still = vec![vec![1.0, 0.0, -1.0], vec![0.0, 1.0, 0.0]];
        assert!(basis(&still, &[1, 2], &[0], &[0, 2], None).is_some());
    }

    /// `E = [2 −1 0; 0 0 1]` (one joint and two tendons with opposite moment arms, and a
    /// motor alone on a driving pulley's row): the minors `(−1, −2, 0)` lift both tendons
    /// together and leave the motor determined; a state's minors must do the same, by more
    /// than round-off of their size, whichever column is freed to get them.
    #[test]
    fn the_minors_lift_the_tendons_only_with_the_signs_they_have_without_friction() {
        let e = vec![vec![2.0, -1.0, 0.0], vec![0.0, 0.0, 1.0]];
        let model = Minors::of(&e, &[0, 1]);
        assert_eq!(model.n, vec![-1.0, -2.0, 0.0]);
        assert_eq!(model.at(&e), model.n);
        assert!(model.compare(&model.n, &[0, 1]).is_ok());
        let with = |row: Vec<f64>| model.at(&[row, vec![0.0, 0.0, 1.0]]);
        assert!(model.compare(&with(vec![3.0, -0.5, 0.0]), &[0, 1]).is_ok());
        assert!(model.compare(&with(vec![3.0, 0.5, 0.0]), &[0, 1]).is_err());
        assert!(model.compare(&with(vec![0.0, 0.0, 0.0]), &[0, 1]).is_err());
        assert!(model.compare(&[-1.0, -1e-12, 0.0], &[0, 1]).is_err());
        let moved = model.at(&[vec![2.0, -1.0, 1.0], vec![0.0, 0.0, 1.0]]);
        assert_eq!(moved, vec![-1.0, -2.0, 0.0]);
        assert!(model.compare(&[-1.0, -2.0, 0.5], &[0, 1]).is_err());
    }
}
