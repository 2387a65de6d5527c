//! The adhesion map figure (PNG and SVG): regions or a continuous quantity, criteria lines,
//! pull-off, large-deformation lines, labels, legend and caption.

use super::log_label;
use crate::map::{criteria, LoadAxis, MapData, Region};
use crate::solver::Status;
use plotters::coord::Shift;
use plotters::prelude::*;
use rayon::prelude::*;

/// A continuous quantity drawn with a colorbar instead of the regions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Quantity {
    /// Contact radius A (log scale).
    A,
    /// Approach Dbar.
    Approach,
    /// c/a - 1 (log scale).
    M,
    /// |A_Hertz / A - 1| (log scale).
    ErrHertz,
    /// |A_DMT / A - 1| (log scale).
    ErrDmt,
    /// |A_JKR / A - 1| (log scale).
    ErrJkr,
}

impl Quantity {
    /// By its command-line name: a, approach, m, err-hertz, err-dmt, err-jkr.
    pub fn from_name(name: &str) -> Option<Quantity> {
        Some(match name {
            "a" => Quantity::A,
            "approach" => Quantity::Approach,
            "m" => Quantity::M,
            "err-hertz" => Quantity::ErrHertz,
            "err-dmt" => Quantity::ErrDmt,
            "err-jkr" => Quantity::ErrJkr,
            _ => return None,
        })
    }

    fn title(self) -> &'static str {
        match self {
            Quantity::A => "Contact radius A (exact MD)",
            Quantity::Approach => "Approach Δ (exact MD)",
            Quantity::M => "Cohesive zone c/a − 1 (exact MD)",
            Quantity::ErrHertz => "Error of Hertz |A_{Hertz}/A − 1|",
            Quantity::ErrDmt => "Error of DMT |A_{DMT}/A − 1|",
            Quantity::ErrJkr => "Error of JKR |A_{JKR}/A − 1|",
        }
    }
    fn log(self) -> bool {
        self != Quantity::Approach
    }
    /// The colour coordinate: log10 for positive quantities, asinh(v / 0.1) (a signed log that
    /// is linear within +-0.1) for the approach, which changes sign.
    fn transform(self, v: f64) -> f64 {
        if self.log() {
            v.log10()
        } else {
            (v / 0.1).asinh()
        }
    }
    /// The value at a solved point (NaN where undefined), before the log transform.
    fn value(self, d: &MapData, i: usize) -> f64 {
        let s = &d.drawn(i);
        if s.status != Status::Ok {
            return f64::NAN;
        }
        let c = || criteria(s.lambda, s.load, s.a, s.approach);
        match self {
            Quantity::A => s.a,
            Quantity::Approach => s.approach,
            Quantity::M => s.m_minus_1,
            Quantity::ErrHertz => c().err_hertz,
            Quantity::ErrDmt => c().err_dmt,
            Quantity::ErrJkr => c().err_jkr,
        }
    }
    fn is_error(self) -> bool {
        matches!(
            self,
            Quantity::ErrHertz | Quantity::ErrDmt | Quantity::ErrJkr
        )
    }
}

/// The fill of a region of the adhesion map (Okabe-Ito, lightened).
pub fn region_color(r: Region) -> RGBColor {
    // Okabe-Ito, lightened so that lines and labels stay legible on top.
    match r {
        Region::NoContact => RGBColor(255, 255, 255),
        Region::Hertz => RGBColor(205, 205, 205),
        Region::Rigid => RGBColor(247, 240, 150),
        Region::Dmt => RGBColor(160, 210, 240),
        Region::Jkr => RGBColor(242, 200, 120),
        Region::Md => RGBColor(128, 206, 180),
        Region::Failed => RGBColor(255, 0, 255),
    }
}

fn line_color(k: usize) -> RGBColor {
    [
        RGBColor(90, 90, 90),
        RGBColor(160, 140, 0),
        RGBColor(0, 114, 178),
        RGBColor(213, 94, 0),
    ][k]
}

type Err = Box<dyn std::error::Error + Send + Sync>;

/// Draws the map (regions, or `q` with a colorbar) at its print size, in the formats asked for.
pub fn render(
    d: &MapData,
    q: Option<Quantity>,
    print: &Print,
    want: Formats,
) -> Result<Rendered, Err> {
    super::draw_figure(kind(q), print, want, &|root| draw(root, d, q))
}

