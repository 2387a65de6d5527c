//! Figures: plotters draws axes, log ticks, labels and legends with an embedded font (identical
//! output on every machine); the map raster is coloured here and placed as one bitmap. Every
//! figure is drawn once, as SVG; its PNG is that SVG rasterised by resvg with anti-aliasing and
//! the same font ([`svg_to_png`]), so the two formats show the same figure.

pub mod atlas;
pub mod map;
pub mod plots;
pub mod rough;

use crate::error::Message;
use std::path::Path;
use std::sync::Once;

/// Registers the embedded DejaVu Sans as "sans-serif" (no system fonts are used).
pub fn fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
        let _ =
            plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, bytes);
    });
}

/// Tick labels for log axes: 0.01 .. 1000 as plain numbers, beyond as powers of ten (markup for
/// a superscript), with a true minus sign.
pub fn log_label(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return String::new();
    }
    let e = v.log10();
    if (e - e.round()).abs() > 1e-6 {
        return String::new();
    }
    let e = e.round() as i32;
    if (-2..=3).contains(&e) {
        // From the exponent: 10^-2 is not exactly 0.01 in binary.
        format!("{}", 10f64.powi(e))
    } else {
        format!("10^{{{}}}", minus(&e.to_string()))
    }
}

/// Replaces hyphen-minus by the minus sign U+2212, as typeset mathematics has it.
pub fn minus(s: &str) -> String {
    s.replace('-', "\u{2212}")
}

/// A colorbar tick on a log10 scale: 10^e in markup, e to one decimal, with a true minus sign
/// (+ 0.0: no "10^-0" from a negative zero).
pub fn power_label(log10_value: f64) -> String {
    let e = crate::physics::domain::short((log10_value * 10.0).round() / 10.0 + 0.0);
    format!("10^{{{}}}", minus(&e))
}

/// Tick labels for linear axes: the value without binary noise (-3.4, not -3.4000000000000004),
/// as a power of ten where it is very large or small, with a true minus sign.
pub fn linear_label(v: f64) -> String {
    // Within rounding of zero (a tick at -1e-17): 0, not -0.0.
    if v.abs() < 1e-12 * 1f64.max(v.abs()) || !v.is_finite() {
        return "0".into();
    }
    let trim = |s: String| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').into()
        } else {
            s
        }
    };
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        let e = v.abs().log10().floor() as i32;
        let m = trim(format!("{:.4}", v / 10f64.powi(e)));
        let p = format!("10^{{{}}}", minus(&e.to_string()));
        if m == "1" || m == "-1" {
            minus(&format!("{}{p}", if m == "-1" { "-" } else { "" }))
        } else {
            minus(&format!("{m}\u{00d7}{p}"))
        }
    } else {
        minus(&trim(format!("{v:.6}")))
    }
}

/// SI prefix for values up to `max_abs`: (the factor to divide by, the prefix).
pub fn si_prefix(max_abs: f64) -> (f64, &'static str) {
    const P: [(i32, &str); 9] = [
        (-15, "f"),
        (-12, "p"),
        (-9, "n"),
        (-6, "\u{00b5}"),
        (-3, "m"),
        (0, ""),
        (3, "k"),
        (6, "M"),
        (9, "G"),
    ];
    let e = if max_abs > 0.0 && max_abs.is_finite() {
        (max_abs.log10() + 1e-9).floor() as i32
    } else {
        0
    };
    let k = (e.div_euclid(3) * 3).clamp(-15, 9);
    let (_, name) = P.iter().find(|p| p.0 == k).copied().unwrap_or((0, ""));
    (10f64.powi(k), name)
}

/// Drawing units per millimetre of the printed figure: every figure is laid out in these units
/// (plotters draws on an integer grid: at 1/16 mm a curve's vertices are placed within a
/// quarter of a pixel at 300 dpi, so thick curves do not wobble). Line widths, markers and
/// gaps below are in these units.
pub const UNITS_PER_MM: f64 = 16.0;
/// A single journal column (mm): the default width of every paper figure.
pub const SINGLE_COLUMN_MM: f64 = 85.0;
/// A figure across both columns (mm).
pub const DOUBLE_COLUMN_MM: f64 = 175.0;
/// PNG resolution unless asked otherwise (dots per inch at print size).
pub const DEFAULT_DPI: f64 = 300.0;
/// The widest PNG side we write (pixels): keeps memory bounded (about 1.2 GB of RGBA at most).
pub const MAX_PNG_SIDE: u32 = 16_000;

