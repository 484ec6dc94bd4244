//! The figures as drawn: read back from the SVG files the command line writes, element by
//! element, and checked on their geometry and text (legends that cover no data, curves that stay
//! visible where they nearly coincide, events on every time panel, labels that are quantities
//! with units), plus the figure of a sweep over records and `flexrock plot`'s formats, sizes and
//! time window.

use crate::common;

use std::path::{Path, PathBuf};

use crate::common::{flexrock, flexrock_in, reference_model, repo, scratch_dir};

fn stderr_of(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn run_ok(args: &[&str]) {
    let o = flexrock(args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

// ---------------------------------------------------------------------------------------------
// A small reader of the SVG plotters writes: one element per tag, absolute coordinates.

/// One drawn element of an SVG, in document order.
#[derive(Debug, Clone)]
struct Element {
    tag: String,
    attrs: Vec<(String, String)>,
    /// The text of a <text> element.
    text: String,
}

impl Element {
    fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    fn number(&self, name: &str) -> f64 {
        self.attr(name)
            .and_then(|v| v.parse().ok())
            .unwrap_or(f64::NAN)
    }

    /// The points of a polyline or polygon.
    fn points(&self) -> Vec<(f64, f64)> {
        self.attr("points")
            .unwrap_or("")
            .split_whitespace()
            .filter_map(|p| {
                let (x, y) = p.split_once(',')?;
                Some((x.parse().ok()?, y.parse().ok()?))
            })
            .collect()
    }

    fn stroke(&self) -> &str {
        self.attr("stroke").unwrap_or("none")
    }

    fn stroke_width(&self) -> f64 {
        self.attr("stroke-width")
            .and_then(|v| v.parse().ok())
            .unwrap_or(1.0)
    }

    /// A grey (r = g = b, not black) or translucent stroke: grid lines, not data.
    fn is_grid(&self) -> bool {
        let s = self.stroke();
        let grey = s.len() == 7 && s[1..3] == s[3..5] && s[3..5] == s[5..7] && s != "#000000";
        let translucent = self
            .attr("opacity")
            .and_then(|v| v.parse::<f64>().ok())
            .is_some_and(|o| o < 1.0);
        grey || translucent
    }
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

fn parse_svg(svg: &str) -> Vec<Element> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        rest = &rest[start + 1..];
        let end = rest.find('>').expect("a closed tag");
        let tag_text = &rest[..end];
        rest = &rest[end + 1..];
        if tag_text.starts_with('/') || tag_text.starts_with('?') || tag_text.starts_with('!') {
            continue;
        }
        let name_end = tag_text
            .find(|c: char| c.is_whitespace() || c == '/')
            .unwrap_or(tag_text.len());
        let tag = tag_text[..name_end].to_string();
        let mut attrs = Vec::new();
        let mut a = &tag_text[name_end..];
        while let Some(eq) = a.find("=\"") {
            let key = a[..eq].trim().to_string();
            let after = &a[eq + 2..];
            let close = after.find('"').expect("a closed attribute");
            attrs.push((key, unescape(&after[..close])));
            a = &after[close + 1..];
        }
        let text = if tag == "text" {
            let close = rest.find("</text>").unwrap_or(0);
            unescape(rest[..close].trim())
        } else {
            String::new()
        };
        out.push(Element { tag, attrs, text });
    }
    out
}

/// A straight stroke with its half width, pixels.
#[derive(Debug, Clone, Copy)]
struct Stroke {
    a: (f64, f64),
    b: (f64, f64),
    half: f64,
}

/// The strokes of a data element (polyline, line, circle, polygon); empty for grid lines and
/// for anything else.
fn strokes(e: &Element) -> Vec<Stroke> {
    if e.is_grid() {
        return Vec::new();
    }
    match e.tag.as_str() {
        "polyline" | "polygon" => {
            let p = e.points();
            let half = 0.5 * e.stroke_width();
            if p.len() == 1 {
                return vec![Stroke {
                    a: p[0],
                    b: p[0],
                    half,
                }];
            }
            p.windows(2)
                .map(|w| Stroke {
                    a: w[0],
                    b: w[1],
                    half,
                })
                .collect()
        }
        "line" => vec![Stroke {
            a: (e.number("x1"), e.number("y1")),
            b: (e.number("x2"), e.number("y2")),
            half: 0.5 * e.stroke_width(),
        }],
        "circle" => {
            let c = (e.number("cx"), e.number("cy"));
            vec![Stroke {
                a: c,
                b: c,
                half: e.number("r"),
            }]
        }
        _ => Vec::new(),
    }
}

/// Distance from a point to a segment.
fn distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (cx, cy) = (a.0 + t * dx, a.1 + t * dy);
    ((p.0 - cx).powi(2) + (p.1 - cy).powi(2)).sqrt()
}

/// True when a stroke touches the box (left, top, right, bottom): sampled every 0.25 pixel
/// along the stroke, a sample within the box widened by the stroke's half width.
fn touches(s: &Stroke, (l, t, r, b): (f64, f64, f64, f64)) -> bool {
    let len = ((s.b.0 - s.a.0).powi(2) + (s.b.1 - s.a.1).powi(2)).sqrt();
    let n = (len / 0.25).ceil().max(1.0) as usize;
    (0..=n).any(|i| {
        let f = i as f64 / n as f64;
        let (x, y) = (s.a.0 + f * (s.b.0 - s.a.0), s.a.1 + f * (s.b.1 - s.a.1));
        x >= l - s.half && x <= r + s.half && y >= t - s.half && y <= b + s.half
    })
}

/// Every inside legend box of an SVG (the frame rectangle drawn in #B4B4B4) and the data
/// strokes drawn before it that touch it.
fn covered_by_legends(svg: &str) -> (usize, Vec<String>) {
    let elements = parse_svg(svg);
    let mut boxes = 0;
    let mut hits = Vec::new();
    for (i, e) in elements.iter().enumerate() {
        if e.tag != "rect" || e.stroke() != "#B4B4B4" {
            continue;
        }
        boxes += 1;
        let (x, y) = (e.number("x"), e.number("y"));
        let rect = (x, y, x + e.number("width"), y + e.number("height"));
        // The legend is drawn last in its panel: what comes before the box is the panel's
        // drawing (and the panels before it, which lie elsewhere).
        for d in &elements[..i] {
            if strokes(d).iter().any(|s| touches(s, rect)) {
                hits.push(format!("{} {} {:?}", d.tag, d.stroke(), rect));
            }
        }
    }
    (boxes, hits)
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The paper's example compared with Newmark (dt = 0.02 s), as in validation/.
fn compare_dir(name: &str) -> PathBuf {
    let out = scratch_dir(name).join("compare");
    run_ok(&[
        "compare",
        reference_model().to_str().unwrap(),
        "--dt",
        "0.02",
        "--out",
        out.to_str().unwrap(),
    ]);
    out
}

fn run_dir(name: &str, extra: &[&str]) -> PathBuf {
    let out = scratch_dir(name).join("run");
    let o = common::run_reference(&out, extra);
    assert!(o.status.success(), "{extra:?}: {}", stderr_of(&o));
    out
}

// ---------------------------------------------------------------------------------------------

#[test]
fn legends_cover_no_drawn_data() {
    let compare = compare_dir("figures-legend-compare");
    let run = run_dir("figures-legend-run", &["--plot"]);
    for path in [
        compare.join("compare_relations.svg"),
        compare.join("compare.svg"),
        run.join("plot_force.svg"),
        run.join("plot_motion.svg"),
        run.join("plot_energy.svg"),
    ] {
        let (_, hits) = covered_by_legends(&read(&path));
        assert!(
            hits.is_empty(),
            "{}: the legend covers {} drawn elements, e.g. {:?}",
            path.display(),
            hits.len(),
            &hits[..hits.len().min(3)]
        );
    }
}

#[test]
fn the_checker_sees_a_legend_over_a_curve() {
    // The checker itself: a box drawn over a line is found, one beside it is not.
    let svg = r##"<svg><polyline fill="none" opacity="1" stroke="#D62728" stroke-width="1" points="0,50 100,50 "/>
<rect x="40" y="40" width="20" height="20" opacity="1" fill="none" stroke="#B4B4B4"/>
<rect x="40" y="70" width="20" height="20" opacity="1" fill="none" stroke="#B4B4B4"/></svg>"##;
    let (boxes, hits) = covered_by_legends(svg);
    assert_eq!(boxes, 2);
    assert_eq!(hits.len(), 1, "{hits:?}");
}

/// The strokes of the polylines of colour `stroke` that lie in the box (left, top, right,
/// bottom).
fn series_strokes(elements: &[Element], stroke: &str, within: (f64, f64, f64, f64)) -> Vec<Stroke> {
    let (l, t, r, b) = within;
    elements
        .iter()
        .filter(|e| e.tag == "polyline" && e.stroke() == stroke)
        .filter(|e| {
            e.points()
                .iter()
                .all(|&(x, y)| x >= l && x <= r && y >= t && y <= b)
        })
        .flat_map(strokes)
        .collect()
}

/// The stroke colour of the legend swatch of the first entry whose text contains `label` (the
/// last polyline before that text), and the swatch's left end.
fn legend_colour(elements: &[Element], label: &str) -> (String, f64) {
    let t = elements
        .iter()
        .position(|e| e.tag == "text" && e.text.contains(label))
        .unwrap_or_else(|| panic!("no legend entry {label}"));
    let swatch = elements[..t]
        .iter()
        .rev()
        .find(|e| e.tag == "polyline")
        .expect("a swatch before the entry");
    let left = swatch
        .points()
        .iter()
        .map(|p| p.0)
        .fold(f64::INFINITY, f64::min);
    (swatch.stroke().to_string(), left)
}

/// The share of the length of `under` (sampled every pixel) that `over`, drawn after it,
/// leaves visible to the eye: no `over` stroke touches it (two thin lines within a pixel of
/// each other read as one line), or its stroke sticks out at least a pixel on both sides of
/// the `over` stroke.
fn visible_share(under: &[Stroke], over: &[Stroke]) -> f64 {
    let (mut seen, mut all) = (0usize, 0usize);
    for s in under {
        let len = ((s.b.0 - s.a.0).powi(2) + (s.b.1 - s.a.1).powi(2)).sqrt();
        let n = len.ceil().max(1.0) as usize;
        for i in 0..n {
            let f = i as f64 / n as f64;
            let p = (s.a.0 + f * (s.b.0 - s.a.0), s.a.1 + f * (s.b.1 - s.a.1));
            all += 1;
            let hidden = over
                .iter()
                .any(|o| distance(p, o.a, o.b) <= o.half + s.half + 0.5 && s.half < o.half + 1.0);
            if !hidden {
                seen += 1;
            }
        }
    }
    seen as f64 / all.max(1) as f64
}

/// spectrum.svg of the pulse map's smallest overturning amplitude up to 15 m/s^2 at `periods`
/// (comma-separated, s), with `extra` flags, in a scratch directory `name`.
fn spectrum_svg(name: &str, periods: &str, extra: &[&str]) -> String {
    let out = scratch_dir(name).join("spectrum");
    let model = repo("models/pulse-map.toml");
    let vary = format!("excitation.period={periods}");
    let mut args = vec![
        "sweep",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        &vary,
        "--find-min",
        "excitation.amplitude=0.5:15",
        "--quiet",
    ];
    args.extend_from_slice(extra);
    run_ok(&args);
    read(&out.join("spectrum.svg"))
}

#[test]
fn the_housner_curve_shows_beside_the_rigid_limit_in_the_spectrum() {
    let svg = spectrum_svg(
        "figures-spectrum",
        "0.5,0.8,1.2,2",
        &["--scan", "30", "--tol", "0.001"],
    );
    let elements = parse_svg(&svg);
    let (housner, _) = legend_colour(&elements, "Housner");
    let (limit, _) = legend_colour(&elements, "rigid limit");
    assert_ne!(housner, limit);
    // The first panel's curves: below the legend (above the panels), left of panel (b).
    let label = |text: &str| {
        elements
            .iter()
            .find(|e| e.tag == "text" && e.text == text)
            .unwrap_or_else(|| panic!("no panel label {text}"))
    };
    // The drawing's height in its own units: the last number of the viewBox (its width and
    // height attributes are in mm).
    let height: f64 = elements[0]
        .attr("viewBox")
        .and_then(|v| v.split_whitespace().nth(3)?.parse().ok())
        .expect("a viewBox");
    let panel = (
        0.0,
        label("(a)").number("y"),
        label("(b)").number("x"),
        height,
    );
    let under = series_strokes(&elements, &housner, panel);
    let over = series_strokes(&elements, &limit, panel);
    assert!(!under.is_empty() && !over.is_empty());
    let share = visible_share(&under, &over);
    assert!(
        share > 0.3,
        "only {:.0} % of the Housner curve shows from under the rigid limit's",
        100.0 * share
    );
    // Quantities with units, real Greek, no model keys.
    for text in ["Tₚ (s)", "aₚ (m/s²)", "ωₚ/p", "aₚ/(g tan α)"] {
        assert!(svg.contains(text), "spectrum.svg lacks {text}");
    }
    // Housner's block names its equation.
    assert!(svg.contains("Housner block, small-angle eq."));
    assert!(!svg.contains("excitation."), "a model key as a label");
    assert!(!svg.contains("alpha") && !svg.contains("omega"));
}

/// A period at which nothing overturns up to HI (0.2 s, as in the tutorial's spectrum) is marked
/// at HI rather than left out of the figure without a word; a spectrum where every period
/// overturns has no such entry.
#[test]
fn the_spectrum_marks_the_periods_that_stand_up_to_hi() {
    let svg = spectrum_svg("figures-spectrum-stands", "0.2,0.8", &[]);
    assert!(svg.contains("stands up to 15"), "no entry for 0.2 s");
    // The mark is an open triangle (a polyline closing on itself over a white polygon), not
    // a point of the body's line: that line has no point at 0.2 s, so it is broken there.
    let elements = parse_svg(&svg);
    assert!(elements
        .iter()
        .any(|e| e.tag == "polygon" && e.attr("fill") == Some("#FFFFFF")));
    let svg = spectrum_svg("figures-spectrum-all", "0.8,1.2", &[]);
    assert!(
        !svg.contains("stands up to"),
        "an entry where every period overturns"
    );
}

#[test]
fn map_labels_are_quantities_and_the_colour_bar_is_labelled() {
    let out = scratch_dir("figures-map").join("map");
    run_ok(&[
        "sweep",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.period=lin:0.3:2:6",
        "--vary",
        "excitation.amplitude=lin:1:8:6",
        "--quiet",
    ]);
    let svg = read(&out.join("map.svg"));
    for text in [
        "Tₚ (s)",
        "aₚ (m/s²)",
        "ωₚ/p",
        "aₚ/(g tan α)",
        "max |q|/B: 0–0.2",
        "0.8–1",
        "overturned",
        "boundary of overturning",
    ] {
        assert!(svg.contains(text), "map.svg lacks {text}");
    }
    assert!(!svg.contains("excitation."), "a model key as a label");
    let elements = parse_svg(&svg);
    // No seams: the filled cells of each map overlap their right and lower neighbours, so
    // that no background shows between two cells of one colour in any viewer. Cells are the
    // filled, unstroked rectangles; for each, its right neighbour (same top) starts left of
    // its right edge.
    let cells: Vec<(f64, f64, f64, f64)> = elements
        .iter()
        .filter(|e| e.tag == "rect" && e.stroke() == "none" && e.attr("fill") != Some("#FFFFFF"))
        .map(|e| {
            let (x, y) = (e.number("x"), e.number("y"));
            (x, y, x + e.number("width"), y + e.number("height"))
        })
        .collect();
    // Runs of one colour are drawn as one rectangle: fewer than the cells, but some.
    assert!(cells.len() >= 6, "{} cells", cells.len());
    let mut abutting = 0;
    for c in &cells {
        for d in &cells {
            let same_row = (c.1 - d.1).abs() < 0.5;
            // d follows c on its right: starts within a pixel of c's right edge.
            if same_row && d.0 > c.0 && (d.0 - c.2).abs() <= 1.0 {
                abutting += 1;
                assert!(d.0 < c.2, "a seam between cells at x = {} and {}", c.2, d.0);
            }
        }
    }
    // (Runs of one colour are one rectangle each: 6 by 6 cells make fewer.)
    assert!(abutting >= 4, "{abutting} neighbouring cells");
}

#[test]
fn plot_motion_marks_the_events_on_every_panel() {
    let run = run_dir("figures-events", &["--plot"]);
    let events = std::fs::read_to_string(run.join("events.csv")).unwrap();
    let n_events = events.lines().count() - 1;
    assert!(n_events >= 4, "{n_events} events");
    let svg = read(&run.join("plot_motion.svg"));
    let elements = parse_svg(&svg);
    // The panels (a) to (d), by the heights of their labels.
    let tops: Vec<f64> = ["(a)", "(b)", "(c)", "(d)"]
        .iter()
        .map(|l| {
            elements
                .iter()
                .find(|e| e.tag == "text" && e.text == *l)
                .unwrap_or_else(|| panic!("no panel {l}"))
                .number("y")
        })
        .collect();
    let panel_of = |y: f64| tops.iter().rposition(|&t| y > t).unwrap_or(0);
    // The events of the first three panels are a rug: short vertical ticks of a colour (not
    // lines across the panel, not grid lines), at most 20 dots (5 pt) long. The fourth marks
    // them on the curve (a triangle each) instead.
    let mut rug = [0usize; 4];
    let mut triangles = [0usize; 4];
    for e in &elements {
        let p = e.points();
        if e.tag == "polyline" && !e.is_grid() && e.stroke() != "#000000" && p.len() == 2 {
            let (dx, dy) = ((p[0].0 - p[1].0).abs(), (p[0].1 - p[1].1).abs());
            if dx < 0.5 && dy > 5.0 && dy <= 20.0 {
                rug[panel_of(p[0].1)] += 1;
            }
        }
        if e.tag == "polygon" && p.len() == 3 {
            triangles[panel_of(p[0].1)] += 1;
        }
    }
    for i in 0..3 {
        assert!(
            rug[i] >= n_events,
            "panel {i}: a rug of {} for {n_events} events ({rug:?})",
            rug[i]
        );
    }
    assert!(
        triangles[3] >= n_events,
        "{triangles:?} triangles for {n_events} events"
    );
    // One legend for the figure, one entry per kind of event.
    assert_eq!(
        elements
            .iter()
            .filter(|e| e.tag == "text" && e.text.starts_with("uplift ("))
            .count(),
        1
    );
    // Labels are quantities with units; no figure numbers or file names in titles.
    for name in ["plot_motion.svg", "plot_force.svg", "plot_energy.svg"] {
        let svg = read(&run.join(name));
        for bad in ["Fig.", "summary.json", "q'"] {
            assert!(!svg.contains(bad), "{name} contains {bad}");
        }
    }
    assert!(svg.contains("q\u{307} (m/s)"));
}

#[test]
fn a_sweep_over_records_and_scales_draws_an_incremental_dynamic_analysis() {
    let dir = scratch_dir("figures-ida");
    let out = dir.join("ida");
    let o = flexrock_in(
        &repo(""),
        &[
            "sweep",
            "models/elcentro1940.toml",
            "--out",
            out.to_str().unwrap(),
            "--vary",
            "excitation.path=validation/records/elCentro.AT2,validation/records/A-ELC180.AT2",
            "--vary",
            "excitation.scale=0.5,1,2,4,8",
            "--set",
            "excitation.tail=1",
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let svg = read(&out.join("ida.svg"));
    let summary = read(&out.join("sweep.json"));
    assert!(summary.contains("ida.svg"), "sweep.json lists its figure");
    // The table says which points overturned.
    let mut reader = csv::Reader::from_path(out.join("sweep.csv")).unwrap();
    let headers = reader.headers().unwrap().clone();
    let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
    let overturned = rows
        .iter()
        .filter(|r| &r[col("overturned")] == "true")
        .count();
    let elements = parse_svg(&svg);
    // One legend entry per record, and for the overturned points.
    for name in ["elCentro", "A-ELC180"] {
        assert!(
            elements.iter().any(|e| e.tag == "text" && e.text == name),
            "no line for {name}"
        );
    }
    assert!(svg.contains("scale factor") && svg.contains("max |q|/B"));
    assert!(!svg.contains("excitation."));
    if overturned > 0 {
        assert!(elements
            .iter()
            .any(|e| e.tag == "text" && e.text.starts_with("first overturning")));
    }
    // A sweep of the amplitude beside another setting than records draws no such figure.
    let other = dir.join("not-records");
    run_ok(&[
        "sweep",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        other.to_str().unwrap(),
        "--vary",
        "excitation.shape=symmetric,antisymmetric",
        "--vary",
        "excitation.amplitude=2,4",
        "--quiet",
    ]);
    assert!(!other.join("ida.svg").exists());
    // Each record's line passes through one marker per standing point (circles of its colour).
    let standing = rows.len() - overturned;
    let circles = elements
        .iter()
        .filter(|e| e.tag == "circle" && !e.is_grid())
        .count();
    // The legend draws one circle per record line.
    assert!(
        circles >= standing + 2,
        "{circles} circles for {standing} standing points"
    );
}

// ---------------------------------------------------------------------------------------------
// `flexrock plot`: formats, size, time window.

fn png_size(path: &Path) -> (u32, u32) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let reader = decoder.read_info().unwrap();
    let info = reader.info();
    (info.width, info.height)
}

#[test]
fn plot_writes_png_of_the_size_asked_and_svg_by_default() {
    let run = run_dir("figures-png", &[]);
    let dir = run.to_str().unwrap();
    run_ok(&["plot", dir]);
    assert!(run.join("plot_motion.svg").is_file());
    assert!(!run.join("plot_motion.png").exists());
    // 85 mm by 120 mm at 300 dpi: 1003.9 by 1417.3 dots, to the nearest pixel.
    run_ok(&[
        "plot",
        dir,
        "--format",
        "svg,pdf,png",
        "--width",
        "85mm",
        "--height",
        "12cm",
    ]);
    for stem in ["plot_motion", "plot_force", "plot_energy"] {
        let png = run.join(format!("{stem}.png"));
        assert_eq!(
            std::fs::read(&png).unwrap()[..8],
            [0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A]
        );
        assert_eq!(png_size(&png), (1004, 1417), "{stem}");
        let svg = read(&run.join(format!("{stem}.svg")));
        assert!(
            svg.starts_with("<svg width=\"85mm\" height=\"120mm\""),
            "{stem}"
        );
        let pdf = std::fs::read(run.join(format!("{stem}.pdf"))).unwrap();
        assert!(pdf.starts_with(b"%PDF-"), "{stem}");
    }
    // A bare number is pixels of 1/96 in, as SVG counts them; --dpi sets the PNG's.
    run_ok(&[
        "plot", dir, "--format", "png", "--width", "480", "--height", "3.5in", "--dpi", "96",
    ]);
    assert_eq!(png_size(&run.join("plot_energy.png")), (480, 336));
}

#[test]
fn plot_draws_a_time_window() {
    let run = run_dir("figures-window", &[]);
    let dir = run.to_str().unwrap();
    run_ok(&["plot", dir, "--from", "2", "--to", "4"]);
    let svg = read(&run.join("plot_motion.svg"));
    // The x tick labels of the time panels lie in [2, 4].
    let elements = parse_svg(&svg);
    let ticks: Vec<f64> = elements
        .iter()
        .filter(|e| e.tag == "text")
        .filter_map(|e| e.text.trim().parse::<f64>().ok())
        .collect();
    assert!(ticks
        .iter()
        .any(|&t| (t - 2.0).abs() < 1e-9 || (t - 4.0).abs() < 1e-9));
    assert!(
        !ticks.iter().any(|&t| t == 10.0 || t == 15.0),
        "ticks beyond the window: {ticks:?}"
    );
}

#[test]
fn plot_refuses_bad_windows_and_sizes_naming_the_flag() {
    let run = run_dir("figures-refuse", &[]);
    let dir = run.to_str().unwrap();
    let before = common::file_names(&run);
    for (args, flag, value) in [
        (vec!["--from", "4", "--to", "2"], "--from", "4"),
        (vec!["--from", "3", "--to", "3"], "--from", "3"),
        (vec!["--from", "-1"], "--from", "-1"),
        (vec!["--to", "nan"], "--to", "NaN"),
        (vec!["--to", "inf"], "--to", "inf"),
        (vec!["--width", "10"], "--width", "2.646 mm"),
        (vec!["--width", "30mm"], "--width", "30 mm"),
        (vec!["--height", "100000"], "--height", "must be from 20 mm"),
        (vec!["--height", "25mm"], "--height", "25 mm"),
        (vec!["--dpi", "10"], "--dpi", "10"),
        (vec!["--from", "1000"], "--from", "1000"),
    ] {
        let mut all = vec!["plot", dir];
        all.extend_from_slice(&args);
        let o = flexrock(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        let e = stderr_of(&o);
        assert!(e.contains(flag) && e.contains(value), "{args:?}: {e}");
        assert_eq!(common::file_names(&run), before, "{args:?} wrote files");
    }
    let o = flexrock(&["plot", dir, "--format", "gif"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr_of(&o).contains("--format"));
    for bad in ["85 furlongs", "mm"] {
        let o = flexrock(&["plot", dir, "--width", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(
            stderr_of(&o).contains("--width"),
            "{bad}: {}",
            stderr_of(&o)
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Every command's figures: formats, sizes on paper, refusals, and text that fits at 85 mm.

/// Each command that draws figures, as (its arguments before --out, the stems of its figures).
/// The FEM's runs are shortened to keep the test quick.
fn drawing_commands() -> Vec<(Vec<String>, Vec<&'static str>)> {
    let model = reference_model().to_str().unwrap().to_string();
    let row = repo("models/row-pair.toml").to_str().unwrap().to_string();
    let args = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        (
            args(&["compare", &model, "--duration", "2"]),
            vec!["compare", "compare_relations"],
        ),
        (
            args(&[
                "converge",
                &model,
                "--duration",
                "2",
                "--dt",
                "0.02,0.01",
                "--rtol",
                "1e-4,1e-6",
            ]),
            vec!["convergence_dt", "convergence_work"],
        ),
        (
            args(&[
                "fem",
                &model,
                "--compare",
                "--set",
                "simulation.duration=1.5",
            ]),
            vec![
                "fem_deformed_shapes",
                "fem_components",
                "fem_q_vs_r",
                "fem_s_vs_r",
                "fem_top_velocity",
                "fem_angular_momentum",
                "compare_q",
                "compare_flexural",
                "compare_top_velocity",
                "compare_q_vs_r",
                "compare_s_vs_r",
            ],
        ),
        (args(&["fem", &model, "--pushover"]), vec!["pushover"]),
        (
            args(&["run", &row, "--plot", "--duration", "2"]),
            vec!["row_motion", "row_shapes"],
        ),
    ]
}

/// Every text of an SVG that is not turned (the y labels are) lies within the figure's width,
/// measured with the font the figures are drawn in: no title or label is cut at the edge.
fn assert_texts_fit(svg: &str, what: &str) {
    let elements = parse_svg(svg);
    let root = elements.iter().find(|e| e.tag == "svg").expect("an svg");
    let width: f64 = root
        .attr("viewBox")
        .unwrap()
        .split(' ')
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    for e in elements
        .iter()
        .filter(|e| e.tag == "text" && !e.text.is_empty())
    {
        if e.attr("transform").is_some() {
            continue;
        }
        let size_pt = e.number("font-size") * 72.0 / flexrock::figures::page::DOTS_PER_INCH;
        let w = flexrock::figures::plot::text_width(&e.text, size_pt);
        let x = e.number("x");
        let left = match e.attr("text-anchor") {
            Some("middle") => x - w / 2.0,
            Some("end") => x - w,
            _ => x,
        };
        assert!(
            left >= -1.0 && left + w <= width + 1.0,
            "{what}: {:?} spans {left:.0} to {:.0} of a figure {width} wide",
            e.text,
            left + w
        );
    }
}

#[test]
fn every_command_draws_its_figures_in_each_format_at_each_width() {
    for (args, stems) in drawing_commands() {
        for width in ["85mm", "180mm"] {
            let out = scratch_dir(&format!("every-format-{}-{width}", args[0])).join("out");
            let mut all: Vec<&str> = args.iter().map(String::as_str).collect();
            all.extend(["--out", out.to_str().unwrap(), "--format", "svg,pdf,png"]);
            all.extend(["--width", width]);
            let o = flexrock(&all);
            assert!(o.status.success(), "{all:?}: {}", stderr_of(&o));
            for stem in &stems {
                let svg = read(&out.join(format!("{stem}.svg")));
                assert!(
                    svg.starts_with(&format!("<svg width=\"{width}\"")),
                    "{stem}: {}",
                    &svg[..80]
                );
                if width == "85mm" {
                    assert_texts_fit(&svg, stem);
                }
                let pdf = std::fs::read(out.join(format!("{stem}.pdf"))).unwrap();
                assert!(pdf.starts_with(b"%PDF-"), "{stem}");
                let png = out.join(format!("{stem}.png"));
                assert_eq!(
                    std::fs::read(&png).unwrap()[..8],
                    [0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A],
                    "{stem}"
                );
                // 85 mm at 300 dpi: 1004 pixels; 180 mm: 2126.
                let pixels = if width == "85mm" { 1004 } else { 2126 };
                assert_eq!(png_size(&png).0, pixels, "{stem}");
            }
        }
    }
}

#[test]
fn every_command_refuses_a_bad_size_or_format_and_writes_nothing() {
    for (args, _) in drawing_commands() {
        for (bad, flag) in [
            (vec!["--width", "30mm"], "--width"),
            (vec!["--height", "600mm"], "--height"),
            (vec!["--format", "gif"], "--format"),
            (vec!["--width", "85 furlongs"], "--width"),
        ] {
            let out = scratch_dir(&format!("refuse-format-{}", args[0])).join("out");
            let mut all: Vec<&str> = args.iter().map(String::as_str).collect();
            all.extend(["--out", out.to_str().unwrap()]);
            all.extend(&bad);
            let o = flexrock(&all);
            assert_eq!(o.status.code(), Some(2), "{all:?}: {}", stderr_of(&o));
            assert!(stderr_of(&o).contains(flag), "{all:?}: {}", stderr_of(&o));
            assert!(!out.exists(), "{all:?} wrote {}", out.display());
        }
    }
    // A figure flag where nothing is drawn is refused, not ignored.
    let model = reference_model();
    let out = scratch_dir("refuse-format-unplotted").join("out");
    for args in [
        vec!["run", model.to_str().unwrap(), "--format", "pdf"],
        vec!["fem", model.to_str().unwrap(), "--modes", "--width", "85mm"],
    ] {
        let mut all = args.clone();
        all.extend(["--out", out.to_str().unwrap()]);
        let o = flexrock(&all);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {}", stderr_of(&o));
        let flag = args[2];
        assert!(stderr_of(&o).contains(flag), "{all:?}: {}", stderr_of(&o));
        assert!(!out.exists());
    }
}