/// Draws the map and writes it to the files in `out`.
pub fn save(d: &MapData, q: Option<Quantity>, print: &Print, out: &Outputs) -> anyhow::Result<()> {
    super::save(kind(q), print, out, &|root| draw(root, d, q))
}

fn kind(q: Option<Quantity>) -> Kind {
    if q.is_some() {
        Kind::QuantityMap
    } else {
        Kind::Map
    }
}

/// The y-axis description (markup: an overbar on the normalised load).
fn y_desc(axis: LoadAxis, tip: bool) -> &'static str {
    match (axis, tip) {
        (LoadAxis::AbovePulloff, _) => "load above pull-off  \\bar{P} − \\bar{P}_{c}",
        (_, false) => "load  \\bar{P} = P/(πwR)",
        (_, true) => "load  \\bar{P} = P d/(πwl²)",
    }
}

/// The map's lines in chart coordinates, traced once: each criterion at the tolerance (Hertz,
/// Bradley, DMT, JKR) and the pull-off (the edge of the no-contact region).
struct Traced {
    criteria: [Vec<Vec<(f64, f64)>>; 4],
    pulloff: Vec<Vec<(f64, f64)>>,
}

const CRITERIA: [&str; 4] = ["Hertz", "Bradley (rigid)", "DMT", "JKR"];

/// Traces on a grid strided to about the plot's resolution: finer lines would not show.
fn trace(d: &MapData) -> Traced {
    let sp = &d.spec;
    let (nx, ny) = (sp.nx, sp.ny);
    let k = crate::map::trace_stride(nx, ny);
    let (mx, my) = ((nx - 1) / k + 1, (ny - 1) / k + 1);
    let fields: Vec<[f64; 5]> = (0..mx * my)
        .into_par_iter()
        .map(|j| {
            let i = (j / mx) * k * nx + (j % mx) * k;
            let s = &d.drawn(i);
            let contact = if d.regions[i] == Region::NoContact {
                0.0
            } else {
                1.0
            };
            if s.status != Status::Ok {
                return [1e9, 1e9, 1e9, 1e9, contact];
            }
            let c = criteria(s.lambda, s.load, s.a, s.approach);
            let f = |v: f64| if v.is_finite() { v } else { 1e9 };
            [
                f(c.err_hertz),
                f(c.rigid),
                f(c.err_dmt),
                f(c.err_jkr),
                contact,
            ]
        })
        .collect();
    let scaled = |path: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
        path.into_iter()
            .map(|(x, y)| to_chart(d, x * k as f64, y * k as f64))
            .collect()
    };
    let paths = |c: usize, level: f64| -> Vec<Vec<(f64, f64)>> {
        let field: Vec<f64> = fields.iter().map(|f| f[c]).collect();
        contour_paths(&field, mx, my, level)
            .into_iter()
            .map(scaled)
            .collect()
    };
    let contact: Vec<f64> = fields.iter().map(|f| f[4]).collect();
    let has_edge = contact.contains(&0.0) && contact.contains(&1.0);
    // The five lines are traced at once.
    let mut lines: Vec<Vec<Vec<(f64, f64)>>> = (0..5)
        .into_par_iter()
        .map(|c| match c {
            4 if !has_edge => Vec::new(),
            4 => paths(4, 0.5),
            _ => paths(c, sp.tolerance),
        })
        .collect();
    let pulloff = lines.pop().unwrap_or_default();
    let mut lines = lines.into_iter();
    Traced {
        criteria: [(); 4].map(|_| lines.next().unwrap_or_default()),
        pulloff,
    }
}

fn criterion_style(c: usize) -> ShapeStyle {
    ShapeStyle::from(&line_color(c)).stroke_width(6)
}

fn large_deformation_style() -> ShapeStyle {
    ShapeStyle::from(&BLACK).stroke_width(4)
}

