//! The row's entry: solves a row by the method of its contact law.

use super::compliant::{solve_row_compliant, CompliantSettings, DEFAULT_TOLERANCE};
use super::description::{ContactLaw, Row};
use super::exact::solve_row_exact;
use super::solution::RowSolution;
use crate::floor::FloorMotion;
use crate::integrate::exact::ExactSettings;
use crate::integrate::{History, SolverError};

/// Solves `row` on `floor` exactly over [0, duration]. A row with the compliant contact law is
/// integrated instead ([`solve_row_compliant`]) at rtol = atol = [`DEFAULT_TOLERANCE`].
pub fn solve_row(
    row: &Row,
    floor: &dyn FloorMotion,
    duration: f64,
    settings: &ExactSettings,
    history: History,
) -> Result<RowSolution, SolverError> {
    if let ContactLaw::Compliant { .. } = row.law() {
        let compliant = CompliantSettings {
            rtol: DEFAULT_TOLERANCE,
            atol: DEFAULT_TOLERANCE,
            output_dt: settings.output_dt,
        };
        return solve_row_compliant(row, floor, duration, &compliant, history);
    }
    solve_row_exact(row, floor, duration, settings, history)
}
