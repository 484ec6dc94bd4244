//! Size limits of an analysis: the mesh, the band of its matrices, the steps and the work.

use super::error::{invalid, FemError};

// Size limits of an analysis. They live here and only here: `model::fem_section` applies them
// to the model file and the command line (naming the keys and flags), `validate_mesh` and
// `validate_settings` to direct calls of the library.

/// Most elements along either side of the mesh.
pub const MAX_ELEMENTS_PER_SIDE: usize = 1000;

/// Most entries of one banded matrix of the mesh: 4e6 entries of 8 bytes are 32 MB. The dofs
/// (node rows numbered across the width) give 2 (nx+1)(ny+1) rows of 2 nx + 6 entries (the
/// half-bandwidth 2 nx + 5 and the diagonal). A dynamic run holds about six such matrices (K,
/// K_sigma, the tangent, C, the effective matrix and one being factorised) and a cache of
/// factors capped at [`FACTOR_CACHE_BYTES`], so at most about 0.5 GB. The 8 x 40 mesh has
/// 16 236 entries, 32 x 80 has 374 220, 64 x 160 has 2.8e6.
pub const MAX_BAND_ENTRIES: f64 = 4.0e6;

/// Memory the cache of factorised effective matrices (one per base contact pattern) may use.
pub const FACTOR_CACHE_BYTES: f64 = 256.0 * 1024.0 * 1024.0;

/// Most time steps of a dynamic run (each a row of fem_history.csv and a point of every
/// figure: 1e6 steps are some 250 MB of history text).
pub const MAX_STEPS: f64 = 1.0e6;

/// Most work of a dynamic run, in steps x band entries: each step solves with a banded factor
/// (a few flops per entry). The 8 x 40 mesh runs its 845 steps (1.4e7) in 0.14 s on the
/// 2-core machine of the README's timings, so the limit is about 100 s there.
pub const MAX_STEP_WORK: f64 = 1.0e10;

/// Entries of one banded matrix of an nx x ny mesh (see [`MAX_BAND_ENTRIES`]).
pub fn band_entries(nx: usize, ny: usize) -> f64 {
    2.0 * (nx as f64 + 1.0) * (ny as f64 + 1.0) * (2.0 * nx as f64 + 6.0)
}

/// The size limit an analysis breaks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SizeLimit {
    /// nx outside 1..=[`MAX_ELEMENTS_PER_SIDE`].
    Nx(usize),
    /// ny outside 1..=[`MAX_ELEMENTS_PER_SIDE`].
    Ny(usize),
    /// The mesh's banded matrices are larger than [`MAX_BAND_ENTRIES`].
    Band {
        /// Elements across the width.
        nx: usize,
        /// Elements up the height.
        ny: usize,
    },
    /// More time steps than [`MAX_STEPS`].
    Steps {
        /// The number of time steps asked for.
        steps: f64,
    },
    /// More steps x band entries than [`MAX_STEP_WORK`].
    Work {
        /// The number of time steps asked for.
        steps: f64,
        /// Entries of one banded matrix of the mesh.
        entries: f64,
    },
}

impl SizeLimit {
    /// The rule broken, for messages.
    pub fn rule(&self) -> String {
        use crate::base::format::readable;
        match *self {
            SizeLimit::Nx(_) | SizeLimit::Ny(_) => {
                format!("the number of elements must lie in 1..={MAX_ELEMENTS_PER_SIDE}")
            }
            SizeLimit::Band { nx, ny } => format!(
                "the {nx} x {ny} mesh's banded matrices would have {:.3e} entries \
                 (2 (nx+1)(ny+1) (2 nx + 6)), {} MB each; at most {:e} entries ({} MB) are \
                 accepted, e.g. 64 x 160; choose fewer elements, mostly across the width",
                band_entries(nx, ny),
                readable((band_entries(nx, ny) * 8e-6).round()),
                MAX_BAND_ENTRIES,
                readable(MAX_BAND_ENTRIES * 8e-6)
            ),
            SizeLimit::Steps { steps } => format!(
                "gives {} time steps; at most {:e} are accepted; choose a larger step or a \
                 shorter duration",
                step_count(steps),
                MAX_STEPS
            ),
            SizeLimit::Work { steps, entries } => format!(
                "gives {} time steps on a mesh with {:.0} band entries, {:.2e} in all; at most \
                 {:e} (about 100 s of computing) are accepted; choose a larger step, a shorter \
                 duration or a coarser mesh",
                step_count(steps),
                entries,
                steps * entries,
                MAX_STEP_WORK
            ),
        }
    }
}

/// A number of time steps as a message gives it: whole below 1e15, else in scientific notation
/// (not the 300 digits of a step of 1e-300 s).
pub(super) fn step_count(steps: f64) -> String {
    if steps < 1e15 {
        format!("{:.0}", steps.floor())
    } else {
        format!("{:.3e}", steps)
    }
}

/// Checks the size of a mesh against the limits above.
pub fn check_mesh_size(nx: usize, ny: usize) -> Result<(), SizeLimit> {
    if !(1..=MAX_ELEMENTS_PER_SIDE).contains(&nx) {
        return Err(SizeLimit::Nx(nx));
    }
    if !(1..=MAX_ELEMENTS_PER_SIDE).contains(&ny) {
        return Err(SizeLimit::Ny(ny));
    }
    if band_entries(nx, ny) > MAX_BAND_ENTRIES {
        return Err(SizeLimit::Band { nx, ny });
    }
    Ok(())
}

/// Checks the size of a dynamic run (mesh, steps, work); `dt` and `duration` must be positive.
pub fn check_run_size(nx: usize, ny: usize, dt: f64, duration: f64) -> Result<(), SizeLimit> {
    check_mesh_size(nx, ny)?;
    let steps = duration / dt;
    if !crate::base::limits::at_most(steps, MAX_STEPS) {
        return Err(SizeLimit::Steps { steps });
    }
    let entries = band_entries(nx, ny);
    if !crate::base::limits::at_most(steps * entries, MAX_STEP_WORK) {
        return Err(SizeLimit::Work { steps, entries });
    }
    Ok(())
}

/// The library's form of a size error: named by the parameter.
pub(super) fn size_error(limit: SizeLimit) -> FemError {
    let rule = limit.rule();
    match limit {
        SizeLimit::Nx(n) => invalid("nx", n, &rule),
        SizeLimit::Ny(n) => invalid("ny", n, &rule),
        SizeLimit::Band { nx, ny } => invalid("nx, ny", format!("{nx}, {ny}"), &rule),
        SizeLimit::Steps { steps } | SizeLimit::Work { steps, .. } => {
            invalid("duration / dt", steps, &rule)
        }
    }
}

pub(super) fn validate_mesh(nx: usize, ny: usize) -> Result<(), FemError> {
    check_mesh_size(nx, ny).map_err(size_error)
}
