//! Fixed-base eigenvalues `K φ = ω² M φ` with the lumped (diagonal) mass.
//!
//! Up to [`DENSE_LIMIT`] free dofs the symmetric matrix `M^-½ K M^-½` is solved densely with
//! nalgebra's `SymmetricEigen`; larger meshes use subspace iteration (lowest modes, with the
//! banded LDLᵀ of K) and, above [`DENSE_LIMIT_HIGHEST`] free dofs, power iteration (highest
//! mode; its Rayleigh quotient approaches ω²_max from below).

use nalgebra::{DMatrix, SymmetricEigen};

use super::banded::{BandedLdl, BandedSym};
use super::FemError;

/// Free-dof count above which subspace iteration finds the lowest modes.
pub(crate) const DENSE_LIMIT: usize = 1200;
/// Free-dof count above which power iteration finds the highest mode (cheaper than dense).
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
    power_iteration(k, mass, fixed)
}

/// Power iteration on M⁻¹ K for the largest ω² (Rayleigh quotient converged to 1e-12).
pub(crate) fn power_iteration(
    k: &BandedSym,
    mass: &[f64],
    fixed: &[bool],
) -> Result<f64, FemError> {
    // the alternating pattern starts close to the highest (checkerboard) mode
    let n = k.n;
    let mut x: Vec<f64> = (0..n)
        .map(|d| {
            if fixed[d] {
                0.0
            } else {
                let node = d / 2;
                if (node + d) % 2 == 0 {
                    1.0
                } else {
                    -0.7
                }
            }
        })
        .collect();
    let mut y = vec![0.0; n];
    let mut estimate = 0.0;
    for iteration in 0..20_000 {
        k.mul_vec(&x, &mut y);
        let kx: f64 = x.iter().zip(&y).map(|(a, b)| a * b).sum();
        let mx: f64 = x.iter().zip(mass).map(|(a, m)| a * a * m).sum();
        let rayleigh = kx / mx;
        for d in 0..n {
            x[d] = if fixed[d] { 0.0 } else { y[d] / mass[d] };
        }
        let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        x.iter_mut().for_each(|v| *v /= norm);
        if iteration > 20 && (rayleigh - estimate).abs() <= 1e-10 * rayleigh {
            return Ok(rayleigh);
        }
        estimate = rayleigh;
    }
    Ok(estimate)
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
