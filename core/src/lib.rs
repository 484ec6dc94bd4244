//! flexrock-core: the physics and numerics of flexrock, reference solutions of the Ichinose
//! (1986) model of a slender elastic body rocking on a rigid floor, without the command-line
//! layer (no argument parsing, CSV writers or plots: the `flexrock` package builds those on top
//! of this crate).
//!
//! # From a model file to a sweep
//!
//! 1. **A model**: [`Model::load`] reads a model file (the book's model-file reference lists its
//!    keys), [`Model::from_toml_str`] its text; [`Overrides`] set keys from outside the file,
//!    each checked by the file's rules. Errors name the key, the value and the rule.
//! 2. **A solution**: [`simulate()`] solves it with the solver the file names and returns a
//!    [`Solution`]: the sampled history, every event (uplift, landing, overturning) located to
//!    the solver's tolerance, the rocking episodes, peaks and energy books;
//!    [`tables::summary::summary`] is the run's summary.json.
//! 3. **A study**: a [`analysis::sweep::Request`] (axes over any keys, settings, a minimum overturning
//!    search) on a model file makes a [`Sweep`]; [`Sweep::rows`] computes every point (in
//!    parallel with the `parallel` feature) into typed [`analysis::sweep::PointResult`]s whose cells
//!    ([`analysis::sweep::Cell`]) are the columns of sweep.csv.
//!
//! ```
//! use std::path::Path;
//!
//! use flexrock_core::analysis::sweep::{Axis, Cell, Request, PointResult};
//! use flexrock_core::{Model, Overrides, Sweep};
//!
//! # let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
//! # std::env::set_current_dir(&root).unwrap();
//! // The paper's example: its body under its sine, solved by the adaptive BDF driver.
//! let model = Model::load(Path::new("models/ichinose1986.toml"), &Overrides::default())?;
//! let solution = flexrock_core::simulate(&model)?;
//! assert!(!solution.overturned && !solution.events.is_empty());
//!
//! // Three amplitudes of a 0.8 s one-sine pulse: 2 m/s^2 leaves the body standing.
//! let request = Request {
//!     axes: vec![Axis::parse("excitation.amplitude=2,4,6", Path::new("."))?],
//!     ..Request::default()
//! };
//! let here = std::env::current_dir().unwrap();
//! let sweep = Sweep::new(Path::new("models/sine-pulse.toml"), request, &here)?;
//! let rows = sweep.rows(0..sweep.points(), &|| {});
//! // A row's cells follow PointResult::columns (sweep.csv's columns after the point and the axes).
//! let at = PointResult::columns(false).iter().position(|c| c == "overturned").unwrap();
//! let overturned: Vec<Cell> = rows.iter().map(|row| row.cells(false)[at].clone()).collect();
//! assert_eq!(overturned, [false, true, true].map(|b| Cell::Bool(Some(b))));
//! # Ok::<(), flexrock_core::Error>(())
//! ```
//!
//! The pieces, in layers from the bottom up: each module uses only its own layer and those
//! below it (the book's code map draws them; `core/tests/layers.rs` checks it).
//! - [`base`]: numbers as text ([`base::format`]), units, the rule of a refused value
//!   ([`InvalidParameter`]), double-double arithmetic, suggestions for mistyped names;
//! - [`physics`]: the body ([`physics::body`]), everything derived from it
//!   ([`physics::constants`]), the hybrid automaton ([`physics::automaton`]: modes, right-hand
//!   sides, guards, resets; the only home of the dynamics), published rigid-body criteria;
//! - [`floor`]: floor motions behind the [`FloorMotion`] trait; recorded ground motions read
//!   from their files ([`floor::record`]) and the ground's intensity measures
//!   ([`floor::intensity`]);
//! - [`integrate`]: the solvers that drive the automaton (the exact method, the adaptive diffsol
//!   driver, Newmark, the run budget) and the [`Solution`] they return;
//! - [`bodies`]: what is built on the automaton: the rigid block ([`bodies::rigid`]), rows of
//!   pounding columns ([`bodies::row`]), the finite element check ([`bodies::fem`]) and the
//!   linear oscillator of a response spectrum ([`bodies::oscillator`]);
//! - [`error`]: the one error type; [`model`]: the TOML model file, its schema and checks;
//! - [`simulate()`](fn@simulate): a model solved with the solver it names, and [`properties`];
//! - [`tables`]: the columns of a run's tables, summary.json, a row's results, a table's fields;
//! - [`analysis`]: studies over runs: comparisons, convergence, the FEM and pushover checks,
//!   the overturning criteria, the paper's findings, sweeps and minimum overturning searches.
//!
//! # Example
//!
//! The reference body of the paper under a one-sine pulse, solved by the adaptive BDF driver:
//!
//! ```
//! use flexrock_core::{Model, Overrides};
//!
//! let text = r#"
//!     [body]
//!     height = 4.0
//!     width = 0.7
//!     density = 600.0
//!     youngs_modulus = 5.0e6
//!
//!     [excitation]
//!     kind = "sine-pulse"
//!     amplitude = 4.0
//!     period = 0.8
//!
//!     [simulation]
//!     duration = 6.0
//! "#;
//! let model = Model::from_toml_str(text, &Overrides::default())?;
//! // The pre-uplift period of the paper's body is 1.55 s.
//! assert!((model.constants.period - 1.55).abs() < 1e-3);
//! let solution = flexrock_core::simulate(&model)?;
//! // A 4 m/s^2 one-sine pulse of 0.8 s throws it over (models/sine-pulse.toml).
//! assert!(solution.overturned);
//! assert_eq!(solution.max_q.value, model.body.width);
//! # Ok::<(), flexrock_core::Error>(())
//! ```

#![warn(missing_docs)]

pub mod analysis;
pub mod base;
pub mod bodies;
pub mod error;
pub mod floor;
pub mod integrate;
pub mod model;
pub mod physics;
pub mod simulate;
pub mod tables;

pub use analysis::compare::{match_events, Comparison, EventPair};
pub use analysis::converge::{Case, Convergence, Slope, SlopeKind};
pub use analysis::fem_check::{FemAnalysis, FemComparison};
pub use analysis::pushover_check::PushoverAnalysis;
pub use analysis::sweep::Sweep;
pub use base::invalid::InvalidParameter;
pub use base::units::{unit_of_key, Unit, STANDARD_GRAVITY};
pub use error::{Error, Result};
pub use floor::FloorMotion;
pub use integrate::solution::Solution;
pub use integrate::SolverSettings;
pub use model::{Model, Overrides};
pub use physics::automaton::Automaton;
pub use physics::body::Body;
pub use physics::constants::Constants;
pub use simulate::{
    properties, simulate, simulate_peaks, simulate_rigid, simulate_with, Properties, Provenance,
};
