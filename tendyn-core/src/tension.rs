//! The unknowns at the base: segment tensions, the system `E x = b` and the tension
//! distribution (paper Eqs. 24b, 33, 35 and the "torque resolver" of its ref. 12).
//!
//! - Every segment tension is the strand's last (ground-level) tension plus what the
//!   idlers between them need to turn (Eq. 24b): across an idler of radius `r` and turn
//!   `s`, `T_in = T_out − s (N_axial − τ_f) / r`, `τ_f` its bearing's friction
//!   ([`crate::friction`], zero without).
//! - The rows of `E x = b` are the axial balances of each joint, each driving pulley, and
//!   each loop's pretension. `E` is constant (it is the transmission's virtual-work map),
//!   but where guides with capstan friction make it depend on the state ([`state_matrix`]);
//!   `b` is what the backward recursion leaves over when every unknown is zero, less what
//!   the bearings' friction supplies.
//! - The solution with least norm is `x₀ = E⁺ b`. Redundant open-ended routings add a
//!   null-space part `N λ` so that every tendon stays within its floor and maximum; among
//!   those, the one nearest the objective's target is chosen ([`crate::distribution`],
//!   the one implementation; here its data are gathered from the model and a state the
//!   bounds cannot meet is explained).

use crate::distribution::{self, Line, LineResult, Problem, Status, Work};
use crate::double_double::DoubleDouble;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linalg;
use crate::model::{
    BodyKind, Eliminated, Model, Objective, PulleyRole, Row, Strand, Tendon, TensionSystem, Unknown,
};
use crate::newton_euler::{Load, LoadScalar, Loads};
use crate::real::{Numeric, Real};

/// Axial moment a pulley needs about its own axis to move as it does (inertia and gravity),
/// taken about its centre: `z · (I ω̇ + ω × I ω + c × m a_c)`.
pub fn axial_demand<T: Real>(model: &Model<T>, motion: &[Motion<T>], body: usize) -> T {
    model.bodies[body].axis.dot(motion[body].inertial_moment)
}

/// Tension of every segment of every strand (Eq. 24b), written into `out[s][k]`, each
/// strand's ground-level tension being `ground(unknown)`: a number (the solved unknowns, or
/// zero for `b`) or affine in the unknowns. An idler's tensions balance what its bearing's
/// friction `τ_f` (`friction[body]`, [`crate::friction`]) does not:
/// `T_in = T_out − s (N_axial − τ_f) / r`. A guide with friction scales them by its capstan
/// factor (`capstan[s][k]`, [`crate::friction::capstan_factors`]): `T_in = T_out e^{−σμβ}`.
pub fn segment_tensions<T: Real, S: LoadScalar<T>>(
    model: &Model<T>,
    motion: &[Motion<T>],
    friction: &[T],
    capstan: &[Vec<T>],
    ground: impl Fn(usize) -> S,
    out: &mut [Vec<S>],
) {
    for (s, strand) in model.strands.iter().enumerate() {
        let last = strand.segments.len() - 1;
        let mut t = ground(strand.unknown);
        out[s][last] = t;
        for k in (0..last).rev() {
            let idler = &strand.idlers[k];
            // A frictionless guide passes the tension on unchanged (it takes the tendon's
            // pull on its carrier); one with friction by the capstan law.
            if idler.guide.is_some() {
                if idler.capstan().is_some() {
                    t = t.scale(capstan[s][k]);
                }
                out[s][k] = t;
                continue;
            }
            let step = T::from_f64(idler.turn / idler.radius);
            let mut moment = axial_demand(model, motion, idler.body);
            if model.bodies[idler.body].friction.is_some() {
                moment = moment - friction[idler.body];
            }
            t = t.add_known(-(step * moment));
            out[s][k] = t;
        }
    }
}

/// The balance rows into `out` (one per row of `E`), before motors and explicit tendons
/// are added: numbers (`b` of
/// `E x = b`, from a pass with every unknown zero) or affine forms (whose constants are
/// `b`). For a joint, `τ_j + Σ_coupled c_Pj τ_P`; for a driving pulley, its `τ`; for a
/// loop, its pretension (a constant: the loop's row of `E` carries the strand tensions).
/// Each `τ` is the body's axial moment less what its bearing's friction provides
/// (`friction[body]`): what the tendons and motors must.
/// The affine rows' coefficients are `−E` on the strand columns, which tests check against
/// the transmission's derivation.
pub fn balance_rows<T: Real, L: Load<T>>(
    model: &Model<T>,
    loads: &Loads<T, L>,
    friction: &[T],
    out: &mut [L::Scalar],
) {
    let n_unknowns = model.system.unknowns.len();
    let axial = |b: usize| {
        if model.bodies[b].friction.is_some() {
            loads.axial[b].add_known(-friction[b])
        } else {
            loads.axial[b]
        }
    };
    let rows = model.system.rows.iter().map(|row| match row {
        Row::Joint(j) => {
            let mut r = axial(*j);
            for (i, b) in model.bodies.iter().enumerate() {
                if matches!(
                    b.kind,
                    BodyKind::Pulley {
                        role: PulleyRole::Coupled,
                        ..
                    }
                ) {
                    r = r.add(&axial(i).scale(b.coupling[*j]));
                }
            }
            r
        }
        Row::Pulley(b) => axial(*b),
        Row::Pretension(l) => L::Scalar::known(T::from_f64(model.loops[*l].pretension), n_unknowns),
    });
    for (o, r) in out.iter_mut().zip(rows) {
        *o = r;
    }
}

