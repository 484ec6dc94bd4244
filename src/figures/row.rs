//! The figure of a row's run, `row_motion.svg` (and `.png`): the floor acceleration; every
//! column's top displacement q(t); and the clear gap of every contact, which falls to zero at
//! each impact. Impacts are thin vertical lines in every panel. The gaps come from the row's
//! own contact geometry ([`flexrock_core::bodies::row::Contact::gap`]): no formula of the model is
//! written here. Stretches of held (persistent) contact, and under the compliant law every
//! stretch of contact, are shaded on the gap panel; stretches of faces stuck by friction in a
//! stronger tint over them.
//!
//! And the strip `row_shapes.svg` (and `.png`): the row drawn to true scale at a few instants
//! of its history, each column in its deformed shape at its sample there. Both figures draw from
//! the run's solution only: nothing is solved again.

use crate::error::Result;
use crate::figures::page::{FigureOptions, Format, PAGE_MM};
use crate::figures::plot::{self, Figure, Marker, Panel, RugMark, Series, Span};
use flexrock_core::bodies::row::RowSolution;
use flexrock_core::integrate::solution::Sample;
use flexrock_core::model::RowModel;

/// The figure's file stem.
pub const ROW_FIGURE: &str = "row_motion";
/// The formats a row's figures are written in unless asked otherwise.
pub const FORMATS: [Format; 2] = [Format::Svg, Format::Png];

/// The figure files, row_motion.svg, .png, ... in the formats and size of `options`.
pub fn figures(
    model: &RowModel,
    solution: &RowSolution,
    options: &FigureOptions,
) -> Result<Vec<(String, Vec<u8>)>> {
    let figure = Figure::new(panels(model, solution), 1)
        .shared_x()
        .aspect(4.0, 28.0);
    plot::files(ROW_FIGURE, &figure, options, PAGE_MM)
}

/// The three panels.
pub fn panels(model: &RowModel, solution: &RowSolution) -> Vec<Panel> {
    let n_impacts = solution.impacts.len();
    let label = format!("impact ({n_impacts})");
    let impacts: Vec<RugMark> = solution
        .impacts
        .iter()
        .map(|i| RugMark {
            x: i.t,
            color: 0,
            top: false,
            label: label.clone(),
            marker: Marker::Cross,
        })
        .collect();
    let first = &solution.columns[0].samples;
    let floor = Panel::new("", "t (s)", "a (m/s²)").with(Series::line(
        "",
        first.iter().map(|s| (s.t, s.floor_acc)).collect(),
        0,
    ));
    let mut q = Panel::new("", "t (s)", "q (m)");
    for (i, column) in solution.columns.iter().enumerate() {
        let body = &model.bodies[i];
        // The pre-uplift period from the automaton's own rate: k = omega^2.
        let period = model.row.columns()[i]
            .automaton
            .linear_form(flexrock_core::physics::automaton::Mode::PreUplift)
            .map_or(f64::NAN, |f| std::f64::consts::TAU / f.stiffness.sqrt());
        let name = format!(
            "column {i}: H × B = {} × {} m, T = {} s",
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
            .with_dash(DASHES[i % DASHES.len()]),
        );
    }
    let mut gaps = Panel::new("", "t (s)", "clear gap (mm)");
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
            "gap {c}|{}: {} mm at rest, at y = {} m",
            c + 1,
            crate::writers::significant(1e3 * contact.clearance, 4),
            crate::writers::significant(contact.height, 4)
        );
        // The gaps in colours after the columns' (a colour means one thing in the figure).
        let color = model.bodies.len() + 1 + c;
        gaps = gaps.with(Series::line(&name, points, color).with_dash(DASHES[c % DASHES.len()]));
    }
    gaps.reference_lines = vec![(0.0, "contact".to_string())];
    // Held contact (persistent contact), and under the compliant law every stretch of contact,
    // shaded over its stretch in the pair's colour; the legend counts each pair's stretches.
    let shade = |stretches: &[(usize, f64, Option<f64>)], what: &str, strong: bool| -> Vec<Span> {
        stretches
            .iter()
            .map(|&(contact, from, to)| {
                let count = stretches.iter().filter(|o| o.0 == contact).count();
                Span {
                    from,
                    to: to.unwrap_or(solution.final_time),
                    color: model.bodies.len() + 1 + contact,
                    label: format!("{contact}|{} {what} ({count})", contact + 1),
                    strong,
                }
            })
            .collect()
    };
    let held: Vec<_> = (solution.held.iter())
        .map(|h| (h.contact, h.t_start, h.t_end))
        .collect();
    let touching: Vec<_> = (solution.contacts.iter())
        .map(|s| (s.contact, s.t_start, s.t_end))
        .collect();
    // Faces stuck by friction, within their stretch of contact, in a stronger tint.
    let stuck: Vec<_> = (solution.sticking.iter())
        .map(|s| (s.contact, s.t_start, s.t_end))
        .collect();
    gaps.spans = shade(&held, "held", false);
    gaps.spans.extend(shade(&touching, "in contact", false));
    gaps.spans.extend(shade(&stuck, "faces stuck", true));
    // The legend lists the pairs in order, a pair's stuck stretches drawn over its contacts.
    gaps.spans.sort_by_key(|span| (span.color, span.strong));
    let mut panels = vec![floor, q, gaps];
    for panel in &mut panels {
        panel.rug = impacts.clone();
    }
    panels
}

