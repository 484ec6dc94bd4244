//! `flexrock rigid`: Housner's rigid block of the body's height, width and gravity, alone on the
//! model's floor (its horizontal and vertical motions); events.csv and summary.json.

use std::path::{Path, PathBuf};

use flexrock_core::analysis::rigid_search::RigidSearch;
use flexrock_core::analysis::sweep::HousnerOptions;
use flexrock_core::bodies::rigid::{RigidBlock, RigidOutcome};
use flexrock_core::model::Model;
use flexrock_core::tables::rigid_results::{rigid_event_row, RigidSummary, RIGID_EVENT_COLUMNS};

use crate::writers::{json_bytes, write_atomically, Table};
use crate::Result;

/// summary.json of `flexrock rigid`: the run's summary, and the search's if one was made.
#[derive(serde::Serialize)]
pub struct RigidFile {
    /// The run of the model as given.
    #[serde(flatten)]
    pub summary: RigidSummary,
    /// The smallest overturning value of --find-min, or null.
    pub find_min: Option<RigidSearch>,
}

/// The block's run and what it wrote.
pub struct RigidReport {
    /// The run's summary.
    pub summary: RigidSummary,
    /// The search's result.
    pub search: Option<RigidSearch>,
    /// The files written.
    pub written: Vec<PathBuf>,
}

/// Runs Housner's block of `model`'s body, made as `options` say, and writes its events.csv
/// and summary.json (with the result of `search`, if one was made) to `out` (both or neither).
pub fn run(
    model: &Model,
    options: &HousnerOptions,
    search: Option<RigidSearch>,
    out: &Path,
) -> Result<RigidReport> {
    let b = &model.body;
    let block = RigidBlock::housner(b.height, b.width, b.gravity)
        .and_then(|block| options.apply(block))
        .map_err(flexrock_core::Error::from)?;
    let outcome = flexrock_core::simulate_rigid(model, &block)?;
    let file = RigidFile {
        summary: RigidSummary::of(model, &block, &outcome),
        find_min: search,
    };
    let written = write_atomically(
        out,
        &[
            ("events.csv", events_csv(&outcome)),
            ("summary.json", json_bytes(&file)),
        ],
    )?;
    Ok(RigidReport {
        summary: file.summary,
        search: file.find_min,
        written,
    })
}

/// events.csv of a rigid run.
fn events_csv(outcome: &RigidOutcome) -> Vec<u8> {
    let mut table = Table::new(&RIGID_EVENT_COLUMNS);
    for event in &outcome.events {
        table.row(rigid_event_row(event));
    }
    table.into_bytes()
}

/// What the command prints: the outcome in a few lines, then the files.
pub fn report_text(report: &RigidReport) -> String {
    let s = &report.summary;
    let n = flexrock_core::base::format::shortest;
    let time = |t: Option<f64>| t.map_or_else(|| "none".to_string(), |t| format!("{} s", n(t)));
    let mut text = format!(
        "rigid block ({} equation, e = {}): first uplift {}, {} impact{}, {}\n\
         largest |theta|/alpha = {} at t = {} s\n",
        s.block.equation,
        n(s.block.restitution),
        time(s.first_uplift_s),
        s.n_impact,
        if s.n_impact == 1 { "" } else { "s" },
        match s.t_overturn_s {
            Some(t) => format!("overturned at t = {} s", n(t)),
            None => "did not overturn".to_string(),
        },
        flexrock_core::base::format::significant(s.max_abs_theta_over_alpha, 6),
        n(s.t_max_abs_q_s),
    );
    if let Some(found) = &report.search {
        text.push_str(&match found.min_overturning {
            Some(value) => format!(
                "smallest overturning {} = {} ({} band{} of overturning values; stands at {})\n",
                found.key,
                n(value),
                found.n_bands,
                if found.n_bands == 1 { "" } else { "s" },
                found.safe_below.map_or_else(|| "none".to_string(), n)
            ),
            None => format!(
                "no value of {} in [{}, {}] overturns it\n",
                found.key,
                n(found.lo),
                n(found.hi)
            ),
        });
    }
    for f in &report.written {
        text.push_str(&format!("wrote {}\n", f.display()));
    }
    text
}