/// The font size to give plotters for `points` at print size (its SVG writes size / 1.24).
pub const fn pt(points: f64) -> f64 {
    points * 25.4 / 72.0 * UNITS_PER_MM * 1.24
}
/// Figure titles.
pub const TITLE: f64 = pt(9.5);
/// Axis descriptions.
pub const AXIS: f64 = pt(8.5);
/// Tick labels.
pub const TICK: f64 = pt(7.5);
/// Legends, notes and in-plot labels.
pub const NOTE: f64 = pt(7.0);
/// Region names on the adhesion map.
pub const REGION: f64 = pt(9.5);
/// Length of a legend's line sample, and the room it gets before its label (units).
pub const SAMPLE: i32 = 72;

/// A figure's printed size: its width and the resolution of its PNG.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Print {
    /// The printed width (mm).
    pub width_mm: f64,
    /// The PNG's resolution (dots per inch).
    pub dpi: f64,
}

impl Default for Print {
    fn default() -> Print {
        Print::single_column()
    }
}

impl Print {
    /// One journal column ([`SINGLE_COLUMN_MM`]) at [`DEFAULT_DPI`].
    pub fn single_column() -> Print {
        Print {
            width_mm: SINGLE_COLUMN_MM,
            dpi: DEFAULT_DPI,
        }
    }
    /// Two journal columns ([`DOUBLE_COLUMN_MM`]) at [`DEFAULT_DPI`].
    pub fn double_column() -> Print {
        Print {
            width_mm: DOUBLE_COLUMN_MM,
            dpi: DEFAULT_DPI,
        }
    }
    /// A checked size: 40..600 mm wide, 50..2400 dpi, and a PNG of at most [`MAX_PNG_SIDE`].
    pub fn new(width_mm: f64, dpi: f64) -> Result<Print, Message> {
        let short = crate::physics::domain::short;
        if !(40.0..=600.0).contains(&width_mm) {
            return Err(Message::new().key("width_mm").text(format!(" {} is outside 40..600: give the printed width in millimetres (85 for one column, 175 for two)", short(width_mm))));
        }
        if !(50.0..=2400.0).contains(&dpi) {
            return Err(Message::new().key("dpi").text(format!(" {} is outside 50..2400: give the PNG resolution in dots per inch (300 is usual for print)", short(dpi))));
        }
        let p = Print { width_mm, dpi };
        if p.png_width() > MAX_PNG_SIDE {
            return Err(Message::new()
                .key("width_mm")
                .text(format!(" {} at ", short(width_mm)))
                .key("dpi")
                .text(format!(
                    " {} makes a PNG {} pixels wide, more than {MAX_PNG_SIDE}: lower one of them",
                    short(dpi),
                    p.png_width()
                )));
        }
        Ok(p)
    }
    /// Narrower than about one and a half columns: two-panel figures stack their panels.
    pub fn narrow(&self) -> bool {
        self.width_mm < 120.0
    }
    /// The PNG's width in pixels: 85 mm at 300 dpi is 1004.
    pub fn png_width(&self) -> u32 {
        (self.width_mm / 25.4 * self.dpi).round() as u32
    }
    /// The drawing canvas in units for a figure of height/width `aspect`.
    pub fn canvas(&self, aspect: f64) -> (u32, u32) {
        let w = (self.width_mm * UNITS_PER_MM).round();
        (w as u32, (w * aspect).round() as u32)
    }
}

/// The figures tabor draws, each with its shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The adhesion map's regions.
    Map,
    /// One quantity over the adhesion map's plane ([`map::Quantity`]).
    QuantityMap,
    /// Pull-off forces against lambda.
    Pulloff,
    /// Load-approach curves.
    Curves,
    /// Speed against accuracy of the solver variants.
    Bench,
    /// One error map of the failure atlas ([`atlas`]).
    Atlas,
    /// A real contact and its place on the map (two panels).
    Scene,
    /// An approach-retract cycle (two panels).
    Cycle,
    /// Pressure and gap profiles (two panels).
    Profile,
    /// A fitted force curve and its models.
    Fit,
    /// One quantity over a force map's pixels.
    ForceMap,
    /// A force map's quantities as histograms, with its models and statuses (six panels).
    MapHistograms,
}

