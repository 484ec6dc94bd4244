//! A figure's size on paper and its file formats: lengths as journals give them (85mm, 3.5in),
//! and the SVG every figure is drawn as turned into a vector PDF (svg2pdf, the font embedded) or
//! a PNG (resvg) at a resolution in dots per inch. Knows nothing about what is drawn.

use std::sync::{Arc, OnceLock};

use crate::error::{Error, Result};

/// The drawing unit of every figure's SVG: a dot of a 300 dpi print, so that a PNG at 300 dpi
/// is the SVG at scale 1.
pub const DOTS_PER_INCH: f64 = 300.0;
/// Millimetres per inch.
const MM_PER_INCH: f64 = 25.4;
/// A single journal column, mm (85-90 mm in most journals).
pub const COLUMN_MM: f64 = 85.0;
/// Two journal columns (the text width), mm.
pub const PAGE_MM: f64 = 180.0;
/// The narrowest and widest figure drawn, mm: below 40 mm no panel has room for its tick
/// labels at a legible size, above 500 mm is no printed page.
pub const WIDTH_LIMITS_MM: (f64, f64) = (40.0, 500.0);
/// The resolutions a PNG may have, dots per inch.
pub const DPI_LIMITS: (f64, f64) = (50.0, 1200.0);

/// Dots (the SVG's unit) in `mm` millimetres.
pub fn dots(mm: f64) -> f64 {
    mm / MM_PER_INCH * DOTS_PER_INCH
}

/// Dots in `pt` typographic points (1/72 in).
pub fn pt(pt: f64) -> f64 {
    pt / 72.0 * DOTS_PER_INCH
}

/// Millimetres in `dots` dots.
pub fn mm(dots: f64) -> f64 {
    dots / DOTS_PER_INCH * MM_PER_INCH
}

/// A length on paper, held in millimetres. Read from `85mm`, `8.5cm`, `3.5in`, `250pt`, or a
/// bare number (or `600px`) in pixels of 1/96 in, as SVG and CSS count them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Length(pub f64);

impl Length {
    /// The length given by `text`, or a message saying what it must be.
    pub fn parse(text: &str) -> std::result::Result<Length, String> {
        let t = text.trim();
        let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
        let (number, unit) = t.split_at(split);
        let value: f64 = number.trim().parse().map_err(|_| {
            format!("a length must be a number with a unit, e.g. 85mm, 8.5cm, 3.5in, 250pt or 600px (got {text:?})")
        })?;
        let per_unit = match unit.trim() {
            "mm" => 1.0,
            "cm" => 10.0,
            "in" => MM_PER_INCH,
            "pt" => MM_PER_INCH / 72.0,
            "" | "px" => MM_PER_INCH / 96.0,
            other => {
                return Err(format!(
                "unknown unit {other:?}: use mm, cm, in, pt or px (a bare number is px, 1/96 in)"
            ))
            }
        };
        if !value.is_finite() || value <= 0.0 {
            return Err(format!("a length must be positive (got {text:?})"));
        }
        Ok(Length(value * per_unit))
    }

    /// The length in millimetres.
    pub fn mm(self) -> f64 {
        self.0
    }
}

impl std::fmt::Display for Length {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} mm",
            flexrock_core::base::format::significant(self.0, 4)
        )
    }
}

/// The image format of a figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// SVG text, sized in millimetres.
    Svg,
    /// PNG, 8-bit RGBA, at the page's resolution.
    Png,
    /// A one-page vector PDF with its font embedded.
    Pdf,
}

impl Format {
    /// The file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Png => "png",
            Format::Pdf => "pdf",
        }
    }
}

/// The size of a figure on paper and the resolution of its PNG.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Page {
    /// The width, mm.
    pub width: f64,
    /// The height, mm; None: as the figure's layout needs at this width.
    pub height: Option<f64>,
    /// A PNG's dots per inch.
    pub dpi: f64,
}

impl Page {
    /// A page `width` mm wide, its height as the figure needs, PNG at 300 dpi.
    pub fn width(width: f64) -> Page {
        Page {
            width,
            height: None,
            dpi: DOTS_PER_INCH,
        }
    }

    /// Two columns wide: the size a figure is drawn at unless asked otherwise.
    pub fn double() -> Page {
        Page::width(PAGE_MM)
    }
}

