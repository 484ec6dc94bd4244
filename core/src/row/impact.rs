//! The impact law (book/src/row.md §3): Newton's restitution at every contact that closes,
//! with the impulses of a chain found together.
//!
//! An impulse J >= 0 at contact c pushes its columns apart: the left column's q' changes by
//! -Phi_l J / m_l and the right one's by +Phi_r J / m_r, with Phi the column's velocity shape
//! at the contact and m = M int Phi^2 its kinetic mass in its mode. The closing velocities w of
//! the contacts then change by -A J, with A the symmetric positive definite matrix
//! A_cc = Phi_l^2/m_l + Phi_r^2/m_r, and, for contacts c and c + 1 that share column k,
//! A_c,c+1 = -Phi_k,c Phi_k,c+1 / m_k. Newton's law at each contact, with the impulses of all
//! of them at once, is the linear complementarity problem
//!
//! ```text
//! s = A J - (1 + e) w >= 0,   J >= 0,   J_c s_c = 0 for every c,
//! ```
//!
//! that is, every contact leaves separating at least e times as fast as it closed, and one that
//! leaves faster carries no impulse. For a single contact, J = (1 + e) w / A. A is positive
//! definite, so the problem has exactly one solution, found here by trying the sets of
//! contacts that carry an impulse.

/// The most contacts closing at one instant whose impulses are found together.
pub const MAX_SIMULTANEOUS: usize = 16;

/// Why no impulses could be found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImpactError {
    /// More than [`MAX_SIMULTANEOUS`] contacts at one instant.
    #[error("{0} contacts close at one instant; at most {MAX_SIMULTANEOUS} are resolved together")]
    TooMany(usize),
    /// No set of contacts satisfies the complementarity conditions (A not positive definite).
    #[error("no impulses satisfy Newton's law at every contact (the contact matrix is singular)")]
    NoSolution,
}

/// The impulses J (N s) at contacts with closing velocities `closing` (m/s, positive closing)
/// and contact matrix `matrix` (row-major, n x n, 1/kg), for restitution `e`.
pub fn impulses(closing: &[f64], matrix: &[f64], e: f64) -> Result<Vec<f64>, ImpactError> {
    let n = closing.len();
    if n > MAX_SIMULTANEOUS {
        return Err(ImpactError::TooMany(n));
    }
    let target: Vec<f64> = closing.iter().map(|w| (1.0 + e) * w).collect();
    let a = |i: usize, j: usize| matrix[i * n + j];
    // Tolerance of the complementarity checks, relative to the sizes of the terms.
    let scale = target
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let tolerance = 1e-12 * scale;
    // The sets with fewer contacts first: the one solution is found whatever the order.
    let mut sets: Vec<u32> = (0..(1u32 << n)).collect();
    sets.sort_by_key(|s| s.count_ones());
    for set in sets {
        let active: Vec<usize> = (0..n).filter(|&i| set & (1 << i) != 0).collect();
        let k = active.len();
        let mut j = vec![0.0; n];
        if k > 0 {
            let sub = nalgebra::DMatrix::from_fn(k, k, |r, c| a(active[r], active[c]));
            let rhs = nalgebra::DVector::from_fn(k, |r, _| target[active[r]]);
            let Some(solved) = sub.lu().solve(&rhs) else {
                continue;
            };
            for (r, &i) in active.iter().enumerate() {
                j[i] = solved[r];
            }
        }
        let impulses_nonnegative = j.iter().all(|&x| x >= -tolerance);
        let separating = (0..n).all(|c| {
            let s: f64 = (0..n).map(|d| a(c, d) * j[d]).sum::<f64>() - target[c];
            s >= -tolerance
        });
        if impulses_nonnegative && separating {
            return Ok(j.into_iter().map(|x| x.max(0.0)).collect());
        }
    }
    Err(ImpactError::NoSolution)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_contact_is_newtons_law() {
        // J = (1 + e) w / A.
        let j = impulses(&[2.0], &[0.5], 0.6).unwrap();
        assert!((j[0] - 1.6 * 2.0 / 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_contact_opening_carries_no_impulse() {
        let j = impulses(&[-1.0], &[0.5], 0.6).unwrap();
        assert_eq!(j, [0.0]);
    }

    #[test]
    fn a_chain_of_three_equal_masses_with_elastic_contacts() {
        // Three equal unit masses, the left one moving at 1 onto two at rest, touching (e = 1):
        // A = [[2, -1], [-1, 2]], w = (1, 0). Solved together, the impulses give velocities
        // (-1/3, 2/3, 2/3) (the simultaneous-impact answer of Newton's law applied at once):
        // J = A^-1 (2, 0) = (4/3, 2/3) -> v1 = 1 - 4/3, v2 = 4/3 - 2/3, v3 = 2/3.
        let j = impulses(&[1.0, 0.0], &[2.0, -1.0, -1.0, 2.0], 1.0).unwrap();
        assert!((j[0] - 4.0 / 3.0).abs() < 1e-12 && (j[1] - 2.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn too_many_contacts_are_refused() {
        let n = MAX_SIMULTANEOUS + 1;
        let err = impulses(&vec![1.0; n], &vec![0.0; n * n], 0.5).unwrap_err();
        assert_eq!(err, ImpactError::TooMany(n));
    }
}