/// The tension system at a state where guides with friction make `E` depend on it:
/// `matrix` is `E(σ, q)` ([`state_matrix`]); its pseudo-inverse and null space follow by
/// Householder QR ([`crate::linalg`]). An error where the state leaves `E` without full
/// row rank or, with one null direction, without a null vector that lifts every tendon.
pub fn system_at<T: Numeric>(model: &Model<T>, matrix: Vec<Vec<T>>) -> Result<TensionSystem<T>> {
    let constant = &model.system;
    let (pseudo_inverse, null_space) =
        crate::linalg::pseudo_inverse_and_null_space_of_rows(&matrix);
    // Full row rank, checked where it matters: `E E⁺ = I` to round-off of its size.
    let size = matrix
        .iter()
        .flatten()
        .fold(T::zero(), |m, x| if x.abs() > m { x.abs() } else { m });
    let tolerance = T::from_f64(T::unit_roundoff().sqrt());
    for (i, row) in matrix.iter().enumerate() {
        for j in 0..matrix.len() {
            let e: T = row
                .iter()
                .zip(&pseudo_inverse)
                .fold(T::zero(), |s, (a, p)| s + *a * p[j]);
            let want = if i == j { T::one() } else { T::zero() };
            let off = (e - want).abs();
            if !off.is_finite() || off > tolerance * (T::one() + size) {
                return Err(Error::Tension(
                    "the guides' friction leaves the tension system without full rank at this \
                     state: some joint or driving pulley cannot be balanced"
                        .into(),
                ));
            }
        }
    }
    let positive_null = match null_space.as_slice() {
        [v] => {
            let along = |t: &Tendon| v[t.unknown];
            // Oriented by the tendon component largest in size (one near zero could have
            // either sign by round-off).
            let largest =
                model
                    .tendons
                    .iter()
                    .map(along)
                    .reduce(|a, b| if b.abs() > a.abs() { b } else { a });
            let sign = if largest.is_some_and(|x| x < T::zero()) {
                -T::one()
            } else {
                T::one()
            };
            // Not strictly positive, NaN included.
            let taut = |t: &Tendon| sign * along(t) > T::zero();
            if !model.tendons.iter().all(taut) {
                return Err(Error::Tension(
                    "at this state the guides' friction leaves no way to raise every tendon \
                     together (the null vector of the tension system has components of both \
                     signs): the routing is not controllable in this direction of sliding"
                        .into(),
                ));
            }
            // Scaled to a smallest tendon component of 1, as the model's positive null
            // vector is and the distribution's tolerance expects (Status::of_line).
            let least = model
                .tendons
                .iter()
                .map(|t| sign * along(t))
                .fold(None, |m: Option<T>, x| {
                    Some(m.map_or(x, |m| if x < m { x } else { m }))
                })
                .unwrap_or(T::one());
            let scale = sign / least;
            Some(v.iter().map(|x| scale * *x).collect())
        }
        _ => None,
    };
    Ok(solved(
        constant,
        matrix,
        pseudo_inverse,
        null_space,
        positive_null,
    ))
}

/// A state's system: the model's unknowns and rows with the state's `E` and its solution
/// (no condition number: `NaN`).
fn solved<T>(
    constant: &TensionSystem<T>,
    matrix: Vec<Vec<T>>,
    pseudo_inverse: Vec<Vec<T>>,
    null_space: Vec<Vec<T>>,
    positive_null: Option<Vec<T>>,
) -> TensionSystem<T> {
    TensionSystem {
        unknowns: constant.unknowns.clone(),
        rows: constant.rows.clone(),
        matrix,
        pseudo_inverse,
        null_space,
        positive_null,
        condition: f64::NAN,
        eliminated: None,
    }
}

/// `E` at a state where guides with friction make it depend on the state, `E(σ, q)`: the
/// model's, but a strand over such guides has the column `Σ_k f_k shares[k]`, `f_k =
/// T_k / T` the ratio of segment `k`'s tension to the ground-level one (the product of the
/// capstan factors `capstan[s][·]` between them, [`crate::friction::capstan_factors`]) and
/// `shares[k]` segment `k`'s share of the column ([`crate::model::Strand::shares`]; the
/// tendon's virtual power is `Σ_k T_k (rate of segment k)`). Segments of one ratio are
/// summed before they are scaled, so a strand over no such guide keeps its constant column.
pub fn state_matrix<T: Real>(model: &Model<T>, capstan: &[Vec<T>]) -> Vec<Vec<T>> {
    let mut matrix = model.system.matrix.clone();
    for (strand, factors) in model.strands.iter().zip(capstan) {
        if !strand.idlers.iter().any(|idler| idler.capstan().is_some()) {
            continue;
        }
        let mut column = vec![T::zero(); matrix.len()];
        let mut ratio = T::one();
        for_each_run(strand, matrix.len(), |share, below| {
            for (c, &p) in column.iter_mut().zip(share) {
                *c = *c + ratio * p;
            }
            if let Some(guide) = below {
                ratio = ratio * factors[guide];
            }
        });
        // The pretension rows keep the model's entries (strands over guides are never a
        // loop's sides, whose entries they are).
        for (r, (row, c)) in matrix.iter_mut().zip(column).enumerate() {
            if !matches!(model.system.rows[r], Row::Pretension(_)) {
                row[strand.unknown] = c;
            }
        }
    }
    matrix
}

/// `strand`'s runs, the stretches between guides with friction where the tension is one,
/// from the ground end towards the anchor, as the tensions are (Eq. 24b): `visit` gets
/// each run's share of the strand's column (its segments' shares summed,
/// [`crate::model::Strand::shares`]) and the guide with friction that ends it towards the
/// anchor (`None` at the anchor). Run `i`'s tension is the ground-level one times the
/// capstan factors of the guides that end runs `0..i` ([`state_matrix`]). One buffer
/// serves every run: `state_matrix` is on the runtime's path at every state.
pub(crate) fn for_each_run<T: Real>(
    strand: &Strand<T>,
    rows: usize,
    mut visit: impl FnMut(&[T], Option<usize>),
) {
    let mut pending = vec![T::zero(); rows];
    for k in (0..strand.shares.len()).rev() {
        for (p, &x) in pending.iter_mut().zip(&strand.shares[k]) {
            *p = *p + x;
        }
        let below = k
            .checked_sub(1)
            .filter(|&g| strand.idlers[g].capstan().is_some());
        if k == 0 || below.is_some() {
            visit(&pending, below);
            pending.iter_mut().for_each(|p| *p = T::zero());
        }
    }
}