/// The legend: only lines that are drawn (none where no point is in contact).
fn entries(d: &MapData, t: &Traced) -> Vec<Entry> {
    let mut e: Vec<Entry> = (0..4)
        .filter(|&c| !t.criteria[c].is_empty())
        .map(|c| Entry {
            label: format!("{} within {}%", CRITERIA[c], d.spec.tolerance * 100.0),
            style: criterion_style(c),
            dashed: false,
        })
        .collect();
    if !t.pulloff.is_empty() {
        e.push(Entry {
            label: "pull-off (load control)".into(),
            style: BLACK.stroke_width(6),
            dashed: false,
        });
    }
    if d.large_deformation.iter().any(|l| l.points.len() >= 2) {
        e.push(Entry {
            label: "a/R = 0.1 at σ_{0}/K".into(),
            style: large_deformation_style(),
            dashed: true,
        });
    }
    e
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &MapData,
    q: Option<Quantity>,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (w, h) = root.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    let sp = &d.spec;
    let traced = trace(d);
    let legend = entries(d, &traced);
    let pad = 32;
    let tol = format!("{}%", sp.tolerance * 100.0);
    let caption = match (q, d.tip) {
        (None, Some(shape)) => super::wrap(root, &format!("{}. Each point shows the simplest of the tip's closed forms whose contact radius A is within {tol} of the exact Maugis-Dugdale (MD) one: Sneddon's punch (Hertz, loads ≥ 0); rigid (πλ/2)·max(F(A), |Δ|) ≤ {tol}; DMT-type (the punch plus the rigid tip's Dugdale force); JKR-type (the punch's energy balance); else MD. λ and the load in the tip's units (docs/PHYSICS.md section 12). White: below the pull-off, no contact.", shape.describe()), NOTE, w - 2 * pad),
        (None, None) => super::wrap(root, &format!("Each point shows the simplest model whose contact radius A is within {tol} of the exact Maugis-Dugdale (MD) one: Hertz |A_{{H}}/A − 1| ≤ {tol} (loads ≥ 0); Bradley (rigid) (πλ/2)·max(A², |Δ|) ≤ {tol}; DMT |A_{{DMT}}/A − 1| ≤ {tol}; JKR |A_{{JKR}}/A − 1| ≤ {tol}; else MD. White: below the pull-off, no contact."), NOTE, w - 2 * pad),
        (Some(_), _) => Vec::new(),
    };
    let bottom = super::legend_rows_height(root, &legend, NOTE, w - 2 * pad)
        + caption.len() as i32 * super::line_height(NOTE)
        + 28;
    let (upper, lower) = root.split_vertically(h - bottom);
    let bar_w = (TICK * 4.2) as i32;
    let (plot_area, bar_area) = if q.is_some() {
        upper.split_horizontally(w - bar_w)
    } else {
        (upper.clone(), upper.clone())
    };
    let title = match (q, d.tip) {
        (None, Some(shape)) => format!("Adhesion map of {} (tolerance {tol})", shape.name()),
        (None, None) => format!("Adhesion map (tolerance {tol})"),
        (Some(q), _) => q.title().to_string(),
    };
    let x_range = (sp.lambda_min..sp.lambda_max).log_scale();
    let builder = || {
        let mut b = ChartBuilder::on(&plot_area);
        b.caption(title.clone(), ("sans-serif", TITLE))
            .margin(MARGIN)
            .margin_top(MARGIN + (TICK * 0.5) as i32)
            .margin_right(MARGIN + (TICK * 0.9) as i32)
            .x_label_area_size(X_AREA)
            .y_label_area_size(Y_AREA);
        b
    };
    if sp.load_axis == LoadAxis::Linear {
        let mut chart = builder().build_cartesian_2d(x_range, sp.load_min..sp.load_max)?;
        body(&mut chart, d, q, &traced, Panel::Full)?;
    } else {
        let mut chart =
            builder().build_cartesian_2d(x_range, (sp.load_min..sp.load_max).log_scale())?;
        body(&mut chart, d, q, &traced, Panel::Full)?;
    }
    if let Some(q) = q {
        colorbar(&bar_area, d, q)?;
    }
    let used = super::draw_legend_rows(&lower, &legend, NOTE, (pad, 8), w - 2 * pad)?;
    for (k, l) in caption.iter().enumerate() {
        lower.draw(&Text::new(
            l.clone(),
            (pad, used + 16 + super::line_height(NOTE) * k as i32),
            ("sans-serif", NOTE).into_font().color(&BLACK),
        ))?;
    }
    Ok(())
}