impl Kind {
    /// Height over width. Two-panel figures stack their panels when narrow, so they are taller.
    pub fn aspect(self, p: &Print) -> f64 {
        let n = p.narrow();
        match self {
            Kind::Map | Kind::QuantityMap => {
                if n {
                    0.98
                } else {
                    0.72
                }
            }
            Kind::Pulloff | Kind::Curves => {
                if n {
                    0.82
                } else {
                    0.62
                }
            }
            Kind::Bench | Kind::Atlas => {
                if n {
                    0.9
                } else {
                    0.72
                }
            }
            Kind::Scene | Kind::Cycle => {
                if n {
                    1.45
                } else {
                    0.5
                }
            }
            Kind::Profile => {
                if n {
                    1.25
                } else {
                    0.8
                }
            }
            Kind::Fit => {
                if n {
                    1.1
                } else {
                    0.7
                }
            }
            Kind::ForceMap => 0.85,
            Kind::MapHistograms => {
                if n {
                    1.35
                } else {
                    0.62
                }
            }
        }
    }
}

/// Which files a figure goes to.
#[derive(Clone, Debug, Default)]
pub struct Outputs {
    /// The PNG file, if asked for.
    pub png: Option<std::path::PathBuf>,
    /// The SVG file, if asked for.
    pub svg: Option<std::path::PathBuf>,
    /// The PDF file, if asked for.
    pub pdf: Option<std::path::PathBuf>,
}

/// A figure file that cannot be one of a figure's outputs: the path, and why.
#[derive(Clone, Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FigureFileError {
    /// Its extension is none of .png, .svg and .pdf.
    #[error("{}: a figure is written as .png, .svg or .pdf; name the file with one of those extensions", .0.display())]
    Extension(std::path::PathBuf),
    /// A second file of one format (its extension).
    #[error("{}: a second {} output for one figure; give each format once", .0.display(), .1)]
    Twice(std::path::PathBuf, String),
}

impl Outputs {
    /// A figure file whose format is its extension (.png, .svg or .pdf).
    pub fn from_path(path: &Path) -> Result<Outputs, FigureFileError> {
        let mut o = Outputs::default();
        o.add(path)?;
        Ok(o)
    }
    /// Adds a file, its format chosen by its extension.
    pub fn add(&mut self, path: &Path) -> Result<(), FigureFileError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let slot = match ext.as_deref() {
            Some("png") => &mut self.png,
            Some("svg") => &mut self.svg,
            Some("pdf") => &mut self.pdf,
            _ => return Err(FigureFileError::Extension(path.to_path_buf())),
        };
        if slot.is_some() {
            return Err(FigureFileError::Twice(
                path.to_path_buf(),
                ext.unwrap_or_default(),
            ));
        }
        *slot = Some(path.to_path_buf());
        Ok(())
    }
    /// Whether no file is asked for.
    pub fn is_empty(&self) -> bool {
        self.png.is_none() && self.svg.is_none() && self.pdf.is_none()
    }
    pub(crate) fn formats(&self) -> Formats {
        Formats {
            png: self.png.is_some(),
            svg: self.svg.is_some(),
            pdf: self.pdf.is_some(),
        }
    }
}

/// Which encodings to produce.
#[derive(Clone, Copy, Debug, Default)]
pub struct Formats {
    /// A PNG.
    pub png: bool,
    /// An SVG.
    pub svg: bool,
    /// A PDF.
    pub pdf: bool,
}

/// A figure in the formats asked for.
#[derive(Default)]
pub struct Rendered {
    /// The PNG's bytes.
    pub png: Option<Vec<u8>>,
    /// The SVG's text.
    pub svg: Option<String>,
    /// The PDF's bytes.
    pub pdf: Option<Vec<u8>>,
}

impl Rendered {
    /// Writes each format to its file (each atomically).
    pub fn save(&self, out: &Outputs) -> anyhow::Result<()> {
        let parts: [(&Option<std::path::PathBuf>, Option<&[u8]>); 3] = [
            (&out.png, self.png.as_deref()),
            (&out.svg, self.svg.as_ref().map(|s| s.as_bytes())),
            (&out.pdf, self.pdf.as_deref()),
        ];
        for (path, bytes) in parts {
            if let (Some(p), Some(b)) = (path, bytes) {
                crate::io::write_output(p, b)?;
            }
        }
        Ok(())
    }
}