/// The most boxes of capstan factors [`Elimination::holds_while_sliding`] tries before the
/// directions of sliding validation checks.
const LEADING_BOXES: usize = 256;

/// The least fraction of its column's largest entry a pivot of [`Elimination`] may have:
/// each step of the model's `E` then grows the entries by at most `1 + 1/PIVOT_THRESHOLD`
/// (at a state, capstan factors scale the columns, and with them the multipliers, by up
/// to their ratios; `Elimination::holds_while_sliding` keeps the pivots from zero), while
/// the sparsest row can be chosen among near-equals (sparse LU codes take 0.1; the systems
/// here are at most a few rows, where stability is cheaper than the few operations a
/// sparser row saves).
const PIVOT_THRESHOLD: f64 = 0.5;

/// How generated code solves a state's tension system where guides with friction make
/// `E(σ, q)` depend on the state: by elimination on the columns of every unknown but the
/// free ones (one per null direction, always tendons: motor and loop columns are
/// independent of all others, or the null space would reach them), its rows taken in the
/// order a threshold-pivoting elimination of the model's `E` takes them (the sparsest of
/// the rows near the largest, so that the traced code fills in least). Chosen once,
/// from the model, so the traced code does no pivoting: friction scales the columns of
/// `E` by capstan factors `e^{±μβ}` and leaves its pattern of zeros, but a square part that
/// is regular in the model may still turn singular at some state of a controllable routing,
/// so the generator keeps an order only where [`Elimination::holds_while_sliding`].
///
/// One null direction: the free unknown is first the lead tendon, with the largest
/// component of the model's positive null vector `n` (`n_k` is proportional to the
/// determinant of `E` without column `k`, so of all the square parts of `E` the one
/// eliminated is the farthest from singular), then each other tendon by falling `n_k`
/// ([`Elimination::candidates`]). Several: the columns a completely pivoting elimination of
/// the model's `E` leaves without a pivot (the usual rank-revealing choice).
#[derive(Clone, Debug, PartialEq)]
pub struct Elimination {
    /// The eliminated unknowns, one per row of `E`.
    pub columns: Vec<usize>,
    /// The rows of `E` in pivot order.
    pub rows: Vec<usize>,
    /// The free unknowns, one per null direction, each giving one null vector with a 1 in
    /// its place and 0 at the others.
    pub free: Vec<usize>,
}

impl Elimination {
    /// The order for `model`'s system (the model's `E`, frictionless, at its nominal
    /// parameters); `None` if a free unknown would not be a tendon (which a validated
    /// model's rank rules out, up to round-off).
    pub fn of<T: Numeric>(model: &Model<T>) -> Option<Elimination> {
        let free = match model.system.null_space.len() {
            0 => Vec::new(),
            1 => vec![lead_tendon(model)],
            _ => unpivoted_columns(numbers(&model.system.matrix)),
        };
        Elimination::with_free(model, free)
    }

    /// Every order worth trying, the best first: [`Elimination::of`]'s, then, with one
    /// null direction, each other tendon free, by falling component of the positive null
    /// vector (a tendon whose component is larger leaves a square part farther from
    /// singular). Where the lead tendon's order meets a zero pivot for some direction of
    /// sliding, another tendon's may not.
    pub fn candidates<T: Numeric>(model: &Model<T>) -> Vec<Elimination> {
        let mut out: Vec<Elimination> = Elimination::of(model).into_iter().collect();
        if let (1, Some(n)) = (model.system.null_space.len(), &model.system.positive_null) {
            let mut others: Vec<usize> = (model.tendons.iter())
                .map(|t| t.unknown)
                .filter(|&u| u != lead_tendon(model))
                .collect();
            others.sort_by(|&a, &b| n[b].to_f64().total_cmp(&n[a].to_f64()));
            out.extend(
                others
                    .into_iter()
                    .filter_map(|u| Elimination::with_free(model, vec![u])),
            );
        }
        out
    }

    /// The order with the unknowns `free` left free and the rest eliminated in a threshold-
    /// pivoting elimination of the model's `E`; `None` if a free unknown is not a tendon.
    fn with_free<T: Numeric>(model: &Model<T>, free: Vec<usize>) -> Option<Elimination> {
        let system = &model.system;
        let matrix = numbers(&system.matrix);
        if free.iter().any(|&u| !is_tendon_unknown(model, u)) {
            return None;
        }
        let columns: Vec<usize> = (0..system.unknowns.len())
            .filter(|u| !free.contains(u))
            .collect();
        let n = system.rows.len().min(columns.len());
        let mut e: Vec<Vec<f64>> = (matrix.iter())
            .map(|row| columns.iter().map(|&c| row[c]).collect())
            .collect();
        let mut rows: Vec<usize> = (0..system.rows.len()).collect();
        for j in 0..n {
            // Threshold pivoting with the sparsest row (Markowitz's rule for a fixed
            // column): of the rows whose entry is within PIVOT_THRESHOLD of the column's
            // largest, the one with the fewest other nonzeros left, so that elimination
            // fills in least and the traced code forms fewest terms; the largest entry
            // among those.
            let largest = (j..rows.len()).fold(0.0f64, |m, i| m.max(e[i][j].abs()));
            let others = |i: usize| (j + 1..n).filter(|&k| e[i][k] != 0.0).count();
            let pivot = (j..rows.len())
                .filter(|&i| e[i][j].abs() >= PIVOT_THRESHOLD * largest)
                .reduce(|a, b| {
                    let better = (others(b), -e[b][j].abs()) < (others(a), -e[a][j].abs());
                    if better {
                        b
                    } else {
                        a
                    }
                })
                .unwrap_or(j);
            e.swap(j, pivot);
            rows.swap(j, pivot);
            eliminate_below(&mut e, j, j, j..n);
        }
        Some(Elimination {
            columns,
            rows,
            free,
        })
    }

