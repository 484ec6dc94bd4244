//! The figure of a row's run, `row_motion.svg` (and `.png`): the floor acceleration; every
//! column's top displacement q(t); and the clear gap of every contact, which falls to zero at
//! each impact. Impacts are thin vertical lines in every panel. The gaps come from the row's
//! own contact geometry ([`flexrock_core::row::Contact::gap`]): no formula of the model is
//! written here.

use crate::error::Result;
use crate::figures::plot::{self, Format, Legend, Panel, Series, VerticalLine};
use flexrock_core::model::RowModel;
use flexrock_core::row::RowSolution;

/// The figure's file stem.
pub const ROW_FIGURE: &str = "row_motion";
/// Its size in pixels.
const SIZE: (u32, u32) = (1100, 900);

/// The figure files: row_motion.svg and row_motion.png.
pub fn figures(model: &RowModel, solution: &RowSolution) -> Result<Vec<(String, Vec<u8>)>> {
    let panels = panels(model, solution);
    let mut files = Vec::new();
    for format in [Format::Svg, Format::Png] {
        let name = format!("{ROW_FIGURE}.{}", format.extension());
        let bytes = plot::figure_sized(format, &name, &panels, 1, SIZE)?;
        files.push((name, bytes));
    }
    Ok(files)
}

/// The three panels.
pub fn panels(model: &RowModel, solution: &RowSolution) -> Vec<Panel> {
    let n_impacts = solution.impacts.len();
    let label = format!("impact ({n_impacts})");
    let impacts: Vec<VerticalLine> = solution
        .impacts
        .iter()
        .map(|i| VerticalLine {
            x: i.t,
            color: 4,
            label: label.clone(),
        })
        .collect();
    let first = &solution.columns[0].samples;
    let mut floor = Panel::new("Floor acceleration", "t (s)", "a (m/s²)").with(
        Series::line(
            "a(t)",
            first.iter().map(|s| (s.t, s.floor_acc)).collect(),
            0,
        )
        .with_width(2),
    );
    floor.legend = Legend::Outside;
    let mut q = Panel::new(
        "Top displacement of each column i (H × B, pre-uplift period T)",
        "t (s)",
        "q (m)",
    );
    for (i, column) in solution.columns.iter().enumerate() {
        let body = &model.bodies[i];
        // The pre-uplift period from the automaton's own rate: k = omega^2.
        let period = model.row.columns()[i]
            .automaton
            .linear_form(flexrock_core::automaton::Mode::PreUplift)
            .map_or(f64::NAN, |f| std::f64::consts::TAU / f.stiffness.sqrt());
        let name = format!(
            "{i}: {} × {} m, T = {} s",
            crate::writers::significant(body.height, 4),
            crate::writers::significant(body.width, 4),
            crate::writers::significant(period, 3)
        );
        q = q.with(
            Series::line(
                &name,
                column.samples.iter().map(|s| (s.t, s.q)).collect(),
                i + 1,
            )
            .with_width(2),
        );
    }
    q.legend = Legend::Outside;
    let mut gaps = Panel::new(
        "Clear gap between neighbours i|j (at rest, and the contact height y)",
        "t (s)",
        "gap (mm)",
    );
    for contact in model.row.contacts() {
        let c = contact.index;
        let (left, right) = (&solution.columns[c], &solution.columns[c + 1]);
        let automata = (
            &model.row.columns()[c].automaton,
            &model.row.columns()[c + 1].automaton,
        );
        // The columns share the output grid; samples at event instants (one column's own)
        // are left out.
        let mut points = Vec::new();
        let mut j = 0;
        for l in &left.samples {
            while j < right.samples.len() && right.samples[j].t < l.t {
                j += 1;
            }
            if let Some(r) = right.samples.get(j).filter(|r| r.t == l.t) {
                let gap = contact.gap(automata, (l.mode, l.q), (r.mode, r.q));
                points.push((l.t, 1e3 * gap));
            }
        }
        points.dedup_by(|a, b| a.0 == b.0);
        let name = format!(
            "{c}|{}: {} mm, y = {} m",
            c + 1,
            crate::writers::significant(1e3 * contact.clearance, 4),
            crate::writers::significant(contact.height, 4)
        );
        gaps = gaps.with(Series::line(&name, points, c + 1).with_width(2));
    }
    gaps.reference_lines = vec![(0.0, "contact".to_string())];
    gaps.legend = Legend::Outside;
    let mut panels = vec![floor, q, gaps];
    for (k, panel) in panels.iter_mut().enumerate() {
        panel.vertical_lines = impacts.clone();
        if k > 0 {
            for line in &mut panel.vertical_lines {
                line.label.clear();
            }
        }
    }
    panels
}