/// The drawing code of a figure, on the SVG backend.
pub type DrawSvg<'a> = &'a dyn for<'b> Fn(
    &plotters::prelude::DrawingArea<plotters::prelude::SVGBackend<'b>, plotters::coord::Shift>,
) -> Result<(), Err>;

type Err = Box<dyn std::error::Error + Send + Sync>;

/// The house style of a chart's mesh: one faint light line between the bold ones, the axis
/// titles and tick labels in the figure's sizes. Callers add their label formatters and draw.
pub(crate) fn house_mesh<
    'a,
    'b,
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
    DB: plotters::prelude::DrawingBackend,
>(
    mut mesh: plotters::chart::MeshStyle<'a, 'b, X, Y, DB>,
    x_desc: impl Into<String>,
    y_desc: impl Into<String>,
) -> plotters::chart::MeshStyle<'a, 'b, X, Y, DB> {
    mesh.max_light_lines(1)
        .light_line_style(plotters::style::RGBColor(245, 245, 245))
        .bold_line_style(plotters::style::RGBColor(215, 215, 215));
    house_labels(mesh, x_desc, y_desc)
}

/// The house style of a chart without a grid (maps: the pixels are the data).
pub(crate) fn house_axes<
    'a,
    'b,
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
    DB: plotters::prelude::DrawingBackend,
>(
    mut mesh: plotters::chart::MeshStyle<'a, 'b, X, Y, DB>,
    x_desc: impl Into<String>,
    y_desc: impl Into<String>,
) -> plotters::chart::MeshStyle<'a, 'b, X, Y, DB> {
    mesh.disable_mesh();
    house_labels(mesh, x_desc, y_desc)
}

/// The axis titles and tick labels in the figure's sizes.
fn house_labels<
    'a,
    'b,
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
    DB: plotters::prelude::DrawingBackend,
>(
    mut mesh: plotters::chart::MeshStyle<'a, 'b, X, Y, DB>,
    x_desc: impl Into<String>,
    y_desc: impl Into<String>,
) -> plotters::chart::MeshStyle<'a, 'b, X, Y, DB> {
    mesh.x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK));
    mesh
}

/// Draws a figure once, as SVG at its print size, and converts that SVG to the formats asked
/// for: PNG rasterised by resvg with anti-aliasing, PDF by svg2pdf, both from the same parsed
/// SVG with the same embedded font. The one drawing path of every figure.
pub fn draw_figure(
    kind: Kind,
    print: &Print,
    want: Formats,
    draw: DrawSvg,
) -> Result<Rendered, Err> {
    use plotters::prelude::*;
    fonts();
    let (w, h) = print.canvas(kind.aspect(print));
    let mut s = String::new();
    {
        let root = SVGBackend::with_string(&mut s, (w, h)).into_drawing_area();
        draw(&root)?;
        root.present()?;
    }
    let s = finish_svg(&s, print, (w, h));
    let mut out = Rendered::default();
    if want.png || want.pdf {
        let tree = parse_svg(&s)?;
        if want.png {
            out.png = Some(svg_tree_to_png(&tree, print.png_width())?);
        }
        if want.pdf {
            let page = svg2pdf::PageOptions { dpi: 96.0 };
            let pdf = svg2pdf::to_pdf(&tree, svg2pdf::ConversionOptions::default(), page)
                .map_err(|e| format!("PDF conversion: {e}"))?;
            out.pdf = Some(pdf);
        }
    }
    out.svg = want.svg.then_some(s);
    Ok(out)
}

/// Draws a figure and writes it to the files in `out`.
pub fn save(kind: Kind, print: &Print, out: &Outputs, draw: DrawSvg) -> anyhow::Result<()> {
    let r = draw_figure(kind, print, out.formats(), draw).map_err(anyhow::Error::from_boxed)?;
    r.save(out)
}