    /// Whether this order keeps every pivot of the elimination away from zero, with the
    /// sign it has in the model's `E`, at every direction of sliding validation checks
    /// (`validate::Sliding`; each pivot beyond `1e-12` of `E`'s largest entry) and over the
    /// joints' ranges as validation covers them: where a guide's wrap angle varies over the
    /// ranges, by the same search of boxes of joint angles (`Sliding::state_that_fails`),
    /// so that a routing validation accepts is refused here only where some state within
    /// the ranges breaks a pivot, or the search does not settle. The products of the first
    /// pivots are minors of `E`, affine in each capstan factor taken alone as the null
    /// vector's are (docs/format.md §6a), so where validation's points are the corners of
    /// the boxes the directions reach, no state in between makes the traced code divide by
    /// zero. Before the points, boxes of capstan factors may show it for every factor the
    /// guides can take at once (docs/format.md §6a): the pivots are ratios of the leading
    /// minors of `E` in this order, which then keep their signs and never vanish (the
    /// `1e-12` margin is taken at the boxes' centres only).
    pub fn holds_while_sliding(&self, model: &Model<f64>) -> bool {
        let sliding = crate::validate::Sliding::of(model);
        let without = self.pivots(&model.system.matrix);
        let fails = |e: Vec<Vec<f64>>| -> Option<String> {
            let size = e.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
            let kept = |(p, w): (&f64, &f64)| p.signum() == w.signum() && p.abs() > 1e-12 * size;
            let holds = self.pivots(&e).iter().zip(&without).all(kept);
            (!holds).then(|| "a pivot of the elimination vanishes or turns".to_string())
        };
        let leading: Vec<(Vec<usize>, Vec<usize>)> = (1..=self.rows.len())
            .map(|k| (self.rows[..k].to_vec(), self.columns[..k].to_vec()))
            .collect();
        if (sliding.on_every_factor(model, &leading, &fails, LEADING_BOXES)).is_some() {
            return true;
        }
        let ranged = sliding.ranged(model);
        sliding.points().into_iter().all(|point| {
            if ranged {
                sliding.state_that_fails(model, &point, &fails).is_none()
            } else {
                fails(sliding.matrix(model, &point)).is_none() || !sliding.reachable(&point)
            }
        })
    }

    /// The pivots of the elimination of `e` in this order, without pivoting.
    fn pivots(&self, e: &[Vec<f64>]) -> Vec<f64> {
        let n = self.rows.len();
        let mut factors: Vec<f64> = (self.rows.iter())
            .flat_map(|&r| self.columns.iter().map(move |&c| e[r][c]))
            .collect();
        crate::linalg::lu_factor(&mut factors, n);
        (0..n).map(|j| factors[j * n + j]).collect()
    }
}

/// `E` in f64.
fn numbers<T: Numeric>(matrix: &[Vec<T>]) -> Vec<Vec<f64>> {
    (matrix.iter())
        .map(|row| row.iter().map(|x| x.to_f64()).collect())
        .collect()
}

/// The columns of `e` (full row rank) that Gaussian elimination with complete pivoting
/// leaves without a pivot, in increasing order.
fn unpivoted_columns(mut e: Vec<Vec<f64>>) -> Vec<usize> {
    let width = e.first().map_or(0, Vec::len);
    let mut pivoted = vec![false; width];
    for j in 0..e.len() {
        let best = (j..e.len())
            .flat_map(|i| (0..width).filter(|&c| !pivoted[c]).map(move |c| (i, c)))
            .reduce(|a, b| {
                if e[b.0][b.1].abs() > e[a.0][a.1].abs() {
                    b
                } else {
                    a
                }
            });
        let Some((i, c)) = best else { break };
        e.swap(j, i);
        pivoted[c] = true;
        eliminate_below(&mut e, j, c, 0..width);
    }
    (0..width).filter(|&c| !pivoted[c]).collect()
}

/// One step of Gaussian elimination: row `j` of `e` (the pivot row) subtracted from every
/// row below it so that column `c` (the pivot's) vanishes there, over the columns `span`.
fn eliminate_below(e: &mut [Vec<f64>], j: usize, c: usize, span: core::ops::Range<usize>) {
    let (above, below) = e.split_at_mut(j + 1);
    let pivot_row = &above[j];
    for row in below {
        let f = row[c] / pivot_row[c];
        if f.is_finite() {
            for (x, p) in row[span.clone()].iter_mut().zip(&pivot_row[span.clone()]) {
                *x -= f * p;
            }
        }
    }
}