/// The dashes of the columns' (and gaps') curves in turn, so that they differ in greyscale.
const DASHES: [plot::Dash; 3] = [plot::Dash::Solid, plot::Dash::Dashed, plot::Dash::DashDot];

/// The strip's file stem.
pub const SHAPES_FIGURE: &str = "row_shapes";
/// The most times a strip draws.
pub const MAX_SHAPE_TIMES: usize = 8;
/// How many times the strip chooses on its own.
const AUTOMATIC_TIMES: usize = 4;
/// The height of each panel's plotting area, mm, about (for the resolution of the drawn faces).
const SHAPE_PLOT_MM: f64 = 60.0;
/// Segments along each face of a drawn column, at most.
const FACE_POINTS: usize = 40;
/// A contact whose clear gap is within this of zero (m) is drawn as touching.
const TOUCHING: f64 = 1e-9;

/// One time of the strip, and why it was chosen (empty when the user gave it).
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeTime {
    /// The time, s.
    pub t: f64,
    /// Why it was chosen, e.g. "first impact" (empty: given with --shapes-at).
    pub why: String,
}

/// Every instant at which each column of the run has a sample (the output grid; an impact, where
/// every column takes part in it), with each column's state there: its last sample at that
/// instant, after the events there. The strip draws these states, so that it shows the run.
pub fn sampled_instants(solution: &RowSolution) -> Vec<(f64, Vec<Sample>)> {
    let mut next = vec![0; solution.columns.len()];
    let mut instants: Vec<(f64, Vec<Sample>)> = Vec::new();
    let Some(first) = solution.columns.first() else {
        return instants;
    };
    for sample in &first.samples {
        let t = sample.t;
        if instants.last().is_some_and(|(last, _)| *last == t) {
            continue;
        }
        let mut state = Vec::with_capacity(solution.columns.len());
        for (column, at) in solution.columns.iter().zip(&mut next) {
            while column.samples.get(*at).is_some_and(|s| s.t < t) {
                *at += 1;
            }
            let mut last = None;
            while let Some(s) = column.samples.get(*at).filter(|s| s.t == t) {
                last = Some(s.clone());
                *at += 1;
            }
            match last {
                Some(s) => state.push(s),
                None => break,
            }
        }
        if state.len() == solution.columns.len() {
            instants.push((t, state));
        }
    }
    instants
}