/// Gives plotters' SVG its printed size (the drawing units stay as the viewBox) and turns the
/// label markup into SVG text features: `_{x}` subscript, `^{x}` superscript, `\bar{x}` overline.
fn finish_svg(s: &str, print: &Print, (w, h): (u32, u32)) -> String {
    let mm = |u: u32| {
        format!(
            "{}mm",
            crate::physics::domain::short(u as f64 / UNITS_PER_MM)
        )
    };
    let head = format!("<svg width=\"{w}\" height=\"{h}\" ");
    let sized = format!("<svg width=\"{}\" height=\"{}\" ", mm(w), mm(h));
    let _ = print;
    let s = s.replacen(&head, &sized, 1);
    let mut out = String::with_capacity(s.len() + 256);
    let mut rest = s.as_str();
    while let Some(i) = rest.find("<text") {
        let Some(open) = rest[i..].find('>').map(|j| i + j + 1) else {
            break;
        };
        let Some(close) = rest[open..].find("</text>").map(|j| open + j) else {
            break;
        };
        out.push_str(&rest[..open]);
        out.push_str(&markup(&rest[open..close]));
        rest = &rest[close..];
    }
    out.push_str(rest);
    out
}

/// Label markup to SVG tspans (the text is already XML-escaped by plotters).
pub fn markup(t: &str) -> String {
    const TAGS: [(&str, &str); 3] = [
        ("_{", "<tspan baseline-shift=\"-22%\" font-size=\"72%\">"),
        ("^{", "<tspan baseline-shift=\"38%\" font-size=\"72%\">"),
        ("\\bar{", "<tspan text-decoration=\"overline\">"),
    ];
    let mut out = String::with_capacity(t.len() + 64);
    let mut rest = t;
    'outer: while !rest.is_empty() {
        for (m, tag) in TAGS {
            if let Some(body) = rest.strip_prefix(m) {
                if let Some(end) = body.find('}') {
                    out.push_str(tag);
                    out.push_str(&body[..end]);
                    out.push_str("</tspan>");
                    rest = &body[end + 1..];
                    continue 'outer;
                }
            }
        }
        let c = rest.chars().next().unwrap_or(' ');
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    out
}

/// The label as a reader sees it, without markup (for estimating its width).
pub fn plain(t: &str) -> String {
    t.replace("_{", "")
        .replace("^{", "")
        .replace("\\bar{", "")
        .replace('}', "")
}

fn parse_svg(svg: &str) -> Result<resvg::usvg::Tree, Err> {
    use resvg::usvg;
    use std::sync::{Arc, OnceLock};
    static FONTS: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    let fontdb = FONTS
        .get_or_init(|| {
            let mut db = usvg::fontdb::Database::new();
            db.load_font_data(include_bytes!("../../assets/fonts/DejaVuSans.ttf").to_vec());
            db.set_sans_serif_family("DejaVu Sans");
            Arc::new(db)
        })
        .clone();
    let opt = usvg::Options {
        fontdb,
        font_family: "DejaVu Sans".into(),
        ..Default::default()
    };
    Ok(usvg::Tree::from_str(svg, &opt)?)
}

/// Rasterises an SVG into an anti-aliased PNG `width` pixels wide, with the embedded font (no
/// system fonts: the same bytes on every machine).
pub fn svg_to_png(svg: &str, width: u32) -> Result<Vec<u8>, Err> {
    svg_tree_to_png(&parse_svg(svg)?, width)
}

fn svg_tree_to_png(tree: &resvg::usvg::Tree, width: u32) -> Result<Vec<u8>, Err> {
    use resvg::tiny_skia;
    let size = tree.size();
    let scale = width as f32 / size.width();
    let height = (size.height() * scale).round() as u32;
    let mut pixmap = tiny_skia::Pixmap::new(width, height).ok_or("empty figure")?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    // Opaque RGB (the background is white).
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    Ok(png_bytes(&rgb, width, height)?)
}

/// Encodes an RGB buffer as PNG (deterministic: same pixels, same bytes).
pub fn png_bytes(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, image::ImageError> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out).write_image(
        rgb,
        w,
        h,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(out)
}

/// The viridis colour at `t` in 0..1 (clamped): dark purple to yellow.
pub fn viridis(t: f64) -> plotters::style::RGBColor {
    let c = colorous::VIRIDIS.eval_continuous(t.clamp(0.0, 1.0));
    plotters::style::RGBColor(c.r, c.g, c.b)
}