/// [`system_at`] in straight-line arithmetic, for the code generator to trace (`Real`
/// only: no pivoting, no comparison). `E⁺` is not formed: the `L U` factors of the square
/// part of `E` that `order` eliminates are kept ([`Eliminated`]), and [`solution`] solves
/// with them. Each free unknown `f` gives a null vector `z` with `z_f = 1`, 0 at the other
/// free unknowns, and `E_B z_B = −E_f` for the others; where the routing stays
/// controllable every tendon component of the one direction is positive.
/// - One null direction: `null_space` holds `p = z` itself (not normalised), scaled to a
///   smallest tendon component of 1, as the distribution's tolerance for maxima expects
///   (where no tendon has a maximum, left as it is: the distribution along `p` does not
///   depend on its length).
/// - Several: `null_space` holds the `z` orthonormalised over the tendons by modified
///   Gram-Schmidt, as [`distribution::solve`] takes a basis; `positive_null` is `None`.
///
/// Checks nothing: generated code does not report a state where friction leaves the
/// routing uncontrollable (the runtime solver does).
pub fn system_traced<T: Real>(
    model: &Model<T>,
    matrix: Vec<Vec<T>>,
    order: &Elimination,
) -> TensionSystem<T> {
    let constant = &model.system;
    let n = order.rows.len();
    let mut factors: Vec<T> = (order.rows.iter())
        .flat_map(|&r| {
            order
                .columns
                .iter()
                .map(|&c| matrix[r][c])
                .collect::<Vec<_>>()
        })
        .collect();
    crate::linalg::lu_factor(&mut factors, n);
    let mut null_space: Vec<Vec<T>> = (order.free.iter())
        .map(|&f| {
            let mut y: Vec<T> = order.rows.iter().map(|&r| -matrix[r][f]).collect();
            crate::linalg::lu_substitute(&factors, &mut y);
            let mut z = vec![T::zero(); constant.unknowns.len()];
            z[f] = T::one();
            for (&c, y) in order.columns.iter().zip(y) {
                z[c] = y;
            }
            z
        })
        .collect();
    let positive_null = match &mut null_space[..] {
        [p] => {
            // The smallest tendon component, as `−max(−p)`: only the maxima's status
            // needs it (the tensions along `p` do not depend on its length).
            if model.tendons.iter().any(|t| t.max_tension.is_some()) {
                let least = (model.tendons.iter())
                    .map(|t| p[t.unknown])
                    .reduce(|a, b| -((-a).max(-b)))
                    .unwrap_or(T::one());
                let scale = T::one() / least;
                for x in p.iter_mut() {
                    *x = *x * scale;
                }
            }
            Some(p.clone())
        }
        basis => {
            orthonormalise_over_tendons(model, basis);
            None
        }
    };
    let mut system = solved(constant, matrix, Vec::new(), null_space, positive_null);
    system.eliminated = Some(Eliminated {
        order: order.clone(),
        factors,
    });
    system
}

/// Modified Gram-Schmidt on `basis`, with inner products over the tendon components
/// alone (the others vanish in exact arithmetic) and every component carried along, so
/// that each vector stays in the null space.
fn orthonormalise_over_tendons<T: Real>(model: &Model<T>, basis: &mut [Vec<T>]) {
    let dot = |a: &[T], b: &[T]| dot_over_tendons(model, a, b);
    for j in 0..basis.len() {
        let (done, rest) = basis.split_at_mut(j);
        let v = &mut rest[0];
        for q in done.iter() {
            let along = dot(q, v);
            for (x, q) in v.iter_mut().zip(q) {
                *x = *x - along * *q;
            }
        }
        let inverse = T::one() / dot(v, v).sqrt();
        for x in v.iter_mut() {
            *x = *x * inverse;
        }
    }
}

/// `Σ a_k b_k` over the tendons' unknowns `k`.
fn dot_over_tendons<T: Real>(model: &Model<T>, a: &[T], b: &[T]) -> T {
    (model.tendons.iter()).fold(T::zero(), |s, t| s + a[t.unknown] * b[t.unknown])
}

/// The unknown of the tendon with the largest component of the positive null vector (the
/// first tendon's without one): the free unknown of [`Elimination`].
fn lead_tendon<T: Numeric>(model: &Model<T>) -> usize {
    let Some(n) = &model.system.positive_null else {
        return model.tendons.first().map_or(0, |t| t.unknown);
    };
    model
        .tendons
        .iter()
        .map(|t| t.unknown)
        .reduce(|a, b| if n[b] > n[a] { b } else { a })
        .unwrap_or(0)
}

/// A solution of `system` (the model's, or a state's): the minimal-norm one `x₀ = E⁺ b`,
/// but in a state's system traced for generated code ([`system_traced`]), which holds no
/// `E⁺`: there the one whose free unknown is zero (its part along the null direction is
/// [`minimal_norm`]'s to remove and [`along_line`]'s to account for: the distribution along
/// the null direction starts from any solution, and the least-norm one costs more).
///
/// A loop's pretension is added exactly rather than through `E⁺`: the two strand columns
/// of a loop are negatives of each other in every row but its pretension row (every term
/// of a strand's rate carries one turn sign, and the two sides turn oppositely everywhere),
/// so both sides at the pretension solve that part of `b` exactly, and that solution is
/// orthogonal to the null space. Passing the pretension through the rounded `E⁺` instead
/// leaves an error of about `u · pretension` in every motor torque.
pub fn solution<T: Real>(model: &Model<T>, system: &TensionSystem<T>, b: &[T], out: &mut [T]) {
    let dynamic = |r: usize| !matches!(system.rows[r], Row::Pretension(_));
    if let Some(Eliminated { order, factors }) = &system.eliminated {
        let mut y: Vec<T> = (order.rows.iter())
            .map(|&r| if dynamic(r) { b[r] } else { T::zero() })
            .collect();
        crate::linalg::lu_substitute(factors, &mut y);
        for o in out.iter_mut() {
            *o = T::zero();
        }
        for (&c, y) in order.columns.iter().zip(y) {
            out[c] = y;
        }
    }
    for (o, row) in out.iter_mut().zip(&system.pseudo_inverse) {
        let mut s = T::zero();
        for (r, (p, v)) in row.iter().zip(b).enumerate() {
            if dynamic(r) {
                s = s + *p * *v;
            }
        }
        *o = s;
    }
    for l in &model.loops {
        for strand in l.strands {
            let k = model.strands[strand].unknown;
            out[k] = out[k] + T::from_f64(l.pretension);
        }
    }
}

/// The minimal-norm solution from a [`solution`] `x` of `system`, in place: `x` itself
/// where the system holds `E⁺`; in a traced state's system, `x` less its part in the null
/// space: along the one direction `p`, `x − (pᵀx / pᵀp) p`; along a basis orthonormal over
/// the tendons ([`system_traced`]), `x − Σ q (qᵀx)`. The products are over the tendons:
/// the other components of a null vector vanish (validation keeps every motor and loop
/// side determined), so rounding in them must not weigh the motor torques and loop sides
/// in, nor cost operations in generated code.
pub fn minimal_norm<T: Real>(model: &Model<T>, system: &TensionSystem<T>, x: &mut [T]) {
    if system.eliminated.is_none() {
        return;
    }
    let dot = |a: &[T], b: &[T]| dot_over_tendons(model, a, b);
    for v in &system.null_space {
        let along = match &system.positive_null {
            Some(_) => dot(v, x) / dot(v, v),
            None => dot(v, x),
        };
        for (o, v) in x.iter_mut().zip(v) {
            *o = *o - along * *v;
        }
    }
}