/// The size and resolution a user asks for: each absent one is the figure's own.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sizes {
    /// The width of every figure [default: [`PAGE_MM`]].
    pub width: Option<Length>,
    /// The height of every figure [default: as its layout needs at its width].
    pub height: Option<Length>,
    /// A PNG's dots per inch [default: 300].
    pub dpi: Option<f64>,
}

impl Sizes {
    /// Checks the sizes: a width within [`WIDTH_LIMITS_MM`], a height from 20 mm to the
    /// largest width, a resolution within [`DPI_LIMITS`]. The error names the flag, its value
    /// and the rule.
    pub fn check(&self) -> Result<()> {
        let bad = |flag: &str, value: String, rule: String| {
            Error::from(flexrock_core::Error::InvalidParameter {
                key: flag.to_string(),
                value,
                rule,
            })
        };
        let mm_text = |v: f64| format!("{} mm", flexrock_core::base::format::significant(v, 4));
        let (lo, hi) = WIDTH_LIMITS_MM;
        for (flag, length, low) in [("--width", self.width, lo), ("--height", self.height, 20.0)] {
            if let Some(l) = length {
                if !(low..=hi).contains(&l.mm()) {
                    return Err(bad(
                        flag,
                        mm_text(l.mm()),
                        format!("must be from {low} mm to {hi} mm"),
                    ));
                }
            }
        }
        if let Some(dpi) = self.dpi {
            if !(DPI_LIMITS.0..=DPI_LIMITS.1).contains(&dpi) {
                return Err(bad(
                    "--dpi",
                    dpi.to_string(),
                    format!("must be from {} to {}", DPI_LIMITS.0, DPI_LIMITS.1),
                ));
            }
        }
        Ok(())
    }

    /// The page these sizes give, `width_mm` wide where no width is asked.
    pub fn page(&self, width_mm: f64) -> Page {
        Page {
            width: self.width.map_or(width_mm, Length::mm),
            height: self.height.map(Length::mm),
            dpi: self.dpi.unwrap_or(DOTS_PER_INCH),
        }
    }
}

/// The formats and size a command draws its figures in.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureOptions {
    /// The formats, a file each.
    pub formats: Vec<Format>,
    /// The size on paper and a PNG's resolution.
    pub sizes: Sizes,
}

impl Default for FigureOptions {
    /// SVG at the figure's own size.
    fn default() -> Self {
        FigureOptions {
            formats: vec![Format::Svg],
            sizes: Sizes::default(),
        }
    }
}

impl FigureOptions {
    /// The options with `formats` instead.
    pub fn with_formats(mut self, formats: &[Format]) -> Self {
        self.formats = formats.to_vec();
        self
    }
}

/// The embedded font (DejaVu Sans, assets/fonts/LICENSE-DejaVu.txt): every figure's text is
/// measured with it, and PDF and PNG draw it (the PDF embeds the glyphs used), so no system
/// font is needed.
pub static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The SVG reader's options: the embedded font as the only font, and as every generic family.
fn svg_options() -> &'static resvg::usvg::Options<'static> {
    static OPTIONS: OnceLock<resvg::usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut db = resvg::usvg::fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        let family = "DejaVu Sans";
        db.set_sans_serif_family(family);
        db.set_serif_family(family);
        db.set_monospace_family(family);
        let mut options = resvg::usvg::Options {
            font_family: family.to_string(),
            ..Default::default()
        };
        options.fontdb = Arc::new(db);
        options
    })
}

/// `svg` (a figure as drawn, named `name` in messages) in `format`; a PNG at `dpi`.
pub fn convert(format: Format, name: &str, svg: &str, dpi: f64) -> Result<Vec<u8>> {
    let fail = |message: String| Error::Plot {
        name: name.to_string(),
        message,
    };
    if format == Format::Svg {
        return Ok(svg.as_bytes().to_vec());
    }
    let tree = resvg::usvg::Tree::from_str(svg, svg_options()).map_err(|e| fail(e.to_string()))?;
    match format {
        Format::Svg => unreachable!("returned above"),
        Format::Pdf => {
            // usvg reads lengths at 96 px per inch: a page of the SVG's size in millimetres.
            let page = svg2pdf::PageOptions { dpi: 96.0 };
            svg2pdf::to_pdf(&tree, svg2pdf::ConversionOptions::default(), page)
                .map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let scale = (dpi / 96.0) as f32;
            let size = tree.size();
            // To the nearest pixel (3.5 in at 96 dpi is 336, not 336.00000001 rounded up).
            let (w, h) = (
                (size.width() * scale).round().max(1.0) as u32,
                (size.height() * scale).round().max(1.0) as u32,
            );
            let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h)
                .ok_or_else(|| fail(format!("cannot make an image of {w} × {h} pixels")))?;
            pixmap.fill(resvg::tiny_skia::Color::WHITE);
            resvg::render(
                &tree,
                resvg::tiny_skia::Transform::from_scale(scale, scale),
                &mut pixmap.as_mut(),
            );
            pixmap.encode_png().map_err(|e| fail(e.to_string()))
        }
    }
}