/// A vertical viridis colorbar for values lo..hi in `area`, labelled by `fmt`.
pub fn colorbar<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    lo: f64,
    hi: f64,
    ticks: &[(f64, String)],
) -> Result<(), Box<dyn std::error::Error + Send + Sync>>
where
    DB::ErrorType: 'static,
{
    use plotters::prelude::*;
    // Aligned with the plot beside it: its title row above, its tick labels below.
    let mut chart = ChartBuilder::on(area)
        .margin_top((TITLE * 1.3) as i32 + 32)
        .margin_bottom((AXIS + TICK) as i32 + 48)
        .margin_left(8)
        .margin_right(16)
        // Labels right of the bar, as colorbars have them.
        .y_label_area_size(0)
        .right_y_label_area_size((TICK * 2.6) as i32)
        .build_cartesian_2d(0.0..1.0, lo..hi)?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (w, h) = ((px.end - px.start) as u32, (py.end - py.start) as u32);
    let mut buf = vec![0u8; (w * h * 3) as usize];
    for r in 0..h {
        let c = viridis(1.0 - (r as f64 + 0.5) / h as f64);
        for x in 0..w {
            let k = ((r * w + x) * 3) as usize;
            buf[k..k + 3].copy_from_slice(&[c.0, c.1, c.2]);
        }
    }
    if let Some(el) = BitMapElement::with_owned_buffer((0.0, hi), (w, h), buf) {
        chart.draw_series(std::iter::once(el))?;
    }
    // Ticks drawn here so that each label sits at its value.
    let frame = chart.plotting_area().strip_coord_spec();
    let (fw, fh) = frame.dim_in_pixel();
    frame.draw(&Rectangle::new(
        [(0, 0), (fw as i32 - 1, fh as i32 - 1)],
        BLACK.stroke_width(2),
    ))?;
    for (v, label) in ticks.iter().filter(|t| (lo..=hi).contains(&t.0)) {
        let (x, y) = chart.backend_coord(&(1.0, *v));
        let tick = [(x, y), (x + 12, y)];
        area.draw(&PathElement::new(
            tick.map(|(a, b)| (a - area.get_base_pixel().0, b - area.get_base_pixel().1))
                .to_vec(),
            BLACK.stroke_width(2),
        ))?;
        let style = ("sans-serif", TICK).into_font().color(&BLACK).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        let base = area.get_base_pixel();
        area.draw(&Text::new(
            label.clone(),
            (x + 20 - base.0, y - base.1),
            style,
        ))?;
    }
    Ok(())
}

/// Colour-bar ticks at round steps of the colour coordinate over lo..hi: 1, 2 or 5 times a
/// power of ten, at most seven.
pub fn round_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    let step = [1.0, 2.0, 5.0]
        .iter()
        .flat_map(|m| (-6..=6).map(move |e| m * 10f64.powi(e)))
        .filter(|s| span / s <= 6.0)
        .fold(f64::INFINITY, f64::min);
    let mut v = (lo / step).ceil() * step;
    let mut out = Vec::new();
    while v <= hi + 1e-9 * span {
        out.push(v);
        v += step;
    }
    out
}

/// The legend of a chart's labelled series, framed on a translucent white box.
pub fn legend<'a, DB: plotters::prelude::DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut plotters::prelude::ChartContext<'a, DB, CT>,
    position: plotters::prelude::SeriesLabelPosition,
    font_size: f64,
) -> Result<(), Box<dyn std::error::Error + Send + Sync>>
where
    DB::ErrorType: 'static,
{
    use plotters::prelude::*;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.6))
        .label_font(("sans-serif", font_size))
        .legend_area_size(SAMPLE + 20)
        .margin(16)
        .position(position)
        .draw()?;
    Ok(())
}

/// A legend's line sample in `style`, [`SAMPLE`] long, beside (not under) its label.
pub fn sample(
    style: plotters::style::ShapeStyle,
) -> impl Fn((i32, i32)) -> plotters::element::PathElement<(i32, i32)> {
    move |(x, y)| plotters::element::PathElement::new(vec![(x, y), (x + SAMPLE, y)], style)
}

/// A dashed legend sample, for a dashed series.
pub fn sample_dashed(
    style: plotters::style::ShapeStyle,
) -> impl Fn((i32, i32)) -> plotters::element::DashedPathElement<std::vec::IntoIter<(i32, i32)>, i32>
{
    move |(x, y)| {
        plotters::element::DashedPathElement::new(vec![(x, y), (x + SAMPLE, y)], 16, 10, style)
    }
}

/// One entry of a legend drawn in rows: a line sample (dashed or solid) and its label.
pub struct Entry {
    /// The label, which may hold the [`markup`] of subscripts, superscripts and bars.
    pub label: String,
    /// The line's colour and width.
    pub style: plotters::style::ShapeStyle,
    /// Whether the sample is dashed.
    pub dashed: bool,
}