/// Chart coordinates of grid position (fractional indices).
fn to_chart(d: &MapData, fx: f64, fy: f64) -> (f64, f64) {
    let sp = &d.spec;
    let tx = fx / (sp.nx - 1) as f64;
    let ty = fy / (sp.ny - 1) as f64;
    let l =
        10f64.powf(sp.lambda_min.log10() + tx * (sp.lambda_max.log10() - sp.lambda_min.log10()));
    let y = if sp.load_axis == LoadAxis::Linear {
        sp.load_min + ty * (sp.load_max - sp.load_min)
    } else {
        10f64.powf(sp.load_min.log10() + ty * (sp.load_max.log10() - sp.load_min.log10()))
    };
    (l, y)
}

fn quantity_range(d: &MapData, q: Quantity) -> (f64, f64) {
    if q.is_error() {
        return (-6.0, 0.0);
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..d.len() {
        let v = q.transform(q.value(d, i));
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        // Nothing to colour (every point below the pull-off, say): a unit range, not infinity.
        (0.0, 1.0)
    } else if lo >= hi {
        (lo - 1.0, lo + 1.0)
    } else {
        (lo, hi)
    }
}

use super::{
    viridis, Entry, Formats, Kind, Outputs, Placer, Print, Rendered, AXIS, NOTE, REGION, TICK,
    TITLE,
};

/// Layout of every chart: margin, and the room for the tick labels and axis descriptions.
pub(crate) const MARGIN: i32 = 28;
pub(crate) const X_AREA: i32 = (TICK * 1.15 + AXIS * 1.25) as i32;
pub(crate) const Y_AREA: i32 = (TICK * 2.3 + AXIS * 1.3) as i32;

/// A whole map figure, or a small panel of one (the scene figure's): the panel has short axis
/// names and smaller region labels, and no a/R lines.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Panel {
    Full,
    Inset,
}

/// The map's raster, `w` by `h` RGB bytes: the nearest grid point's region colour, or with a
/// quantity its viridis colour (white where there is no contact, light grey where a model has no
/// answer, the failure colour where the solve failed).
fn raster(d: &MapData, q: Option<Quantity>, w: u32, h: u32) -> Vec<u8> {
    let sp = &d.spec;
    let range = q.map(|q| quantity_range(d, q));
    pixels((sp.nx, sp.ny), (w, h), |i| match (q, range) {
        (Some(q), Some((lo, hi))) => {
            let v = q.transform(q.value(d, i));
            if d.regions[i] == Region::NoContact {
                RGBColor(255, 255, 255)
            } else if v.is_finite() {
                viridis((v - lo) / (hi - lo))
            } else if q.is_error() && d.regions[i] != Region::Failed {
                RGBColor(235, 235, 235) // the model has no answer here
            } else {
                region_color(Region::Failed)
            }
        }
        _ => region_color(d.regions[i]),
    })
}

/// A `w` by `h` RGB raster of an `nx` by `ny` grid (row 0 at the bottom): each pixel the colour
/// of the nearest grid point, `colour(index)`.
pub(crate) fn pixels(
    (nx, ny): (usize, usize),
    (w, h): (u32, u32),
    colour: impl Fn(usize) -> RGBColor + Sync,
) -> Vec<u8> {
    let mut buf = vec![0u8; (w * h * 3) as usize];
    buf.par_chunks_mut((w * 3) as usize)
        .enumerate()
        .for_each(|(r, row)| {
            let iy = ((1.0 - (r as f64 + 0.5) / h as f64) * (ny - 1) as f64).round() as usize;
            for (c, px) in row.chunks_exact_mut(3).enumerate() {
                let ix = (((c as f64 + 0.5) / w as f64) * (nx - 1) as f64).round() as usize;
                let col = colour(iy * nx + ix);
                px.copy_from_slice(&[col.0, col.1, col.2]);
            }
        });
    buf
}

/// Candidate boxes of size `(tw, th)` for a line's label: around each anchor point (nearest
/// first), at three distances, on every side.
fn spots_around(anchors: &[(i32, i32)], (tw, th): (i32, i32)) -> Vec<(i32, i32, i32, i32)> {
    anchors
        .iter()
        .flat_map(|&(x, y)| {
            [12, 36, 72].into_iter().flat_map(move |r| {
                [
                    (x + r, y + r),
                    (x - tw - r, y - th - r),
                    (x + r, y - th - r),
                    (x - tw - r, y + r),
                    (x + r, y - th / 2),
                    (x - tw - r, y - th / 2),
                ]
                .map(|(x0, y0)| (x0, y0, x0 + tw, y0 + th))
            })
        })
        .collect()
}