/// True when the instant `at` is the time `t` (to rounding: a grid time k × dt may differ from
/// the decimal typed by an ulp).
fn same_instant(at: f64, t: f64) -> bool {
    (at - t).abs() <= 1e-9 * t.abs().max(1.0)
}

/// The strip's times when none are given: in this order of preference, the first uplift of any
/// column, the first impact, the largest lean of the row (the largest |q| of any column at an
/// instant of [`sampled_instants`]), the middle of the longest stretch of held contact, and the
/// last impact; at most `AUTOMATIC_TIMES` (4) of them, a time within 1 % of the duration of one
/// already taken left out, sorted. Each is the first instant of [`sampled_instants`] at or after
/// it: one after an event says so ("after first impact"). A row where none of these happens (a
/// row at rest) is drawn at its last instant.
pub fn automatic_shape_times(
    model: &RowModel,
    solution: &RowSolution,
    instants: &[(f64, Vec<Sample>)],
) -> Vec<ShapeTime> {
    use flexrock_core::physics::automaton::EventKind;
    // (time, why, an event's instant: drawn later says "after")
    let mut candidates: Vec<(f64, String, bool)> = Vec::new();
    let first_uplift = solution
        .columns
        .iter()
        .enumerate()
        .filter_map(|(i, c)| {
            c.events
                .iter()
                .find(|e| e.kind == EventKind::Uplift)
                .map(|e| (e.t, i))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((t, i)) = first_uplift {
        candidates.push((t, format!("first uplift of {i}"), true));
    }
    if let Some(first) = solution.impacts.first() {
        candidates.push((first.t, "first impact".to_string(), true));
    }
    let lean = instants
        .iter()
        .flat_map(|(t, state)| (state.iter().enumerate()).map(move |(i, s)| (s.q.abs(), *t, i)))
        .filter(|(q, _, _)| *q > 0.0)
        .max_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((_, t, i)) = lean {
        candidates.push((t, format!("largest lean of {i}"), false));
    }
    let longest = solution
        .held
        .iter()
        .map(|h| (h.t_start, h.t_end.unwrap_or(solution.final_time)))
        .max_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)));
    if let Some((from, to)) = longest {
        candidates.push((0.5 * (from + to), "held contact".to_string(), false));
    }
    if let Some(last) = solution.impacts.last() {
        candidates.push((last.t, "last impact".to_string(), true));
    }
    let apart = 0.01 * model.duration;
    let mut chosen: Vec<ShapeTime> = Vec::new();
    for (t, why, event) in candidates {
        if chosen.len() == AUTOMATIC_TIMES {
            break;
        }
        let Some(&(at, _)) = instants
            .iter()
            .find(|(at, _)| *at >= t || same_instant(*at, t))
        else {
            continue;
        };
        let why = if event && !same_instant(at, t) {
            format!("after {why}")
        } else {
            why
        };
        if chosen.iter().all(|c| (c.t - at).abs() > apart) {
            chosen.push(ShapeTime { t: at, why });
        }
    }
    if chosen.is_empty() {
        if let Some(&(t, _)) = instants.last() {
            chosen.push(ShapeTime {
                t,
                why: "end".to_string(),
            });
        }
    }
    chosen.sort_by(|a, b| a.t.total_cmp(&b.t));
    chosen
}

/// The times of `--shapes-at` (comma-separated seconds), sorted: each finite and in
/// [0, `duration`], at most [`MAX_SHAPE_TIMES`]. Errors name the flag, the value and the rule.
pub fn parse_shape_times(text: &str, duration: f64) -> Result<Vec<ShapeTime>> {
    let refuse = |rule: String| -> crate::error::Error {
        flexrock_core::Error::invalid("--shapes-at", text.to_string(), &rule).into()
    };
    let mut times = Vec::new();
    for item in text.split(',') {
        let item = item.trim();
        let t: f64 = item.parse().map_err(|_| {
            refuse(format!(
                "must be times in seconds separated by commas (e.g. 1.2,3.5); {item:?} is not a number"
            ))
        })?;
        if !(t.is_finite() && (0.0..=duration).contains(&t)) {
            return Err(refuse(format!(
                "every time must be finite and within [0, {duration}] s, the run's duration; {item} is not"
            )));
        }
        times.push(t);
    }
    if times.len() > MAX_SHAPE_TIMES {
        return Err(refuse(format!(
            "at most {MAX_SHAPE_TIMES} times (one panel each); {} given",
            times.len()
        )));
    }
    times.sort_by(f64::total_cmp);
    times.dedup();
    Ok(times
        .into_iter()
        .map(|t| ShapeTime {
            t,
            why: String::new(),
        })
        .collect())
}