/// `c_k`, the tension the objective aims tendon `k` at: 0 (least norm) or the middle of
/// its floor and maximum (centered; validation requires the maximum).
fn aim(model_objective: Objective, t: &Tendon) -> f64 {
    match (model_objective, t.max_tension) {
        (Objective::Centered, Some(max)) => 0.5 * (t.floor + max),
        _ => 0.0,
    }
}

/// The maxima as [`distribution`] takes them: `f64::INFINITY` where there is none.
fn max_of(t: &Tendon) -> f64 {
    t.max_tension.unwrap_or(f64::INFINITY)
}

/// The distribution of a one-dimensional null space in closed form
/// ([`distribution::along_line`] along the positive null vector), applied to the unknowns
/// `x` (a [`solution`] on entry). Generic over [`Real`]: the code generator traces it.
pub fn along_line<T: Real>(
    model: &Model<T>,
    system: &TensionSystem<T>,
    x: &mut [T],
) -> LineResult<T> {
    let p = system
        .positive_null
        .as_ref()
        .expect("a redundant routing has a positive null vector");
    let direction: Vec<T> = model.tendons.iter().map(|t| p[t.unknown]).collect();
    let floor: Vec<f64> = model.tendons.iter().map(|t| t.floor).collect();
    let max: Vec<f64> = model.tendons.iter().map(max_of).collect();
    let mut tensions: Vec<T> = model.tendons.iter().map(|t| x[t.unknown]).collect();
    // μ* = pᵀ(c − T₀) / pᵀp, where `pᵀT₀ = 0` for the minimal-norm `T₀`: zero, exactly,
    // for the least-norm objective. A traced state's solution is not the minimal-norm one.
    let particular = system.eliminated.is_some();
    let target = if model.objective == Objective::LeastNorm && !particular {
        T::zero()
    } else {
        let (pc, pp) = (model.tendons.iter().zip(&direction).zip(&tensions)).fold(
            (T::zero(), T::zero()),
            |(pc, pp), ((t, &pk), &tk)| {
                let mut c = T::from_f64(aim(model.objective, t));
                if particular {
                    c = c - tk;
                }
                (pc + pk * c, pp + pk * pk)
            },
        );
        pc / pp
    };
    let line = Line {
        direction: &direction,
        floor: &floor,
        max: &max,
        target,
    };
    let result = distribution::along_line(&line, &mut tensions);
    for (t, v) in model.tendons.iter().zip(tensions) {
        x[t.unknown] = v;
    }
    result
}

/// The model's bounds over `system`'s null space as a [`Problem`] of
/// [`distribution::solve`] (the code generator reads its constants from it too).
pub fn bounds<'m, T: Real>(
    model: &'m Model<T>,
    system: &'m TensionSystem<T>,
) -> impl Problem<T> + 'm {
    Bounds::new(model, system)
}

/// Subsets of `d + 1` tendons beyond which [`facets`] tries none: each facet found costs a
/// run `K` multiply-adds where the floors are met and a maximum is not.
const FACET_CANDIDATES: usize = 64;

/// The facets of the minimal-norm tensions that `problem`'s bounds allow, for a null space
/// that is a constant (generated code's [`distribution::Facet`]s), as normals `w` over the
/// tendons with `‖w‖₁ = 1` and their supports.
///
/// By Farkas' lemma, no tensions within the bounds produce the motion exactly when
/// `wᵀT₀ > c(w) = max {wᵀT : floor ≤ T ≤ max}` for some `w` orthogonal to the null space
/// (`wᵀT = wᵀT₀` for every `T = T₀ + N λ`). On that space of dimension `K − d`, `wᵀT₀ −
/// c(w)` is linear wherever the signs of `w` are fixed, so it is positive somewhere exactly
/// when it is at an edge of such a region: a `w` that vanishes on all but `d + 1` tendons,
/// the null vector of the basis restricted to them. Each is computed in double-double
/// from the `f64` basis the problem holds (so that, rounded, it is orthogonal to that basis
/// to about one ulp), taken with both signs, and kept where its support is finite (a tendon
/// with no maximum that `w` would raise gives none). Where the restricted basis has lower
/// rank, its null space has more than one dimension and the one vector taken from it is
/// still orthogonal to the basis: a valid inequality, if not an edge. None where there are
/// more than `FACET_CANDIDATES` subsets: the distribution then finds such states by its own
/// steps.
pub fn facets<P: Problem<f64>>(problem: &P) -> Vec<(Vec<f64>, f64)> {
    let (k, d) = (problem.tendons(), problem.directions());
    let mut subsets = Vec::new();
    let mut subset: Vec<usize> = (0..=d).collect();
    if d + 1 > k {
        return Vec::new();
    }
    // Every (d + 1)-subset of the tendons in lexicographic order, up to the limit.
    loop {
        if subsets.len() == FACET_CANDIDATES {
            return Vec::new();
        }
        subsets.push(subset.clone());
        let Some(i) = (0..=d).rev().find(|&i| subset[i] < k - 1 - (d - i)) else {
            break;
        };
        subset[i] += 1;
        for j in i + 1..=d {
            subset[j] = subset[j - 1] + 1;
        }
    }
    let mut found: Vec<(Vec<f64>, f64)> = Vec::new();
    for subset in subsets {
        let rows: Vec<Vec<DoubleDouble>> = (0..d)
            .map(|i| subset.iter().map(|&t| problem.null(i, t).into()).collect())
            .collect();
        let (_, null) = linalg::pseudo_inverse_and_null_space_of_rows(&rows);
        let [along] = null.as_slice() else {
            continue;
        };
        let norm: DoubleDouble = along.iter().map(|x| x.abs()).sum();
        // (A non-finite null vector, from a non-finite basis, gives no facet.)
        if !norm.to_f64().is_normal() {
            continue;
        }
        for sign in [1.0, -1.0] {
            let mut w = vec![0.0; k];
            for (&t, x) in subset.iter().zip(along) {
                w[t] = (*x / norm * sign).to_f64();
            }
            let support: f64 = (0..k)
                .map(|t| match w[t] {
                    x if x > 0.0 => x * problem.max(t),
                    x if x < 0.0 => x * problem.floor(t),
                    _ => 0.0,
                })
                .sum();
            let known = found
                .iter()
                .any(|(v, _)| v.iter().zip(&w).all(|(a, b)| (a - b).abs() <= 1e-12));
            if support.is_finite() && !known {
                found.push((w, support));
            }
        }
    }
    found
}

