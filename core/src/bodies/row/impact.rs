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
//! definite, so the problem has exactly one solution. Contacts that share no column do not
//! couple (A is zero between them), so each chain of contacts that do is its own problem, solved
//! by trying the sets of its contacts that carry an impulse.

/// The most contacts of one chain (each sharing a column with the next) closing at one instant,
/// whose impulses are found together.
pub const MAX_SIMULTANEOUS: usize = 16;

/// Why no impulses could be found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImpactError {
    /// More than [`MAX_SIMULTANEOUS`] contacts of one chain at one instant.
    #[error(
        "{0} contacts of one chain (each sharing a column with the next) close at one instant; at \
         most {MAX_SIMULTANEOUS} are resolved together"
    )]
    TooMany(usize),
    /// No set of contacts satisfies the complementarity conditions (A not positive definite).
    #[error("no impulses satisfy Newton's law at every contact (the contact matrix is singular)")]
    NoSolution,
}

/// The impulses J (N s) at contacts with closing velocities `closing` (m/s, positive closing)
/// and contact matrix `matrix` (row-major, n x n, 1/kg), for restitution `e`: each set of
/// contacts coupled through the matrix solved on its own.
pub fn impulses(closing: &[f64], matrix: &[f64], e: f64) -> Result<Vec<f64>, ImpactError> {
    let n = closing.len();
    // The coupled sets: contacts joined by a nonzero entry, grown from each one not yet placed.
    let mut set_of = vec![usize::MAX; n];
    let mut j = vec![0.0; n];
    for seed in 0..n {
        if set_of[seed] != usize::MAX {
            continue;
        }
        let mut members = vec![seed];
        set_of[seed] = seed;
        let mut next = 0;
        while next < members.len() {
            let i = members[next];
            next += 1;
            for k in 0..n {
                if set_of[k] == usize::MAX && (matrix[i * n + k] != 0.0 || matrix[k * n + i] != 0.0)
                {
                    set_of[k] = seed;
                    members.push(k);
                }
            }
        }
        members.sort_unstable();
        let m = members.len();
        if m > MAX_SIMULTANEOUS {
            return Err(ImpactError::TooMany(m));
        }
        let sub_closing: Vec<f64> = members.iter().map(|&i| closing[i]).collect();
        let sub_matrix: Vec<f64> = members
            .iter()
            .flat_map(|&r| members.iter().map(move |&c| matrix[r * n + c]))
            .collect();
        for (&i, x) in members.iter().zip(coupled(&sub_closing, &sub_matrix, e)?) {
            j[i] = x;
        }
    }
    Ok(j)
}

/// [`impulses`] of one coupled set of contacts, by trying the sets that carry an impulse.
fn coupled(closing: &[f64], matrix: &[f64], e: f64) -> Result<Vec<f64>, ImpactError> {
    let n = closing.len();
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

    /// A chain of n contacts between n + 1 equal unit masses: A = 2 on the diagonal, -1 beside.
    fn chain(n: usize) -> Vec<f64> {
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + i] = 2.0;
            if i + 1 < n {
                a[i * n + i + 1] = -1.0;
                a[(i + 1) * n + i] = -1.0;
            }
        }
        a
    }

    #[test]
    fn too_many_contacts_are_refused() {
        let n = MAX_SIMULTANEOUS + 1;
        let err = impulses(&vec![1.0; n], &chain(n), 0.5).unwrap_err();
        assert_eq!(err, ImpactError::TooMany(n));
    }

    #[test]
    fn independent_contacts_are_solved_each_on_its_own() {
        // Many more pairs than one chain may hold, each alone: J = (1 + e) w / A_cc, whatever
        // the number; and two chains of three beside each other, each as the chain alone.
        let n = 4 * MAX_SIMULTANEOUS;
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + i] = 0.5 + i as f64;
        }
        let w: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * i as f64).collect();
        let j = impulses(&w, &a, 0.6).unwrap();
        for i in 0..n {
            assert!((j[i] - 1.6 * w[i] / (0.5 + i as f64)).abs() < 1e-12 * j[i]);
        }
        let one = chain(3);
        let mut two = vec![0.0; 36];
        for r in 0..3 {
            for c in 0..3 {
                two[r * 6 + c] = one[r * 3 + c];
                two[(r + 3) * 6 + c + 3] = one[r * 3 + c];
            }
        }
        let alone = impulses(&[1.0, 0.0, 0.5], &one, 0.5).unwrap();
        let both = impulses(&[1.0, 0.0, 0.5, 1.0, 0.0, 0.5], &two, 0.5).unwrap();
        assert_eq!(&both[..3], &alone[..]);
        assert_eq!(&both[3..], &alone[..]);
    }
}
