//! The tension system `E x = b` (paper Eqs. 33, 35): `E` built column by column from the
//! strands, tendons and motors, its rank diagnosed by the SVD, `E⁺`, `null(E)` and a
//! strictly positive null vector. Invariant: a system is returned only with `E` of full
//! row rank, every motor and loop side determined, and the tendons kept taut by a strictly
//! positive null vector when the routing has open-ended tendons (with capstan friction,
//! whichever way the tendons slide: [`sliding_directions`]); a failing routing is reported
//! with the system it implies.

use super::Validator;
use crate::error::{Error, ImpliedSystem, Result};
use crate::format::MechanismFile;
use crate::model::{
    Body, BodyKind, Loop, Model, Motor, MotorKind, PulleyRole, Row, Tendon, TensionSystem, Unknown,
};
use crate::transmission::{Rate, StrandGeometry};
use nalgebra::DMatrix;

/// A strand's rate (`ẋ` over `q̇` and the driving pulleys' angles) as a column of `E`: its
/// joint coefficients on the joints' rows, a driving pulley's on that pulley's row.
pub(super) fn column_of(
    f: &MechanismFile,
    bodies: &[Body<f64>],
    rows: &[Row],
    rate: &Rate,
) -> Vec<f64> {
    let mut column = vec![0.0; rows.len()];
    for (r, row) in rows.iter().enumerate() {
        if let Row::Joint(j) = row {
            column[r] = rate.joints[*j];
        }
    }
    for &(p, c) in &rate.pulleys {
        let b = bodies.iter().position(|b| b.name == f.pulleys[p].name);
        let row = rows
            .iter()
            .position(|r| Some(r) == b.map(Row::Pulley).as_ref());
        column[row.expect("a driving pulley has its row")] = c;
    }
    column
}

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
        let mut e = vec![vec![0.0; m]; rows.len()];
        for (col, u) in unknowns.iter().enumerate() {
            match u {
                Unknown::Strand(s) => {
                    let column = column_of(f, bodies, &rows, &strands[*s].1.pull_rate);
                    for (row, x) in e.iter_mut().zip(column) {
                        row[col] = x;
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

/// Whether some joint velocity makes every group of guides slide the way `pattern` says:
/// the linear program `pattern_g (u_g · q̇) ≥ 1` for every group (`u_g` its sliding speed
/// per joint velocity) has a solution. Its cone is open, so `≥ 1` loses nothing.
fn reachable(groups: &[Vec<f64>], pattern: &[f64]) -> bool {
    use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome};
    let Some(n) = groups.first().map(Vec::len) else {
        return true;
    };
    let mut lp = Problem::new(OptimizationDirection::Minimize);
    let qd: Vec<_> = (0..n)
        .map(|_| lp.add_var(0.0, (f64::NEG_INFINITY, f64::INFINITY)))
        .collect();
    for (u, sign) in groups.iter().zip(pattern) {
        let terms: Vec<_> = qd.iter().zip(u).map(|(&v, &c)| (v, sign * c)).collect();
        lp.add_constraint(terms.as_slice(), ComparisonOp::Ge, 1.0);
    }
    matches!(lp.solve(), Ok(SolveOutcome::Solution(_)))
}

/// With capstan friction on guides `E` depends on the direction each tendon slides over
/// its guides: the routing must be controllable (full row rank, a null vector that lifts
/// every tendon) for every direction it can take. Guides whose sliding speeds are equal or
/// opposite (`slide` vectors parallel) slide together, so each such group is one sign;
/// every pattern of up to 12 groups is checked at `q = 0` (the wrap angles at the joints'
/// offsets), and a failing one refuses the routing if some joint velocity produces it
/// ([`reachable`]). Beyond 12 groups the patterns checked are the two where every group
/// slides one way and those with one group flipped (a sufficient condition only at run
/// time, where every state's system is checked again).
pub(super) fn sliding_directions(v: &Validator, model: &Model<f64>) -> Result<()> {
    // The guides with friction, by strand and idler, and the group each belongs to with
    // the sign relating its speed to the group's.
    let mut groups: Vec<Vec<f64>> = Vec::new();
    let mut members: Vec<(usize, usize, usize, f64)> = Vec::new();
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
            members.push((s, k, group, sign));
        }
    }
    let n = groups.len();
    if n == 0 {
        return Ok(());
    }
    let patterns: Vec<Vec<f64>> = if n <= 12 {
        (0..1usize << n)
            .map(|bits| {
                (0..n)
                    .map(|i| if bits >> i & 1 == 1 { -1.0 } else { 1.0 })
                    .collect()
            })
            .collect()
    } else {
        let mut p = vec![vec![1.0; n], vec![-1.0; n]];
        for i in 0..n {
            for base in [1.0, -1.0] {
                let mut one = vec![base; n];
                one[i] = -base;
                p.push(one);
            }
        }
        p
    };
    let q = vec![0.0; model.dof];
    for pattern in patterns {
        let mut sigma: Vec<Vec<f64>> = model
            .strands
            .iter()
            .map(|s| vec![0.0; s.idlers.len()])
            .collect();
        for &(s, k, group, sign) in &members {
            sigma[s][k] = sign * pattern[group];
        }
        if let Err(e) = crate::dynamics::system_sliding(model, &q, &sigma) {
            // A pattern no joint velocity produces (groups whose speeds are tied by the
            // joints they share) cannot fail in use: only a reachable one refuses.
            if !reachable(&groups, &pattern) {
                continue;
            }
            let why = match e {
                Error::Tension(why) => why,
                other => other.to_string(),
            };
            let described: Vec<String> = members
                .iter()
                .map(|&(s, k, _, _)| {
                    let body = model.strands[s].idlers[k].body;
                    format!(
                        "`{}` over `{}` towards its {}",
                        model.strands[s].name,
                        model.bodies[body].name,
                        if sigma[s][k] > 0.0 { "exit" } else { "anchor" }
                    )
                })
                .collect();
            let first = model.strands[members[0].0].idlers[members[0].1].body;
            return Err(v.routing(
                &model.bodies[first].name,
                format!(
                    "with capstan friction the routing must be controllable whichever way the \
                     tendons slide, but sliding {} (at q = 0) it is not: {why}; lower `mu` or \
                     route the tendon differently",
                    described.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::reachable;

    /// Three groups sliding at `q̇₁`, `q̇₂` and `q̇₁ + q̇₂`: the third cannot slide backwards
    /// while the first two slide forwards, but every other sign pattern occurs.
    #[test]
    fn a_pattern_of_sliding_directions_is_reachable_only_where_some_joint_velocity_gives_it() {
        let groups = vec![vec![1.0, 0.0], vec![0.0, 1.0], vec![1.0, 1.0]];
        assert!(!reachable(&groups, &[1.0, 1.0, -1.0]));
        assert!(!reachable(&groups, &[-1.0, -1.0, 1.0]));
        assert!(reachable(&groups, &[1.0, 1.0, 1.0]));
        assert!(reachable(&groups, &[1.0, -1.0, 1.0]));
        assert!(reachable(&groups, &[1.0, -1.0, -1.0]));
    }
}
