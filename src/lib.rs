//! flexrock: reference solutions of the Ichinose (1986) model of a slender elastic body rocking
//! on a rigid floor.
//!
//! The pieces, each in its own module:
//! - [`body`]: the physical body; [`constants`]: everything derived from it (MODEL.md 2-5);
//! - [`automaton`]: the hybrid automaton (modes, right-hand sides, guards, resets);
//! - [`excitation`]: floor motions behind the [`excitation::FloorMotion`] trait;
//! - [`solver`]: solvers that drive the automaton; [`solution`]: what they return;
//! - [`fem`]: the plane-stress finite element check of the paper's Section 3;
//! - [`model`]: the TOML model file; [`output`]: CSV/JSON writers; [`run`]: the commands;
//! - [`run_dir`]: a run's output directory read back (typed), and its event table;
//!   [`run_plot`]: the figures of a run;
//! - [`compare`], [`converge`]: Newmark against the adaptive reference; [`findings`]: the paper's
//!   qualitative findings in numbers; [`plot`]: SVG figures from series; [`report`]: the
//!   validation report assembled from their files;
//! - [`sweep`]: parametric studies (axes, minimum overturning searches, chunks, shards, maps);
//! - [`rigid`]: the slender rigid block of the rigid limit (Housner's block), which the elastic
//!   body must tend to as E grows.
//!
//! # Example
//!
//! The reference body of the paper under a one-sine pulse, solved by the adaptive BDF driver:
//!
//! ```
//! use flexrock::model::{Model, Overrides};
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
//! let solution = flexrock::run::simulate(&model)?;
//! // A 4 m/s^2 one-sine pulse of 0.8 s throws it over (models/sine-pulse.toml).
//! assert!(solution.overturned);
//! assert_eq!(solution.max_q.value, model.body.width);
//! # Ok::<(), flexrock::Error>(())
//! ```

pub mod automaton;
pub mod body;
pub mod compare;
pub mod constants;
pub mod converge;
pub mod error;
pub mod excitation;
pub mod fem;
pub mod findings;
pub mod flexural_shape;
pub mod model;
pub mod output;
pub mod plot;
pub mod record;
pub mod record_tools;
pub mod report;
pub mod rigid;
pub mod run;
pub mod run_dir;
pub mod run_plot;
pub mod solution;
pub mod solver;
pub mod sweep;

pub use error::{Error, Result};