/// Gives the SVG `svg` that plotters drew in whole dots its size on paper, `size` (width and
/// height, mm; the drawing's coordinates unchanged, so scaled by less than a dot's rounding),
/// and a description `desc` (what each panel shows).
pub fn on_paper(svg: String, (width_mm, height_mm): (f64, f64), desc: &str) -> String {
    let Some(end) = svg.find('>') else {
        return svg;
    };
    let head = &svg[..end];
    let number = |key: &str| -> Option<f64> {
        let at = head.find(&format!(" {key}=\""))? + key.len() + 3;
        head[at..].split('"').next()?.parse().ok()
    };
    let (Some(w), Some(h)) = (number("width"), number("height")) else {
        return svg;
    };
    // To a hundredth of a millimetre, in the fewest digits: 85mm, 137.58mm.
    let length = |v: f64| flexrock_core::base::format::shortest((v * 100.0).round() / 100.0);
    let mut out = format!(
        "<svg width=\"{}mm\" height=\"{}mm\" viewBox=\"0 0 {w} {h}\" xmlns=\"http://www.w3.org/2000/svg\">\n",
        length(width_mm),
        length(height_mm)
    );
    if !desc.is_empty() {
        out.push_str("<desc>");
        for c in desc.chars() {
            match c {
                '<' => out.push_str("&lt;"),
                '>' => out.push_str("&gt;"),
                '&' => out.push_str("&amp;"),
                c => out.push(c),
            }
        }
        out.push_str("</desc>\n");
    }
    out.push_str(svg[end + 1..].trim_start_matches('\n'));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_read_in_journal_units() {
        assert_eq!(Length::parse("85mm"), Ok(Length(85.0)));
        assert_eq!(Length::parse("8.5cm"), Ok(Length(85.0)));
        assert_eq!(Length::parse("2in"), Ok(Length(50.8)));
        assert_eq!(Length::parse("72pt"), Ok(Length(25.4)));
        assert_eq!(Length::parse("96"), Ok(Length(25.4)));
        assert_eq!(Length::parse("96px"), Ok(Length(25.4)));
        for bad in ["85 furlongs", "mm", "-3mm", "0in", "nan mm", ""] {
            assert!(Length::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn pages_convert_to_a_pdf_and_a_png_of_the_size_on_paper() {
        // 85 mm by 42.5 mm: 1004 by 502 dots.
        let (w, h) = (dots(85.0), dots(42.5));
        let svg = format!(
            "<svg width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" xmlns=\"http://www.w3.org/2000/svg\">\n\
             <text x=\"10\" y=\"100\" font-family=\"sans-serif\" font-size=\"40\">Aq</text></svg>"
        );
        let svg = on_paper(svg, (85.0, 42.5), "a test");
        assert!(
            svg.starts_with("<svg width=\"85mm\" height=\"42.5mm\""),
            "{svg}"
        );
        let png = convert(Format::Png, "t.png", &svg, 300.0).unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(png));
        let info = decoder.read_info().unwrap();
        let (pw, ph) = (info.info().width, info.info().height);
        assert!(
            (1004..=1005).contains(&pw) && (502..=503).contains(&ph),
            "{pw} × {ph}"
        );
        let pdf = convert(Format::Pdf, "t.pdf", &svg, 300.0).unwrap();
        let text = String::from_utf8_lossy(&pdf);
        assert!(text.starts_with("%PDF-"));
        // The page in points: 85 mm = 240.94 pt; the font is embedded.
        assert!(text.contains("MediaBox"), "no page size");
        assert!(text.contains("FontFile2"), "no embedded font");
    }
}
