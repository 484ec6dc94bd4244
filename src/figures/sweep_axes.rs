//! The axes of a sweep's figures: the label of a model-file key, and the cells drawn around
//! an axis's values.

/// The axis label of a model-file key: the quantity's symbol and unit (the key itself for a key
/// without one here).
pub fn axis_label(key: &str) -> String {
    let label = match key {
        "excitation.amplitude" => "aₚ (m/s²)",
        "excitation.period" => "Tₚ (s)",
        "excitation.scale" => "scale factor",
        "excitation.cycles" => "cycles",
        "excitation.start" => "start time (s)",
        "excitation.ramp" => "ramp time (s)",
        "body.height" => "H (m)",
        "body.width" => "B (m)",
        "body.depth" => "depth (m)",
        "body.period" => "T (s)",
        "body.damping_ratio" => "h",
        "body.youngs_modulus" => "E (Pa)",
        "body.flexural_rigidity" => "EI (N m²)",
        "body.density" => "ρ (kg/m³)",
        "body.mass" => "mass (kg)",
        "body.poisson_ratio" => "ν",
        "body.gravity" => "g (m/s²)",
        "solver.dt" => "Δt (s)",
        "solver.rtol" => "rtol",
        "row.gaps" => "gap g, every gap (m)",
        "row.restitution" => "restitution e",
        "row.stiffness" => "contact stiffness k (N/m)",
        "simulation.duration" => "duration (s)",
        _ => return row_key_label(key).unwrap_or_else(|| key.to_string()),
    };
    label.to_string()
}

/// The label of a key of a row: one gap (`row.gaps.I`), a column's key (`column.I.KEY`) or
/// every column's (`column.KEY`), by the label of the body's key.
fn row_key_label(key: &str) -> Option<String> {
    let parts: Vec<&str> = key.split('.').collect();
    let body = |name: &str| {
        let label = axis_label(&format!("body.{name}"));
        (!label.starts_with("body.")).then_some(label)
    };
    let with_unit = |label: &str, suffix: &str| match label.split_once(" (") {
        Some((symbol, unit)) => format!("{symbol}{suffix} ({unit}"),
        None => format!("{label}{suffix}"),
    };
    match parts.as_slice() {
        ["row", "gaps", i] => Some(format!("gap g{} (m)", subscript(i))),
        ["column", i, name] => Some(match (body(name), *name) {
            (Some(label), _) => with_unit(&label, &subscript(i)),
            (None, "q0") => format!("q₀ of column {i} (m)"),
            (None, "qdot0") => format!("q\u{307}₀ of column {i} (m/s)"),
            (None, _) => key.to_string(),
        }),
        ["column", name] => body(name).map(|label| with_unit(&label, ", every column")),
        _ => None,
    }
}

/// A column's or gap's index as subscript digits.
fn subscript(index: &str) -> String {
    index
        .chars()
        .map(|c| match c.to_digit(10) {
            Some(d) => char::from_u32(0x2080 + d).unwrap_or(c),
            None => c,
        })
        .collect()
}

/// Edges of cells centred on ascending `centres`: midpoints, the ends extended by half a cell.
/// Written so that no intermediate sum overflows; empty for no centres.
pub fn edges(centres: &[f64]) -> Vec<f64> {
    let n = centres.len();
    match n {
        0 => return Vec::new(),
        1 => {
            let half = 0.5 * centres[0].abs().max(1e-12) * 0.1;
            return vec![centres[0] - half, centres[0] + half];
        }
        _ => {}
    }
    let half_step = |a: f64, b: f64| 0.5 * b - 0.5 * a;
    let mut e = Vec::with_capacity(n + 1);
    e.push(centres[0] - half_step(centres[0], centres[1]));
    for w in centres.windows(2) {
        e.push(0.5 * w[0] + 0.5 * w[1]);
    }
    e.push(centres[n - 1] + half_step(centres[n - 2], centres[n - 1]));
    e
}

/// The indices of `values` in ascending order of value (NaN last).
pub fn ascending(values: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    order
}

/// True when cells around `values` can be drawn: finite, distinct, and edges that grow.
pub fn drawable(values: &[f64]) -> bool {
    let sorted: Vec<f64> = ascending(values).iter().map(|&i| values[i]).collect();
    let e = edges(&sorted);
    !e.is_empty() && e.iter().all(|x| x.is_finite()) && e.windows(2).all(|w| w[0] < w[1])
}
