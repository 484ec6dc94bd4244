//! Fixed-base eigenvalues `K φ = ω² M φ` with the lumped (diagonal) mass.
//!
//! Up to [`DENSE_LIMIT`] free dofs the symmetric matrix `M^-½ K M^-½` is solved densely with
//! nalgebra's `SymmetricEigen`; larger meshes use subspace iteration (lowest modes, with the
//! banded LDLᵀ of K) and, above [`DENSE_LIMIT_HIGHEST`] free dofs, Lanczos iteration (highest
//! mode; its largest Ritz value approaches ω²_max from below).

use nalgebra::{DMatrix, SymmetricEigen};

use super::banded::{BandedLdl, BandedSym};
use super::error::FemError;

/// Free-dof count above which subspace iteration finds the lowest modes.
pub(crate) const DENSE_LIMIT: usize = 1200;
/// Free-dof count above which Lanczos iteration finds the highest mode (cheaper than dense).
pub(crate) const DENSE_LIMIT_HIGHEST: usize = 300;

/// Squared circular frequencies ω² (ascending) of `k` with the given dofs fixed.
pub(crate) fn dense_eigenvalues(
    k: &BandedSym,
    mass: &[f64],
    fixed: &[bool],
) -> Result<Vec<f64>, FemError> {
    let free: Vec<usize> = (0..k.n).filter(|&d| !fixed[d]).collect();
    let scale: Vec<f64> = free.iter().map(|&d| 1.0 / mass[d].sqrt()).collect();
    let a = DMatrix::from_fn(free.len(), free.len(), |r, c| {
        k.get(free[r], free[c]) * scale[r] * scale[c]
    });
    let mut values: Vec<f64> = SymmetricEigen::new(a).eigenvalues.iter().copied().collect();
    if values.iter().any(|v| !v.is_finite()) {
        return Err(FemError::SingularMatrix {
            context: "eigenvalues are not finite".into(),
        });
    }
    values.sort_by(f64::total_cmp);
    Ok(values)
}

/// The `count` lowest ω² of `k` with the `fixed` dofs held.
pub(crate) fn lowest_eigenvalues(
    k: &BandedSym,
    mass: &[f64],
    fixed: &[bool],
    count: usize,
) -> Result<Vec<f64>, FemError> {
    let free = fixed.iter().filter(|f| !**f).count();
    if free <= DENSE_LIMIT {
        let mut v = dense_eigenvalues(k, mass, fixed)?;
        v.truncate(count);
        return Ok(v);
    }
    subspace_iteration(k, mass, fixed, count)
}

/// Largest ω² of `k` with the `fixed` dofs held.
pub(crate) fn highest_eigenvalue(
    k: &BandedSym,
    mass: &[f64],
    fixed: &[bool],
) -> Result<f64, FemError> {
    let free = fixed.iter().filter(|f| !**f).count();
    if free <= DENSE_LIMIT_HIGHEST {
        let v = dense_eigenvalues(k, mass, fixed)?;
        return v.last().copied().ok_or_else(|| FemError::SingularMatrix {
            context: "no free dofs".into(),
        });
    }
    lanczos_highest(k, mass, fixed)
}

/// Lanczos iteration (full reorthogonalisation) on `M^-½ K M^-½` for the largest ω². The
/// largest Ritz value approaches ω²_max from below and, the top of the spectrum being an
/// extreme, converges in tens of steps where power iteration needs thousands when the highest
/// frequencies cluster.
pub(crate) fn lanczos_highest(
    k: &BandedSym,
    mass: &[f64],
    fixed: &[bool],
) -> Result<f64, FemError> {
    let n = k.n;
    let free_count = fixed.iter().filter(|f| !**f).count();
    let scale: Vec<f64> = mass.iter().map(|m| 1.0 / m.sqrt()).collect();
    // A v = M^-½ K M^-½ v on the free dofs
    let mut scratch = vec![0.0; n];
    let mut product = vec![0.0; n];
    let mut apply = |v: &[f64], out: &mut Vec<f64>| {
        for d in 0..n {
            scratch[d] = if fixed[d] { 0.0 } else { v[d] * scale[d] };
        }
        k.mul_vec(&scratch, &mut product);
        for d in 0..n {
            out[d] = if fixed[d] { 0.0 } else { product[d] * scale[d] };
        }
    };
    // start close to the highest (checkerboard) mode
    let mut q: Vec<f64> = (0..n)
        .map(|d| match (fixed[d], (d / 2 + d) % 2 == 0) {
            (true, _) => 0.0,
            (false, true) => 1.0,
            (false, false) => -0.7,
        })
        .collect();
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm == 0.0 {
        return Err(FemError::SingularMatrix {
            context: "no free dofs".into(),
        });
    }
    q.iter_mut().for_each(|v| *v /= norm);
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let (mut alphas, mut betas) = (Vec::new(), Vec::new());
    let mut w = vec![0.0; n];
    let mut estimate = f64::NAN;
    for step in 0..free_count {
        apply(&q, &mut w);
        let alpha: f64 = q.iter().zip(&w).map(|(a, b)| a * b).sum();
        alphas.push(alpha);
        basis.push(q.clone());
        // w -= alpha q + beta q_prev, then against the whole basis again (twice is enough)
        for _ in 0..2 {
            for b in &basis {
                let c: f64 = b.iter().zip(&w).map(|(x, y)| x * y).sum();
                w.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
            }
        }
        let beta = w.iter().map(|v| v * v).sum::<f64>().sqrt();
        let converged = if step % 5 == 4 || beta <= 1e-12 * alpha.abs() || step + 1 == free_count {
            let top = largest_tridiagonal_eigenvalue(&alphas, &betas);
            let done = (top - estimate).abs() <= 1e-12 * top.abs();
            estimate = top;
            done
        } else {
            false
        };
        if converged || beta <= 1e-12 * alpha.abs() {
            break;
        }
        betas.push(beta);
        q.iter_mut().zip(&w).for_each(|(x, y)| *x = y / beta);
    }
    if !estimate.is_finite() {
        return Err(FemError::SingularMatrix {
            context: "highest eigenvalue is not finite".into(),
        });
    }
    Ok(estimate)
}

