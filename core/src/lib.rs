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
//!    [`summary::summary`] is the run's summary.json.
//! 3. **A study**: a [`sweep::Request`] (axes over any keys, settings, a minimum overturning
//!    search) on a model file makes a [`Sweep`]; [`Sweep::rows`] computes every point (in
//!    parallel with the `parallel` feature) into typed [`sweep::Row`]s whose cells
//!    ([`sweep::Cell`]) are the columns of sweep.csv.
//!
//! ```
//! use std::path::Path;
//!
//! use flexrock_core::sweep::{Axis, Cell, Request, Row};
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
//! // A row's cells follow Row::columns (sweep.csv's columns after the point and the axes).
//! let at = Row::columns(false).iter().position(|c| c == "overturned").unwrap();
//! let overturned: Vec<Cell> = rows.iter().map(|row| row.cells(false)[at].clone()).collect();
//! assert_eq!(overturned, [false, true, true].map(|b| Cell::Bool(Some(b))));
//! # Ok::<(), flexrock_core::Error>(())
//! ```
//!
//! The pieces, each in its own module:
//! The pieces, each in its own module:
//! - [`body`]: the physical body; [`constants`]: everything derived from it
//!   (book/src/model.md §2-§5);
//! - [`automaton`]: the hybrid automaton (modes, right-hand sides, guards, resets);
//! - [`excitation`]: floor motions behind the [`excitation::FloorMotion`] trait; [`record`]:
//!   recorded ground motions read from their files; [`intensity`]: their intensity measures;
//! - [`solver`]: solvers that drive the automaton (the adaptive diffsol driver, Newmark, the
//!   run budget); [`solution`]: what they return; [`simulate`](mod@simulate): a model solved
//!   with the solver it names, and [`properties`];
//! - [`model`]: the TOML model file (its schema and checks);
//! - [`fem`]: the plane-stress finite element check of the paper's Section 3 (mesh, elements,
//!   banded solver, eigenvalues, dynamics, pushover);
//! - [`rigid`]: the rigid block of the rigid limit (Housner's block), which the elastic body must
//!   tend to as E grows, by the small-angle (default) or the full rocking equation;
//!   [`rigid_criteria`]: published overturning criteria of rigid bodies (Ishiyama 1982);
//!   [`findings`]: the paper's qualitative findings in numbers;
//! - `flexural_shape` (private): the self-weighted cantilever mode psi of the consistent variant;
//! - [`run_tables`]: the columns of a run's tables; [`summary`]: summary.json of a run;
//! - [`sweep`]: parametric studies and minimum overturning searches;
//! - [`error`]: the one error type; [`format`](mod@format): numbers and file kinds for messages;
//!   [`columns`]: a table's columns as one list of (name, field), for the analyses' typed rows;
//! - the analyses above [`simulate`](mod@simulate): [`compare`](mod@compare) (two solutions of
//!   one model measured against each other: matched events, peaks, q(t) on the output grid),
//!   [`converge`](mod@converge) (the convergence study: cases, orders and efficiency slopes),
//!   [`fem_check`] (a finite element run, its uplift episodes and peaks, and its comparison with
//!   the one-degree-of-freedom model) and [`pushover_check`] (the static pushover curves against
//!   the model's restoring force).
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

pub mod automaton;
pub mod body;
pub mod columns;
pub mod compare;
pub mod constants;
pub mod converge;
pub mod criteria;
mod double_double;
pub mod error;
pub mod excitation;
pub mod fem;
pub mod fem_check;
pub mod findings;
mod flexural_shape;
pub mod format;
pub mod intensity;
mod invalid;
mod limits;
pub mod model;
pub mod pushover_check;
pub mod record;
pub mod rigid;
pub mod rigid_criteria;
pub mod row;
pub mod row_results;
pub mod run_tables;
pub mod simulate;
pub mod solution;
pub mod solver;
mod suggest;
pub mod summary;
pub mod sweep;
mod units;

pub use automaton::Automaton;
pub use body::Body;
pub use compare::{match_events, Comparison, EventPair};
pub use constants::Constants;
pub use converge::{Case, Convergence, Slope, SlopeKind};
pub use error::{Error, Result};
pub use excitation::FloorMotion;
pub use fem_check::{FemAnalysis, FemComparison};
pub use invalid::InvalidParameter;
pub use model::{Model, Overrides};
pub use pushover_check::PushoverAnalysis;
pub use simulate::{properties, simulate, simulate_peaks, simulate_with, Properties, Provenance};
pub use solution::Solution;
pub use solver::SolverSettings;
pub use sweep::Sweep;
pub use units::{unit_of_key, Unit, STANDARD_GRAVITY};