/// The font size at most `size` at which `text` fits on one line across `area` (less its
/// margins): a long title is set smaller rather than cut off at both ends.
pub fn fitting_size<DB: plotters::prelude::DrawingBackend, CT: plotters::coord::CoordTranslate>(
    area: &plotters::prelude::DrawingArea<DB, CT>,
    text: &str,
    size: f64,
) -> f64 {
    let avail = area.dim_in_pixel().0 as f64 - 2.0 * map::MARGIN as f64;
    let w = text_width(area, text, size) as f64;
    if w > avail && w > 0.0 {
        (size * avail / w).max(size * 0.5)
    } else {
        size
    }
}

/// Width in units of a label (markup removed) at font `size`: plotters' estimate, which is a few
/// percent wider than the SVG text, so boxes built on it are safe.
pub fn text_width<DB: plotters::prelude::DrawingBackend, CT: plotters::coord::CoordTranslate>(
    area: &plotters::prelude::DrawingArea<DB, CT>,
    text: &str,
    size: f64,
) -> i32 {
    let style: plotters::style::TextStyle = ("sans-serif", size).into();
    area.estimate_text_size(&plain(text), &style)
        .map(|(w, _)| w as i32)
        .unwrap_or((plain(text).chars().count() as f64 * 0.6 * size) as i32)
}

/// Line height of text at font `size` (units).
pub fn line_height(size: f64) -> i32 {
    (size * 0.95).ceil() as i32
}

/// Splits `text` into lines no wider than `max_w` at font `size`.
pub fn wrap<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    text: &str,
    size: f64,
    max_w: i32,
) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        let next = if cur.is_empty() {
            word.to_string()
        } else {
            format!("{cur} {word}")
        };
        if !cur.is_empty() && text_width(area, &next, size) > max_w {
            lines.push(std::mem::replace(&mut cur, word.to_string()));
        } else {
            cur = next;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// Lays legend entries out in rows across `max_w`: the index ranges of each row.
pub fn legend_rows<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    entries: &[Entry],
    size: f64,
    max_w: i32,
) -> Vec<std::ops::Range<usize>> {
    let mut rows = Vec::new();
    let (mut start, mut x) = (0, 0);
    for (i, e) in entries.iter().enumerate() {
        let w = SAMPLE + 16 + text_width(area, &e.label, size) + 48;
        if x > 0 && x + w > max_w {
            rows.push(start..i);
            (start, x) = (i, 0);
        }
        x += w;
    }
    if start < entries.len() {
        rows.push(start..entries.len());
    }
    rows
}

/// Draws legend entries in rows from (x0, y0) across `max_w`; returns the height used.
pub fn draw_legend_rows<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    entries: &[Entry],
    size: f64,
    (x0, y0): (i32, i32),
    max_w: i32,
) -> Result<i32, Err>
where
    DB::ErrorType: 'static,
{
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    let lh = line_height(size) + 12;
    let rows = legend_rows(area, entries, size, max_w);
    for (r, range) in rows.iter().enumerate() {
        let y = y0 + r as i32 * lh + lh / 2;
        let mut x = x0;
        for e in &entries[range.clone()] {
            if e.dashed {
                area.draw(&plotters::element::DashedPathElement::new(
                    vec![(x, y), (x + SAMPLE, y)],
                    16,
                    10,
                    e.style,
                ))?;
            } else {
                area.draw(&PathElement::new(vec![(x, y), (x + SAMPLE, y)], e.style))?;
            }
            let style = ("sans-serif", size)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center));
            area.draw(&Text::new(e.label.clone(), (x + SAMPLE + 16, y), style))?;
            x += SAMPLE + 16 + text_width(area, &e.label, size) + 48;
        }
    }
    Ok(rows.len() as i32 * lh)
}

/// Height that [`draw_legend_rows`] will use.
pub fn legend_rows_height<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    entries: &[Entry],
    size: f64,
    max_w: i32,
) -> i32 {
    legend_rows(area, entries, size, max_w).len() as i32 * (line_height(size) + 12)
}

/// Pixel boxes (x0, y0, x1, y1) already taken on a figure, and a search for a free spot.
#[derive(Default)]
pub struct Placer {
    /// The boxes taken.
    pub boxes: Vec<(i32, i32, i32, i32)>,
    /// Polylines (pixel coordinates) that labels must not cross.
    pub lines: Vec<Vec<(i32, i32)>>,
}

