//! What `flexrock sweep` prints: its few lines of report, and its warnings.

use super::store;

/// What a reader of a sweep must know (printed on standard error): what the store met (chunks
/// computed again, a directory it could not lock), and points whose runs are no more accurate
/// than their energy residual says.
pub fn warnings(report: &store::SweepReport) -> Vec<String> {
    let mut warnings = report.warnings.clone();
    let inaccurate = report.summary.counts.inaccurate;
    if inaccurate == 0 {
        return warnings;
    }
    warnings.push(format!(
        "{inaccurate} of {} points have an energy residual above {} % of their energy scale \
         (column energy_residual_share): their results are no more accurate than that; tighten \
         solver.rtol (--set solver.rtol=...)",
        report.summary.points.end - report.summary.points.first,
        100.0 * crate::commands::run::ENERGY_RESIDUAL_WARNING_SHARE
    ));
    warnings
}

/// The few lines `flexrock sweep` prints; `seconds` is the wall time of this process, if it
/// computed anything.
pub fn report_text(report: &store::SweepReport, seconds: Option<f64>) -> String {
    use std::fmt::Write as _;
    let s = &report.summary;
    let mut t = String::new();
    let slice = match s.shard {
        Some(shard) => format!(
            " (shard {} of {}: points {}..{})",
            shard.index, shard.count, s.points.first, s.points.end
        ),
        None => String::new(),
    };
    let _ = writeln!(
        t,
        "flexrock {}: sweep of {}{slice} in {}",
        crate::commands::run::VERSION,
        crate::writers::count(s.points.total, "point", "points"),
        report.dir.display()
    );
    let c = s.counts;
    let _ = writeln!(
        t,
        "  {} ok, {} invalid, {} failed; {} overturned{}",
        c.ok,
        c.invalid,
        c.failed,
        c.overturned,
        if s.plan.find_min.is_some() {
            " within the searched interval"
        } else if s.plan.row_columns.is_some() {
            " (a column of the row overturned and ended the run)"
        } else {
            ""
        }
    );
    let _ = write!(
        t,
        "  {} computed now, {} found done",
        report.computed, report.resumed
    );
    match seconds {
        Some(secs) if report.computed > 0 => {
            let _ = writeln!(
                t,
                " ({:.3} s, {:.0} points/s)",
                secs,
                report.computed as f64 / secs.max(1e-9)
            );
        }
        _ => t.push('\n'),
    }
    for f in &report.files {
        let verb = if report.written { "wrote" } else { "found" };
        let _ = writeln!(t, "  {verb} {}", f.display());
    }
    t
}