struct Bounds<'m, T> {
    model: &'m Model<T>,
    system: &'m TensionSystem<T>,
    target: Vec<T>,
    inverse_length: Vec<T>,
}

impl<'m, T: Real> Bounds<'m, T> {
    fn new(model: &'m Model<T>, system: &'m TensionSystem<T>) -> Self {
        let target = system
            .null_space
            .iter()
            .map(|v| {
                model.tendons.iter().fold(T::zero(), |s, t| {
                    s + v[t.unknown] * T::from_f64(aim(model.objective, t))
                })
            })
            .collect();
        let null = &system.null_space;
        let inverse_length = model
            .tendons
            .iter()
            .map(|t| distribution::inverse_length(null.iter().map(|v| v[t.unknown])))
            .collect();
        Bounds {
            model,
            system,
            target,
            inverse_length,
        }
    }
}

impl<T: Real> Problem<T> for Bounds<'_, T> {
    fn tendons(&self) -> usize {
        self.model.tendons.len()
    }
    fn directions(&self) -> usize {
        self.system.null_space.len()
    }
    fn null(&self, d: usize, k: usize) -> T {
        self.system.null_space[d][self.model.tendons[k].unknown]
    }
    fn floor(&self, k: usize) -> f64 {
        self.model.tendons[k].floor
    }
    fn max(&self, k: usize) -> f64 {
        max_of(&self.model.tendons[k])
    }
    fn target(&self, d: usize) -> T {
        self.target[d]
    }
    fn inverse_length(&self, k: usize) -> T {
        self.inverse_length[k]
    }
}

/// The tension distribution for a null space of any dimension (module
/// [`distribution`]): every open-ended tendon within its floor and `max_tension`, the
/// objective least. `x` holds the minimal-norm solution on entry and the distributed one
/// on return. When no tensions within the bounds produce the motion, the error names the
/// tendons whose bounds block and what they can produce.
pub fn distribute<T: Numeric>(
    model: &Model<T>,
    system: &TensionSystem<T>,
    x: &mut [T],
) -> Result<()> {
    let d = system.null_space.len();
    let k = model.tendons.len();
    if d == 0 || k == 0 {
        return Ok(());
    }
    let t0: Vec<T> = model.tendons.iter().map(|t| x[t.unknown]).collect();
    let not_finite = |x: &[T]| {
        model
            .tendons
            .iter()
            .find(|t| !x[t.unknown].is_finite())
            .map(|t| {
                Error::Tension(format!(
                    "tension of `{}` is not finite ({})",
                    t.name,
                    x[t.unknown].to_f64()
                ))
            })
    };
    if let Some(e) = not_finite(x) {
        return Err(e);
    }
    let (status, certificate) = if d == 1 {
        let r = along_line(model, system, x);
        let status = r
            .excess
            .map_or(Status::Feasible, |(e, s)| Status::of_line(e, s, k));
        (
            status,
            (status == Status::MaxExceeded).then(|| line_certificate(model, system, &t0)),
        )
    } else {
        let problem = Bounds::new(model, system);
        let mut reals = vec![T::zero(); Work::<T>::reals(d)];
        let mut active = vec![0usize; d];
        // Buffers of the size `Work::reals` asks for always split.
        let Some(mut work) = Work::split(&mut reals, &mut active, d) else {
            return Err(Error::Tension("work buffers of the wrong size".into()));
        };
        let mut tensions = vec![T::zero(); k];
        let mut w = vec![T::zero(); k];
        let status = distribution::solve(&problem, &t0, &mut work, &mut tensions, Some(&mut w));
        for (t, v) in model.tendons.iter().zip(&tensions) {
            x[t.unknown] = *v;
        }
        (status, Some(w))
    };
    match status {
        Status::Feasible => {}
        Status::MaxExceeded => {
            let w: Vec<f64> = certificate
                .unwrap_or_default()
                .iter()
                .map(|v| v.to_f64())
                .collect();
            let t0: Vec<f64> = t0.iter().map(|v| v.to_f64()).collect();
            return Err(Error::Tension(blocked(model, system, &t0, &w)));
        }
        // Validation covers the wrap angles the joints' ranges allow (those at q = 0
        // without them), at every capstan factor or every way of sliding unless `check`
        // says otherwise: floors that cannot be met here are capstan factors that multiply
        // past what f64 resolves, or a state validation did not cover.
        Status::Unresolved if model.has_capstan() => {
            return Err(Error::Tension(
                "at this state no tensions were found that keep every tendon at its floor: \
                 the guides' capstan factors make the tensions it needs differ by more than \
                 floating point resolves, or leave the routing uncontrollable in this \
                 direction of sliding at a state validation did not cover (wrap angles \
                 beyond the joints' `range`s, or beyond those at q = 0 without them; or, \
                 where `tendyn check` says `only at` or `not every state between`, a way or \
                 state it did not check); lower `mu`, or give the joints the `range`s they \
                 move in"
                    .into(),
            ))
        }
        Status::Unresolved => {
            return Err(Error::Tension(
                "the distribution did not finish within its bound on steps (round-off at a \
                 degenerate state); please report the mechanism and the state"
                    .into(),
            ))
        }
    }
    not_finite(x).map_or(Ok(()), Err)
}