/// The raster, the axes, the lines and the labels of a map.
fn body<'a, DB: DrawingBackend + 'a, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<plotters::coord::combinators::LogCoord<f64>, Y>>,
    d: &MapData,
    q: Option<Quantity>,
    traced: &Traced,
    panel: Panel,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let sp = &d.spec;
    let y_log = sp.load_axis != LoadAxis::Linear;
    // The raster: one bitmap pixel per drawing unit, nearest grid point (the SVG and PDF embed
    // it; the lines on top are vectors).
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (w, h) = ((px.end - px.start) as u32, (py.end - py.start) as u32);
    let buf = raster(d, q, w, h);
    let top_left = (sp.lambda_min, sp.load_max);
    if let Some(el) = BitMapElement::with_owned_buffer(top_left, (w, h), buf) {
        chart.draw_series(std::iter::once(el))?;
    }
    let (x_desc, y_desc) = match panel {
        Panel::Full => ("Maugis parameter  λ", y_desc(sp.load_axis, d.tip.is_some())),
        Panel::Inset => ("λ", "\\bar{P}"),
    };
    super::house_axes(chart.configure_mesh(), x_desc, y_desc)
        .x_label_formatter(&|v| log_label(*v))
        .y_label_formatter(&|v| {
            if y_log {
                log_label(*v)
            } else {
                super::linear_label(*v)
            }
        })
        .draw()?;

    let mut placer = Placer::default();
    let pixels = |chart: &ChartContext<'a, DB, _>, path: &[(f64, f64)]| -> Vec<(i32, i32)> {
        path.iter().map(|p| chart.backend_coord(p)).collect()
    };
    for (c, paths) in traced.criteria.iter().enumerate() {
        for path in paths {
            placer.lines.push(pixels(chart, path));
            chart.draw_series(LineSeries::new(path.clone(), criterion_style(c)))?;
        }
    }
    for path in &traced.pulloff {
        placer.lines.push(pixels(chart, path));
        chart.draw_series(LineSeries::new(path.clone(), BLACK.stroke_width(6)))?;
    }
    let lines: Vec<_> = d
        .large_deformation
        .iter()
        .filter(|l| l.points.len() >= 2 && panel == Panel::Full)
        .collect();
    for line in &lines {
        placer.lines.push(pixels(chart, &line.points));
        chart.draw_series(DashedLineSeries::new(
            line.points.clone(),
            24,
            16,
            large_deformation_style(),
        ))?;
    }
    if q.is_none() {
        region_labels(chart, d, &mut placer, panel)?;
    }
    strength_labels(chart, &lines, &mut placer)
}

/// Each a/R line's strength ratio beside it, where the label crosses no line and no label.
fn strength_labels<'a, DB: DrawingBackend + 'a, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<plotters::coord::combinators::LogCoord<f64>, Y>>,
    lines: &[&crate::map::LargeDeformationLine],
    placer: &mut Placer,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let frame = {
        let (x, y) = chart.plotting_area().get_pixel_range();
        (x.start + 4, y.start + 4, x.end - 4, y.end - 4)
    };
    for line in lines {
        let text = format!("σ_{{0}}/K = {}", line.strength_ratio);
        let tw = super::text_width(chart.plotting_area(), &text, NOTE);
        let th = super::line_height(NOTE);
        let n = line.points.len();
        let anchors = [0.7, 0.5, 0.85, 0.3, 0.6, 0.4, 0.75, 0.2, 0.9, 0.1]
            .map(|f| chart.backend_coord(&line.points[((n - 1) as f64 * f) as usize]));
        let spots = spots_around(&anchors, (tw, th));
        // Where every spot crosses a line (a crowded map), the one crossing fewest, on no label.
        let found = placer
            .take(spots.iter().copied(), frame)
            .or_else(|| placer.take_least_crossing(spots, frame));
        if let Some(b) = found {
            let style = ("sans-serif", NOTE).into_font().color(&BLACK).pos(
                plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Left,
                    plotters::style::text_anchor::VPos::Top,
                ),
            );
            chart.plotting_area().strip_coord_spec().draw(&Text::new(
                text,
                (b.0 - frame.0 + 4, b.1 - frame.1 + 4),
                style,
            ))?;
        }
    }
    Ok(())
}