/// A column's outline in its deformed shape, closed (m, the floor at y = 0): the body of width
/// `width` and height `height` standing with its left toe at `x0` at rest, each section moved
/// across by `s` U(y/H) (`shape` is U, 1 at the top), then turned as a rigid body by r/H about
/// its pivot toe (the right toe for `Mode::RockRight`, the left for `Mode::RockLeft`; before
/// uplift r = 0), to the small-rotation order of the model: a point at (x, y) moves by
/// (y r/H, -(x - x_pivot) r/H). So the top moves across by s + r = q and the toe away from the
/// pivot lifts by B |r| / H. Each face is drawn in `segments` straight pieces.
pub fn column_outline(
    x0: f64,
    (width, height): (f64, f64),
    (s, r): (f64, f64),
    mode: flexrock_core::physics::automaton::Mode,
    shape: &dyn Fn(f64) -> f64,
    segments: usize,
) -> Vec<(f64, f64)> {
    let place = |x: f64, y: f64| deformed_point(x0, (width, height), (s, r), mode, shape, (x, y));
    let segments = segments.max(1);
    let heights: Vec<f64> = (0..=segments)
        .map(|k| height * k as f64 / segments as f64)
        .collect();
    let mut outline: Vec<(f64, f64)> = heights.iter().map(|&y| place(x0, y)).collect();
    outline.extend(heights.iter().rev().map(|&y| place(x0 + width, y)));
    outline.push(outline[0]);
    outline
}

/// Where the point (x, y) of the column of [`column_outline`] (at rest) is drawn.
pub fn deformed_point(
    x0: f64,
    (width, height): (f64, f64),
    (s, r): (f64, f64),
    mode: flexrock_core::physics::automaton::Mode,
    shape: &dyn Fn(f64) -> f64,
    (x, y): (f64, f64),
) -> (f64, f64) {
    use flexrock_core::physics::automaton::Mode;
    let pivot = match mode {
        Mode::RockLeft => x0,
        Mode::RockRight => x0 + width,
        _ if r < 0.0 => x0,
        _ => x0 + width,
    };
    let theta = r / height;
    let flexed = x + s * shape(y / height);
    (flexed + theta * y, y - theta * (x - pivot))
}

/// The strip's figure files, row_shapes.svg, .png, ... in the formats and size of `options`:
/// one panel per time of `times`, each the row at that instant of `instants` (see
/// [`sampled_instants`]) drawn to true scale. A time that is no such instant is refused, naming
/// `--shapes-at`: the strip shows the run, and the run has no state there.
pub fn shape_figures(
    model: &RowModel,
    solution: &RowSolution,
    instants: &[(f64, Vec<Sample>)],
    times: &[ShapeTime],
    options: &FigureOptions,
) -> Result<Vec<(String, Vec<u8>)>> {
    let mut states = Vec::with_capacity(times.len());
    for time in times {
        let Some((_, state)) = instants.iter().find(|(at, _)| same_instant(*at, time.t)) else {
            return Err(flexrock_core::Error::invalid(
                "--shapes-at",
                crate::writers::shortest(time.t),
                &format!(
                    "every time must be an instant of the row's history, where every column has \
                     a sample: a multiple of simulation.output_dt ({} s) up to the run's end ({} s)",
                    crate::writers::shortest(model.settings.output_dt),
                    crate::writers::shortest(solution.final_time)
                ),
            )
            .into());
        };
        states.push(state.clone());
    }
    let panels = shape_panels(model, solution, times, &states);
    // Each panel as wide as the row drawn to scale needs, and room for its title and legend.
    let span = panels
        .first()
        .and_then(|p| p.series.last())
        .map_or((1.0, 1.0), |frame| {
            let (a, b) = (frame.points[0], frame.points[1]);
            (b.0 - a.0, b.1 - a.1)
        });
    // Plotting areas of the drawing's own proportions (with the paddings of an equal-aspect
    // panel: 3 % each side across, 5 % up and down), no narrower than half their height.
    let aspect = ((1.06 * span.0) / (1.1 * span.1)).max(0.5);
    let columns = panels.len();
    let figure = Figure::new(panels, columns).aspect(aspect, SHAPE_PLOT_MM);
    plot::files(SHAPES_FIGURE, &figure, options, PAGE_MM)
}