/// Largest eigenvalue of the symmetric tridiagonal matrix with diagonal `alphas` and
/// off-diagonal `betas`.
fn largest_tridiagonal_eigenvalue(alphas: &[f64], betas: &[f64]) -> f64 {
    let m = alphas.len();
    let t = DMatrix::from_fn(m, m, |r, c| {
        if r == c {
            alphas[r]
        } else if r == c + 1 {
            betas[c]
        } else if c == r + 1 {
            betas[r]
        } else {
            0.0
        }
    });
    SymmetricEigen::new(t)
        .eigenvalues
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Subspace iteration for the lowest `count` eigenvalues of `K φ = λ M φ`.
pub(crate) fn subspace_iteration(
    k: &BandedSym,
    mass: &[f64],
    fixed: &[bool],
    count: usize,
) -> Result<Vec<f64>, FemError> {
    let n = k.n;
    let p = (2 * count).max(count + 8).min(n);
    let factors = BandedLdl::factor(&k.with_identity_rows(fixed))?;
    // start vectors: smooth polynomial-like patterns in the dof index
    let mut x = DMatrix::from_fn(n, p, |d, c| {
        if fixed[d] {
            0.0
        } else {
            let s = (d as f64 + 1.0) / n as f64;
            (s * (c as f64 + 1.0) * 1.7 + c as f64).sin() + if d % 2 == c % 2 { 1.0 } else { 0.0 }
        }
    });
    let mut previous = vec![f64::INFINITY; count];
    for _ in 0..500 {
        let mut y = DMatrix::zeros(n, p);
        for c in 0..p {
            let mut col: Vec<f64> = (0..n)
                .map(|d| if fixed[d] { 0.0 } else { mass[d] * x[(d, c)] })
                .collect();
            factors.solve_in_place(&mut col);
            for d in 0..n {
                y[(d, c)] = if fixed[d] { 0.0 } else { col[d] };
            }
        }
        let mut ky = DMatrix::zeros(n, p);
        let mut buffer = vec![0.0; n];
        for c in 0..p {
            let col: Vec<f64> = y.column(c).iter().copied().collect();
            k.mul_vec(&col, &mut buffer);
            for d in 0..n {
                ky[(d, c)] = if fixed[d] { 0.0 } else { buffer[d] };
            }
        }
        let my = DMatrix::from_fn(n, p, |d, c| mass[d] * y[(d, c)]);
        let k_reduced = y.transpose() * &ky;
        let m_reduced = y.transpose() * &my;
        let chol = m_reduced
            .clone()
            .cholesky()
            .ok_or_else(|| FemError::SingularMatrix {
                context: "subspace iteration lost independence".into(),
            })?;
        let l_inv = chol
            .l()
            .try_inverse()
            .ok_or_else(|| FemError::SingularMatrix {
                context: "subspace iteration lost independence".into(),
            })?;
        let a = &l_inv * k_reduced * l_inv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let eig = SymmetricEigen::new(a);
        let mut order: Vec<usize> = (0..p).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let q = l_inv.transpose() * &eig.eigenvectors;
        let mut next = DMatrix::zeros(n, p);
        for (c, &o) in order.iter().enumerate() {
            next.set_column(c, &(&y * q.column(o)));
        }
        x = next;
        let values: Vec<f64> = order
            .iter()
            .take(count)
            .map(|&o| eig.eigenvalues[o])
            .collect();
        let converged = values
            .iter()
            .zip(&previous)
            .all(|(v, p)| (v - p).abs() <= 1e-10 * v.abs());
        if converged {
            return Ok(values);
        }
        previous = values;
    }
    Ok(previous)
}