/// Region labels search a C x C grid of cells; all-pairs distances: 48 keeps it to ~5M per
/// region.
const C: usize = 48;

/// The map's regions at the centres of a C x C grid of cells.
fn coarse_regions(d: &MapData) -> Vec<Region> {
    let (nx, ny) = (d.spec.nx, d.spec.ny);
    (0..C * C)
        .map(|k| {
            let (cx, cy) = (k % C, k / C);
            d.region_at(
                (cx * 2 + 1) * (nx - 1) / (2 * C - 1),
                (cy * 2 + 1) * (ny - 1) / (2 * C - 1),
            )
        })
        .collect()
}

/// The cells of region `r`, freest first: each scored by its distance from any other region
/// and from the frame (labels are wide: horizontal distance counts a third), capped, and among
/// equally free cells the region's vertical middle first.
fn ranked_cells(coarse: &[Region], r: Region) -> Vec<(f64, usize)> {
    let mid_y = {
        let ys: Vec<f64> = (0..C * C)
            .filter(|&k| coarse[k] == r)
            .map(|k| (k / C) as f64)
            .collect();
        ys.iter().sum::<f64>() / ys.len() as f64
    };
    let mut ranked: Vec<(f64, usize)> = (0..C * C)
        .filter(|&k| coarse[k] == r)
        .map(|k| {
            let (x, y) = ((k % C) as f64, (k / C) as f64);
            // Labels are wide: horizontal distance counts a third.
            let mut dist = (x + 1.0)
                .min(C as f64 - x)
                .min(3.0 * (y + 1.0))
                .min(3.0 * (C as f64 - y))
                / 3.0;
            for (j, &cj) in coarse.iter().enumerate() {
                if cj != r {
                    let (u, v) = ((j % C) as f64, (j / C) as f64);
                    dist = dist.min((((x - u) / 3.0).powi(2) + (y - v).powi(2)).sqrt());
                }
            }
            // Among equally free cells, prefer the region's vertical middle.
            (dist.min(6.0) - 0.01 * (y - mid_y).abs(), k)
        })
        .collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    ranked
}

/// Region names at the freest spot of each region: cells of a coarse grid ranked by their
/// distance from any other region (and from the frame), the first whose label box crosses no
/// line and no label placed before.
fn region_labels<'a, DB: DrawingBackend + 'a, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<plotters::coord::combinators::LogCoord<f64>, Y>>,
    d: &MapData,
    placer: &mut Placer,
    panel: Panel,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64>,
{
    let sizes: &[f64] = if panel == Panel::Full {
        &[REGION, NOTE]
    } else {
        &[NOTE]
    };
    let (nx, ny) = (d.spec.nx, d.spec.ny);
    let frac = |c: usize, n: usize| ((c * 2 + 1) * (n - 1)) as f64 / (2 * C - 1) as f64;
    let coarse = coarse_regions(d);
    let frame = {
        let (x, y) = chart.plotting_area().get_pixel_range();
        (x.start + 2, y.start + 2, x.end - 2, y.end - 2)
    };
    for r in Region::ALL {
        if r == Region::NoContact || coarse.iter().filter(|&&x| x == r).count() < 12 {
            continue;
        }
        let ranked = ranked_cells(&coarse, r);
        let label = match r {
            Region::Rigid => "Bradley".to_string(),
            Region::Md => "MD".to_string(),
            _ => r.label().to_string(),
        };
        // The larger size where it fits, else the smaller one; no label rather than one on a line.
        let Some((b, size)) = sizes.iter().find_map(|&size| {
            let (tw, th) = (
                super::text_width(chart.plotting_area(), &label, size),
                super::line_height(size),
            );
            let spots: Vec<_> = ranked
                .iter()
                .map(|&(_, k)| {
                    let (x, y) =
                        chart.backend_coord(&to_chart(d, frac(k % C, nx), frac(k / C, ny)));
                    (x - tw / 2, y - th / 2, x + tw / 2, y + th / 2)
                })
                .collect();
            placer.take(spots, frame).map(|b| (b, size))
        }) else {
            continue;
        };
        let style = ("sans-serif", size).into_font().color(&BLACK).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        let (x0, y0) = (frame.0 - 2, frame.1 - 2);
        chart.plotting_area().strip_coord_spec().draw(&Text::new(
            label,
            ((b.0 + b.2) / 2 - x0, (b.1 + b.3) / 2 - y0),
            style,
        ))?;
    }
    Ok(())
}