/// The left toe of each column at rest: the bases spaced by the widths and the gaps.
pub fn base_positions(model: &RowModel) -> Vec<f64> {
    let mut x = 0.0;
    let mut at = Vec::new();
    for (i, body) in model.bodies.iter().enumerate() {
        at.push(x);
        x += body.width + model.section.gaps.get(i).copied().unwrap_or(0.0);
    }
    at
}

/// The strip's panels, from each time's state of every column.
pub fn shape_panels(
    model: &RowModel,
    solution: &RowSolution,
    times: &[ShapeTime],
    states: &[Vec<Sample>],
) -> Vec<Panel> {
    use flexrock_core::physics::constants::flexural_shape_at;
    let bases = base_positions(model);
    let shapes: Vec<_> = model
        .bodies
        .iter()
        .map(|body| {
            let body = body.clone();
            move |xi: f64| {
                if xi >= 1.0 {
                    1.0
                } else {
                    flexural_shape_at(&body, xi).unwrap_or(f64::NAN)
                }
            }
        })
        .collect();
    let mut panels = Vec::new();
    let mut bounds = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
    // The drawing's scale, about: the tallest column over the plot's height in dots.
    let tallest = model.bodies.iter().map(|b| b.height).fold(0.0, f64::max);
    let metres_per_pixel = 1.3 * tallest / crate::figures::page::dots(SHAPE_PLOT_MM);
    for (time, state) in times.iter().zip(states) {
        let title = if time.why.is_empty() {
            format!("t = {} s", crate::writers::significant(time.t, 4))
        } else {
            format!(
                "t = {} s, {}",
                crate::writers::significant(time.t, 3),
                time.why
            )
        };
        let mut panel = Panel::new(&title, "x (m)", "y (m)");
        panel.equal_aspect = true;
        let mut outlines = Vec::new();
        for (i, sample) in state.iter().enumerate() {
            let body = &model.bodies[i];
            // About one segment per pixel the bending moves a face across (the figure's
            // coordinates are whole pixels, and more pieces than that draw a staircase).
            let segments = (sample.s.abs() / metres_per_pixel).ceil() as usize;
            let outline = column_outline(
                bases[i],
                (body.width, body.height),
                (sample.s, sample.r),
                sample.mode,
                &shapes[i],
                segments.clamp(1, FACE_POINTS),
            );
            for &(x, y) in &outline {
                bounds = (bounds.0.min(x), bounds.1.max(x), bounds.2.max(y));
            }
            let name = format!(
                "column {i}: {} × {} m",
                crate::writers::significant(body.height, 4),
                crate::writers::significant(body.width, 4)
            );
            panel = panel.with(Series::line(&name, outline.clone(), i + 1));
            outlines.push(outline);
        }
        for contact in model.row.contacts() {
            let c = contact.index;
            let (l, r) = (&state[c], &state[c + 1]);
            let automata = (
                &model.row.columns()[c].automaton,
                &model.row.columns()[c + 1].automaton,
            );
            let gap = contact.gap(automata, (l.mode, l.q), (r.mode, r.q));
            let held = solution.held.iter().any(|h| {
                h.contact == c && h.t_start <= time.t && h.t_end.is_none_or(|end| time.t <= end)
            });
            let struck = solution
                .impacts
                .iter()
                .any(|i| i.contact == c && (i.t - time.t).abs() <= 1e-9 * time.t.max(1.0));
            if !(held || struck || gap <= TOUCHING) {
                continue;
            }
            // The contact point: the left column's right face at the contact's height.
            let body = &model.bodies[c];
            let at = deformed_point(
                bases[c],
                (body.width, body.height),
                (l.s, l.r),
                l.mode,
                &shapes[c],
                (bases[c] + body.width, contact.height),
            );
            let (label, marker, color) = if held {
                (format!("{c}|{} held", c + 1), plot::Marker::Circle, 4)
            } else {
                (
                    format!("{c}|{} touching", c + 1),
                    plot::Marker::TriangleDown,
                    0,
                )
            };
            panel = panel.with(Series::markers(&label, vec![at], color, marker));
        }
        panels.push(panel);
    }
    // One scale for every panel (drawn to true scale: x and y in metres alike): the same
    // ranges, from the floor to the tallest column, across the row and a margin.
    let tallest = model.bodies.iter().map(|b| b.height).fold(0.0, f64::max);
    let margin = 0.15 * (bounds.1 - bounds.0).max(1.0);
    let (left, right) = (bounds.0 - margin, bounds.1 + margin);
    let top = 1.02 * bounds.2.max(tallest);
    for panel in &mut panels {
        panel.series.insert(
            0,
            Series::line("", vec![(left, 0.0), (right, 0.0)], 0).with_width(1.5),
        );
        let mut frame = Series::line("", vec![(left, -0.02 * tallest), (right, top)], 0);
        frame.line = false;
        panel.series.push(frame);
    }
    panels
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrock_core::physics::automaton::Mode;

    fn close(a: (f64, f64), b: (f64, f64)) -> bool {
        (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12
    }

    /// A column rocking about its right toe with known s and r: its top moves across by
    /// q = s + r, the right toe stays where it stood, the left toe lifts by B r / H, and a
    /// section at mid-height moves by s U(1/2) + r/2 (with a made-up shape U = xi^2).
    #[test]
    fn an_outline_is_bent_by_s_and_turned_about_its_toe_by_r() {
        let (x0, b, h, s, r) = (1.5, 0.7, 4.0, 0.03, 0.2);
        let shape = |xi: f64| xi * xi;
        let outline = column_outline(x0, (b, h), (s, r), Mode::RockRight, &shape, FACE_POINTS);
        let n = FACE_POINTS;
        assert_eq!(outline.len(), 2 * n + 3);
        let lift = b * r / h;
        // Left face: bottom to top; right face: top to bottom; closed.
        assert!(close(outline[0], (x0, lift)), "{:?}", outline[0]);
        assert!(
            close(outline[n], (x0 + s + r, h + lift)),
            "{:?}",
            outline[n]
        );
        assert!(
            close(outline[n + 1], (x0 + b + s + r, h)),
            "{:?}",
            outline[n + 1]
        );
        assert!(
            close(outline[2 * n + 1], (x0 + b, 0.0)),
            "{:?}",
            outline[2 * n + 1]
        );
        assert_eq!(outline[2 * n + 2], outline[0]);
        let mid = outline[n / 2];
        assert!(
            close(mid, (x0 + s / 4.0 + r / 2.0, h / 2.0 + lift)),
            "{mid:?}"
        );
        // Rocking about the left toe: it stays, the right toe lifts.
        let outline = column_outline(x0, (b, h), (-s, -r), Mode::RockLeft, &shape, FACE_POINTS);
        assert!(close(outline[0], (x0, 0.0)), "{:?}", outline[0]);
        assert!(
            close(outline[2 * n + 1], (x0 + b, lift)),
            "{:?}",
            outline[2 * n + 1]
        );
        assert!(close(outline[n], (x0 - s - r, h)), "{:?}", outline[n]);
        // Before uplift both toes stay on the floor.
        let outline = column_outline(x0, (b, h), (s, 0.0), Mode::PreUplift, &shape, FACE_POINTS);
        assert!(close(outline[0], (x0, 0.0)) && close(outline[2 * n + 1], (x0 + b, 0.0)));
        assert!(close(outline[n], (x0 + s, h)));
    }

    /// The bases stand at the widths plus the gaps: 0, B0 + g0, B0 + g0 + B1 + g1.
    #[test]
    fn the_columns_stand_at_their_widths_and_gaps() {
        let text = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/row-record.toml"),
        )
        .unwrap();
        let model = row_model(
            &text.replace(
                "../validation/records/elCentro.AT2",
                std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("validation/records/elCentro.AT2")
                    .to_str()
                    .unwrap(),
            ),
        );
        let at = base_positions(&model);
        assert_eq!(at.len(), 3);
        assert!(close((at[0], at[1]), (0.0, 0.7 + 0.015)));
        assert!((at[2] - (0.7 + 0.015 + 0.7 + 0.01)).abs() < 1e-12);
    }

    fn row_model(text: &str) -> RowModel {
        let dir = std::env::temp_dir().join(format!("flexrock-strip-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{}.toml", text.len()));
        std::fs::write(&path, text).unwrap();
        RowModel::load(&path, None).unwrap()
    }

    /// The strip draws the run's own samples: at a grid time every column's state is its
    /// sample there (the last, after the events there); at an impact of a pair both columns
    /// have a sample, and the contact is closed (to rounding), which no grid sample shows.
    #[test]
    fn the_strip_draws_the_runs_own_samples() {
        let text = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/row-pair.toml"),
        )
        .unwrap();
        let model = row_model(&text);
        let solution = flexrock_core::simulate::simulate_row(&model).unwrap();
        let instants = sampled_instants(&solution);
        let last = solution.impacts.last().expect("the pair strikes").t;
        // A grid time after the last impact (the grid is 0.005 s).
        let t = ((last + 0.3) / 0.005).round() * 0.005;
        let (_, state) = instants
            .iter()
            .find(|(at, _)| same_instant(*at, t))
            .expect("a grid time is an instant of the strip");
        for (i, column) in solution.columns.iter().enumerate() {
            let sample = column
                .samples
                .iter()
                .rev()
                .find(|s| (s.t - t).abs() < 1e-12)
                .expect("a grid sample");
            assert_eq!(state[i].q, sample.q, "column {i}");
            assert_eq!(state[i].s, sample.s, "column {i}");
        }
        let first = solution.impacts[0].t;
        let (_, state) = instants
            .iter()
            .find(|(at, _)| *at == first)
            .expect("the first impact is an instant of the strip");
        let contact = &model.row.contacts()[0];
        let automata = (
            &model.row.columns()[0].automaton,
            &model.row.columns()[1].automaton,
        );
        let gap = contact.gap(
            automata,
            (state[0].mode, state[0].q),
            (state[1].mode, state[1].q),
        );
        assert!(gap.abs() < 1e-9, "gap {gap} at the first impact");
        // The automatic strip shows it as it is, not after it.
        let times = automatic_shape_times(&model, &solution, &instants);
        assert!(
            times
                .iter()
                .any(|s| s.t == first && s.why == "first impact"),
            "{times:?}"
        );
        // A time between grid points is no instant of the run: refused, naming the flag.
        let between = ShapeTime {
            t: t + 0.0025,
            why: String::new(),
        };
        let e = shape_figures(
            &model,
            &solution,
            &instants,
            &[between],
            &FigureOptions::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("--shapes-at") && e.contains("output_dt"), "{e}");
    }
}