impl Placer {
    fn crosses_line(&self, b: (i32, i32, i32, i32)) -> bool {
        self.crossings(b) > 0
    }
    /// How many lines box `b` crosses.
    pub fn crossings(&self, b: (i32, i32, i32, i32)) -> usize {
        let inside = |p: (f64, f64)| {
            p.0 >= b.0 as f64 && p.0 <= b.2 as f64 && p.1 >= b.1 as f64 && p.1 <= b.3 as f64
        };
        self.lines
            .iter()
            .filter(|l| {
                l.windows(2).any(|w| {
                    let (a, c) = (
                        (w[0].0 as f64, w[0].1 as f64),
                        (w[1].0 as f64, w[1].1 as f64),
                    );
                    let n = ((c.0 - a.0).abs().max((c.1 - a.1).abs()) / 6.0)
                        .ceil()
                        .max(1.0) as usize;
                    (0..=n).any(|k| {
                        let t = k as f64 / n as f64;
                        inside((a.0 + t * (c.0 - a.0), a.1 + t * (c.1 - a.1)))
                    })
                })
            })
            .count()
    }
    /// Whether box `b` is free: inside `frame`, over no box and no line.
    pub fn free(&self, b: (i32, i32, i32, i32), frame: (i32, i32, i32, i32)) -> bool {
        let overlaps = |o: &(i32, i32, i32, i32)| b.0 < o.2 && o.0 < b.2 && b.1 < o.3 && o.1 < b.3;
        b.0 >= frame.0
            && b.1 >= frame.1
            && b.2 <= frame.2
            && b.3 <= frame.3
            && !self.boxes.iter().any(overlaps)
            && !self.crosses_line(b)
    }
    /// The first free box among `candidates` (taking it), else None.
    pub fn take(
        &mut self,
        candidates: impl IntoIterator<Item = (i32, i32, i32, i32)>,
        frame: (i32, i32, i32, i32),
    ) -> Option<(i32, i32, i32, i32)> {
        let b = candidates.into_iter().find(|&b| self.free(b, frame))?;
        self.boxes.push(b);
        Some(b)
    }
    /// The box among `candidates` inside `frame` and over no box that crosses the fewest lines
    /// (the first of those), for a label that must be placed on a crowded figure.
    pub fn take_least_crossing(
        &mut self,
        candidates: impl IntoIterator<Item = (i32, i32, i32, i32)>,
        frame: (i32, i32, i32, i32),
    ) -> Option<(i32, i32, i32, i32)> {
        let none = Placer {
            boxes: self.boxes.clone(),
            lines: Vec::new(),
        };
        let b = candidates
            .into_iter()
            .filter(|&b| none.free(b, frame))
            .min_by_key(|&b| self.crossings(b))?;
        self.boxes.push(b);
        Some(b)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn linear_labels_have_no_binary_noise() {
        assert_eq!(super::linear_label(-3.4000000000000004), "\u{2212}3.4");
        assert_eq!(super::linear_label(2.0), "2");
        assert_eq!(super::linear_label(-1e12), "\u{2212}10^{12}");
        assert_eq!(super::linear_label(2.5e-5), "2.5\u{00d7}10^{\u{2212}5}");
        assert_eq!(super::log_label(1e-4), "10^{\u{2212}4}");
        assert_eq!(super::log_label(0.01), "0.01");
    }

    #[test]
    fn si_prefixes_keep_ticks_between_1_and_1000() {
        assert_eq!(super::si_prefix(2.5e-8), (1e-9, "n"));
        assert_eq!(super::si_prefix(1.5e-8).1, "n");
        assert_eq!(super::si_prefix(999e-9).1, "n");
        assert_eq!(super::si_prefix(1e-6).1, "\u{00b5}");
        assert_eq!(super::si_prefix(3.0).1, "");
    }

    #[test]
    fn markup_becomes_svg_text_features() {
        let m = super::markup("\\bar{P}_{c} 10^{3}");
        assert!(
            m.starts_with("<tspan text-decoration=\"overline\">P</tspan><tspan baseline-shift"),
            "{m}"
        );
        assert!(
            m.contains(">c</tspan> 10<tspan") && m.ends_with(">3</tspan>"),
            "{m}"
        );
        assert_eq!(super::plain("\\bar{P}_{c}"), "Pc");
    }
}