/// Draws a small map (regions and their boundaries, no legend) into `area`: the scene figure's
/// panel. Returns the chart so that the caller can mark points on it.
pub(crate) fn inset<'a, DB: DrawingBackend + 'a>(
    area: &'a DrawingArea<DB, Shift>,
    d: &MapData,
    caption: &str,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<
            plotters::coord::combinators::LogCoord<f64>,
            plotters::coord::types::RangedCoordf64,
        >,
    >,
    Err,
>
where
    DB::ErrorType: 'static,
{
    let sp = &d.spec;
    let mut chart = ChartBuilder::on(area)
        .caption(
            caption,
            ("sans-serif", super::fitting_size(area, caption, AXIS)),
        )
        .margin(MARGIN)
        .margin_right(MARGIN + (TICK * 0.9) as i32)
        .x_label_area_size(X_AREA)
        .y_label_area_size((TICK * 1.6 + AXIS * 1.3) as i32)
        .build_cartesian_2d(
            (sp.lambda_min..sp.lambda_max).log_scale(),
            sp.load_min..sp.load_max,
        )?;
    body(&mut chart, d, None, &trace(d), Panel::Inset)?;
    Ok(chart)
}

/// Marching-squares contour paths of `field` (row-major, nx x ny) at `level`, in fractional grid
/// indices.
pub fn contour_paths(field: &[f64], nx: usize, ny: usize, level: f64) -> Vec<Vec<(f64, f64)>> {
    let Ok(lines) = contour::ContourBuilder::new(nx, ny, true).lines(field, &[level]) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for line in &lines {
        for ls in &line.geometry().0 {
            // contour puts sample i at the centre of cell [i, i+1]: shift by half a cell and
            // clamp to the sampled range.
            let pts: Vec<(f64, f64)> =
                ls.0.iter()
                    .map(|c| {
                        (
                            (c.x - 0.5).clamp(0.0, (nx - 1) as f64),
                            (c.y - 0.5).clamp(0.0, (ny - 1) as f64),
                        )
                    })
                    .collect();
            // Closed rings run along the frame where the field is below the level at the edge:
            // those segments are not boundaries, so the path is cut there.
            let (xm, ym) = ((nx - 1) as f64, (ny - 1) as f64);
            let on_edge = |a: (f64, f64), b: (f64, f64)| {
                (a.0 == 0.0 && b.0 == 0.0)
                    || (a.0 == xm && b.0 == xm)
                    || (a.1 == 0.0 && b.1 == 0.0)
                    || (a.1 == ym && b.1 == ym)
            };
            let mut cur: Vec<(f64, f64)> = Vec::new();
            for w in pts.windows(2) {
                if on_edge(w[0], w[1]) {
                    if cur.len() >= 2 {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                } else {
                    if cur.is_empty() {
                        cur.push(w[0]);
                    }
                    cur.push(w[1]);
                }
            }
            if cur.len() >= 2 {
                out.push(cur);
            }
        }
    }
    out
}

fn colorbar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    d: &MapData,
    q: Quantity,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let (lo, hi) = quantity_range(d, q);
    let ticks: Vec<(f64, String)> = if q.log() {
        super::round_ticks(lo, hi)
            .into_iter()
            .map(|v| (v, super::power_label(v)))
            .collect()
    } else {
        // The signed-log scale: round values (0, +-0.1, +-1, +-10, ...) at their places.
        let mut vals = vec![0.0];
        for e in -1..=8 {
            for m in [1.0, 3.0] {
                let v = m * 10f64.powi(e);
                vals.extend([v, -v]);
            }
        }
        let mut t: Vec<(f64, f64)> = vals.into_iter().map(|v| (q.transform(v), v)).collect();
        t.retain(|p| (lo..=hi).contains(&p.0));
        t.sort_by(|a, b| a.0.total_cmp(&b.0));
        // At most seven, evenly thinned.
        let k = t.len().div_ceil(7).max(1);
        t.into_iter()
            .step_by(k)
            .map(|(c, v)| (c, super::minus(&super::linear_label(v))))
            .collect()
    };
    super::colorbar(area, lo, hi, &ticks)
}
