//! Controllable at every capstan factor by the signs of `E` alone, for routings of
//! open-ended tendons alone, however many ways their guides slide. Invariant: `true` only
//! where, for every positive capstan factor of every guide, `E` has full row rank and a
//! null vector that lifts every tendon.
//!
//! A strand's column of `E` is `Σ_r F_r a_r` over its runs ([`Columns`], the boxes' own),
//! each `F_r` a product of capstan factors, positive whatever the guides do. So an entry
//! whose runs' shares in its row are all of one sign keeps that sign at every state, and
//! one whose shares there are all zero stays zero.
//!
//! Order the rows `r_1 … r_m` and say a tendon *enters* at the first row it has an entry in.
//! If at each row a tendon of positive entry and one of negative entry enter, then at
//! every state, going down the rows, the tendons entering at `r_k` can be given positive
//! tensions that cancel row `r_k`'s moment from the tendons that entered before (those of
//! fixed sign take what the others leave, whichever sign it has): a null vector that lifts
//! every tendon (one that enters nowhere takes any positive tension). And any combination
//! of rows that vanishes vanishes at its last row `r_k` too, in a column entering there,
//! zero in the rows before: `E` has full row rank. A finger whose every joint has a flexor
//! and an extensor of its own is such a routing, whatever its friction: the tip joint's
//! pair first, then each joint's towards the base. One with fewer than two tendons per
//! joint (`n + 1` on two or more joints) is not, and with enough friction some direction
//! of sliding can leave it uncontrollable.
//!
//! The rows are taken greedily: among those where a tendon of each sign would enter, the
//! one where the fewest enter, which keeps the others for the rows after it. A routing
//! another order would show is then missed, never wrongly shown.

use super::factor_boxes::Columns;
use crate::model::Model;

/// The sign an entry of `E` keeps at every state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Sign {
    Zero,
    Positive,
    Negative,
    /// Runs of both signs in the row, or one within round-off of zero: no sign for every
    /// state.
    Either,
}

/// How far below its column's largest share (over every row and run) a run's nonzero
/// share leaves its entry of no fixed sign: a moment arm lost in the round-off of the
/// others.
const NEGLIGIBLE: f64 = 1e-9;

/// Whether `E`'s sign pattern alone shows the routing controllable at every capstan
/// factor, from its columns' `runs`: only for routings whose every unknown is an
/// open-ended tendon's tension (a motor torque or loop side would also have to stay
/// determined).
pub(super) fn controllable_at_every_factor(model: &Model<f64>, runs: &Columns) -> bool {
    let columns = model.system.unknowns.len();
    let tendons_only = (0..columns).all(|c| model.tendons.iter().any(|tendon| tendon.unknown == c));
    tendons_only && peels(&signs(model.system.matrix.len(), columns, runs))
}

/// The sign each entry of `E` keeps at every state, row by row, from its column's runs.
fn signs(rows: usize, columns: usize, runs: &Columns) -> Vec<Vec<Sign>> {
    let scales: Vec<f64> = (0..columns)
        .map(|c| {
            (runs.runs(c).iter().flat_map(|run| &run.share)).fold(0.0f64, |a, x| a.max(x.abs()))
        })
        .collect();
    (0..rows)
        .map(|r| {
            (0..columns)
                .map(|c| {
                    let shares = runs.runs(c).iter().map(|run| run.share[r]);
                    sign_of(shares, NEGLIGIBLE * scales[c])
                })
                .collect()
        })
        .collect()
}

/// The sign of `Σ_r F_r x_r` for every positive `F_r`, given the `x_r`; below `tiny` in
/// size a nonzero one fixes none.
fn sign_of(shares: impl Iterator<Item = f64>, tiny: f64) -> Sign {
    shares.fold(Sign::Zero, |sign, x| match (sign, x) {
        (_, 0.0) => sign,
        (Sign::Zero | Sign::Positive, x) if x > tiny => Sign::Positive,
        (Sign::Zero | Sign::Negative, x) if x < -tiny => Sign::Negative,
        _ => Sign::Either,
    })
}

/// Whether the rows can be ordered so that at each a tendon of each sign enters (module
/// documentation), taking them greedily.
pub(super) fn peels(signs: &[Vec<Sign>]) -> bool {
    let columns = signs.first().map_or(0, Vec::len);
    let mut entered = vec![false; columns];
    let mut left: Vec<usize> = (0..signs.len()).collect();
    while !left.is_empty() {
        let entering = |r: usize| -> Vec<Sign> {
            (0..columns)
                .filter(|&c| !entered[c] && signs[r][c] != Sign::Zero)
                .map(|c| signs[r][c])
                .collect()
        };
        let next = (0..left.len())
            .map(|at| (at, entering(left[at])))
            .filter(|(_, new)| new.contains(&Sign::Positive) && new.contains(&Sign::Negative))
            .min_by_key(|(_, new)| new.len());
        let Some((at, _)) = next else {
            return false;
        };
        let r = left.swap_remove(at);
        for (c, sign) in signs[r].iter().enumerate() {
            entered[c] |= *sign != Sign::Zero;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::{peels, sign_of, Sign};
    use Sign::{Either as E, Negative as N, Positive as P, Zero as Z};

    /// A finger of three joints whose every joint has a flexor and an extensor ending on
    /// its link, each passing the joints before it on one side (rows from the base):
    /// peeled from the tip.
    #[test]
    fn a_flexor_and_an_extensor_on_every_joint_peel_from_the_tip() {
        let signs = vec![
            vec![P, N, N, P, P, N],
            vec![Z, Z, P, N, N, P],
            vec![Z, Z, Z, Z, P, N],
        ];
        assert!(peels(&signs));
    }

    /// Three joints, four tendons (`n + 1`): a pair enters at the tip, but each joint
    /// before it has one new tendon only, so no order shows it; nor where the only
    /// tendon of one sign has an entry of no fixed sign.
    #[test]
    fn one_tendon_more_than_joints_does_not_peel() {
        let signs = vec![vec![P, N, N, P], vec![Z, P, N, P], vec![Z, Z, P, N]];
        assert!(!peels(&signs));
        let signs = vec![vec![P, E, P], vec![Z, P, N]];
        assert!(!peels(&signs));
    }

    /// The order is found, not the rows' own: taken first, the first row here would
    /// leave the second no tendon to enter.
    #[test]
    fn rows_peel_in_the_order_that_leaves_each_a_pair() {
        let signs = vec![vec![P, N, P, E, N], vec![P, N, Z, Z, Z]];
        assert!(peels(&signs));
        // Whichever row comes first, the other has no tendon of positive entry left.
        let signs = vec![vec![P, N, P, E, N], vec![P, N, P, Z, Z]];
        assert!(!peels(&signs));
    }

    /// An entry keeps a sign only where every run's share has it, beyond round-off.
    #[test]
    fn an_entry_keeps_the_sign_all_its_runs_share() {
        assert_eq!(sign_of([0.0, 0.0].into_iter(), 1e-12), Z);
        assert_eq!(sign_of([0.0, 0.5, 0.2].into_iter(), 1e-12), P);
        assert_eq!(sign_of([-0.5, 0.0].into_iter(), 1e-12), N);
        assert_eq!(sign_of([-0.5, 0.2].into_iter(), 1e-12), E);
        assert_eq!(sign_of([1e-15].into_iter(), 1e-12), E);
    }
}
