//! A row of slender elastic columns on one floor, each the single body of the model, with clear
//! gaps between neighbours: columns that rock or sway far enough strike each other
//! (book/src/row.md).
//!
//! Each column keeps its own automaton: its modes, its flow within each, its uplifts, landings
//! and overturning are exactly those of the body alone. The row adds contacts between
//! neighbours, each at the top of the shorter of the two ([`Contact`]), and an impact law at
//! them ([`impulses`]): Newton's restitution on the closing velocity of the contact points, the
//! impulse acting on each column through its velocity shape, simultaneous impacts of a chain
//! resolved together as a linear complementarity problem. Between impacts the columns move
//! independently, so a row whose gaps never close gives each column's single run.
//!
//! ```
//! use flexrock_core::physics::automaton::EventKind;
//! use flexrock_core::physics::body::{prism_mass, solid_section_flexural_rigidity, Body};
//! use flexrock_core::physics::body::{ConstantSet, SelfWeight};
//! use flexrock_core::floor::PaperSine;
//! use flexrock_core::bodies::row::{solve_row, ColumnSpec, Row};
//! use flexrock_core::integrate::exact::ExactSettings;
//! use flexrock_core::integrate::{History, InitialState};
//!
//! // Two columns of the paper's size, the right one stiffer, 2 cm apart, under the paper's sine.
//! let column = |youngs_modulus: f64| ColumnSpec {
//!     body: Body {
//!         height: 4.0,
//!         width: 0.7,
//!         depth: 1.0,
//!         mass: prism_mass(600.0, 4.0, 0.7, 1.0),
//!         flexural_rigidity: solid_section_flexural_rigidity(youngs_modulus, 0.7, 1.0),
//!         damping_ratio: 0.05,
//!         gravity: 9.81,
//!         constant_set: ConstantSet::Exact,
//!         self_weight: SelfWeight::Paper,
//!         landing_restitution: 1.0,
//!         damping_while_rocking: true,
//!     },
//!     initial: InitialState { q: 0.0, qdot: 0.0 },
//! };
//! let row = Row::new(&[column(5e6), column(5e7)], &[0.02], 0.5)?;
//! let floor = PaperSine::new(4.0, 1.0, 0.412);
//! let settings = ExactSettings { output_dt: 0.01 };
//! let solved = solve_row(&row, &floor, 6.0, &settings, History::Sampled)?;
//! // The softer column sways further and strikes its neighbour.
//! assert!(!solved.impacts.is_empty());
//! let first = solved.impacts[0];
//! assert!(first.impulse > 0.0 && first.separating_velocity > 0.0);
//! // Each impact is an event of both columns, whose q' jumps there.
//! for column in &solved.columns {
//!     assert!(column.events.iter().any(|e| e.kind == EventKind::Impact));
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod compliant;
mod contact;
mod description;
mod exact;
mod impact;
pub mod law;
mod solution;
mod solve;

pub use compliant::{solve_row_compliant, CompliantSettings, DEFAULT_TOLERANCE, METHOD};
pub use contact::{Contact, ContactSample, ContactState, Face};
pub use description::{Column, ColumnSpec, ContactLaw, Row, MAX_FRICTION};
pub use exact::ACCUMULATION_SHARE;
pub use impact::{impulses, ImpactError, MAX_SIMULTANEOUS};
pub use solution::{ContactStretch, HeldContact, ImpactRecord, RowSolution, StickStretch};
pub use solve::solve_row;