/// The certificate of an empty interval along the positive null vector `p`: the floor
/// `i` that bounds `μ` highest from below and the maximum `j` that bounds it lowest from
/// above give `w = e_j / p_j − e_i / p_i`, with `max wᵀT = max_j/p_j − floor_i/p_i` below
/// `wᵀT₀` exactly when `μ_floor > μ_max`.
fn line_certificate<T: Numeric>(model: &Model<T>, system: &TensionSystem<T>, t0: &[T]) -> Vec<T> {
    let p = system.positive_null.as_ref().expect("d = 1");
    let pk = |k: usize| p[model.tendons[k].unknown];
    let pick = |f: &dyn Fn(usize) -> Option<T>| {
        (0..t0.len())
            .filter_map(|k| f(k).map(|v| (k, v)))
            .fold(None, |best: Option<(usize, T)>, (k, v)| match best {
                Some((_, b)) if b >= v => best,
                _ => Some((k, v)),
            })
            .map(|(k, _)| k)
    };
    let floor = pick(&|k| Some((T::from_f64(model.tendons[k].floor) - t0[k]) / pk(k)));
    let max = pick(&|k| {
        model.tendons[k]
            .max_tension
            .map(|m| -((T::from_f64(m) - t0[k]) / pk(k)))
    });
    let mut w = vec![T::zero(); t0.len()];
    if let (Some(i), Some(j)) = (floor, max) {
        w[i] = w[i] - T::one() / pk(i);
        w[j] = w[j] + T::one() / pk(j);
    }
    w
}

/// The message for a state the bounds cannot meet, from a certificate `w` (see
/// [`distribution::solve`]): along `w` the motion needs `wᵀT₀`, more than the bounded
/// tendons give at their extreme (`T_k` at its maximum where `w_k > 0`, at its floor
/// where `w_k < 0`). `w` lies in the row space of the tension system, `w = E_Tᵀ y`, so
/// `wᵀT = yᵀ(E_T T)`: a combination of the balances (generalized forces on joints) the
/// tendons take part in, `y = (E⁺)ᵀ w`.
fn blocked<T: Numeric>(
    model: &Model<T>,
    system: &TensionSystem<T>,
    t0: &[f64],
    w: &[f64],
) -> String {
    let rows = system.rows.len();
    let pinv = |u: usize, r: usize| system.pseudo_inverse[u][r];
    let mut y = vec![0.0; rows];
    for (t, wk) in model.tendons.iter().zip(w) {
        for (r, yr) in y.iter_mut().enumerate() {
            *yr += wk * pinv(t.unknown, r).to_f64();
        }
    }
    let lead = (0..rows).fold(0, |b, r| if y[r].abs() > y[b].abs() { r } else { b });
    let s = y[lead];
    if s == 0.0 || !s.is_finite() {
        return "no tensions within the floors and maxima produce this motion".into();
    }
    let needed: f64 = w.iter().zip(t0).map(|(a, b)| a * b).sum::<f64>() / s;
    let extreme: f64 = model
        .tendons
        .iter()
        .zip(w)
        .map(|(t, &wk)| {
            if wk > 0.0 {
                wk * max_of(t)
            } else {
                wk * t.floor
            }
        })
        .sum::<f64>()
        / s;
    // Components below √u of the largest are round-off of the certificate (its own
    // scalar's: f32 leaves far larger ones than f64).
    let noise = T::unit_roundoff().sqrt();
    let small = noise * w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let at_max: Vec<String> = model
        .tendons
        .iter()
        .zip(w)
        .filter(|(_, &wk)| wk > small)
        .map(|(t, _)| format!("`{}` at its maximum {} N", t.name, max_of(t)))
        .collect();
    let who = match at_max.len() {
        0 => "the tendons at their floors".to_string(),
        1 => at_max[0].clone(),
        n => format!("{} and {}", at_max[..n - 1].join(", "), at_max[n - 1]),
    };
    let row_name = |r: usize| match &system.rows[r] {
        Row::Joint(j) => (format!("`{}`", model.bodies[*j].name), "N·m"),
        Row::Pulley(b) => (
            format!("the driving pulley `{}`", model.bodies[*b].name),
            "N·m",
        ),
        Row::Pretension(l) => (
            format!("the pretension of loop `{}`", model.loops[*l].name),
            "N",
        ),
    };
    let others = (0..rows).any(|r| r != lead && y[r].abs() > noise * s.abs());
    let (target, unit) = if others {
        let terms: Vec<String> = (0..rows)
            .filter(|&r| y[r].abs() > noise * s.abs())
            .enumerate()
            .map(|(i, r)| {
                let c = y[r] / s;
                let sign = match (i, c < 0.0) {
                    (0, true) => "−",
                    (0, false) => "",
                    (_, true) => " − ",
                    (_, false) => " + ",
                };
                format!("{sign}{}·{}", significant(c.abs()), row_name(r).0)
            })
            .collect();
        (format!("the combination {}", terms.concat()), "N·m")
    } else {
        row_name(lead)
    };
    let (n, e) = (significant(needed), significant(extreme));
    if s > 0.0 {
        format!(
            "{who} cannot produce {n} {unit} on {target}; the most they can produce with every \
             other tendon at its floor is {e} {unit}"
        )
    } else {
        format!(
            "{who} cannot bring {target} down to {n} {unit}; the least they can produce with \
             every other tendon at its floor is {e} {unit}"
        )
    }
}

/// `x` to four significant digits, without a trailing exponent for ordinary sizes.
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs().log10().floor() as i32;
    if (-4..6).contains(&magnitude) {
        format!("{x:.*}", (3 - magnitude).max(0) as usize)
    } else {
        format!("{x:.3e}")
    }
}

/// Whether unknown `k` is a tension of an open-ended tendon.
pub fn is_tendon_unknown<T>(model: &Model<T>, k: usize) -> bool {
    matches!(model.system.unknowns[k], Unknown::Explicit(_))
        || model.tendons.iter().any(|t| t.unknown == k)
}
