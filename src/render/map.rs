//! The adhesion map figure (PNG and SVG): regions or a continuous quantity, criteria lines,
//! pull-off, large-deformation lines, labels, legend and caption.

use super::log_label;
use crate::map::{criteria, LoadAxis, MapData, Region};
use crate::solver::Status;
use plotters::coord::Shift;
use plotters::prelude::*;
use rayon::prelude::*;
use std::path::Path;

pub const WIDTH: u32 = 1600;
pub const HEIGHT: u32 = 1200;

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
            Quantity::A => "Contact radius A (exact Maugis-Dugdale)",
            Quantity::Approach => "Approach Δ = δ (K² / (π² w² R))^(1/3) (exact Maugis-Dugdale)",
            Quantity::M => "Cohesive zone c/a − 1 (exact Maugis-Dugdale)",
            Quantity::ErrHertz => "Error of Hertz: |A_Hertz / A − 1|",
            Quantity::ErrDmt => "Error of DMT: |A_DMT / A − 1|",
            Quantity::ErrJkr => "Error of JKR: |A_JKR / A − 1|",
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
    fn inverse(self, t: f64) -> f64 {
        if self.log() {
            10f64.powf(t)
        } else {
            0.1 * t.sinh()
        }
    }
    /// The value at a solved point (NaN where undefined), before the log transform.
    fn value(self, d: &MapData, i: usize) -> f64 {
        let s = &d.states[i];
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

/// Draws the figure: PNG bytes and/or an SVG document, as asked. The figure is drawn once, as
/// SVG; the PNG is that SVG rasterised with anti-aliasing, so the two look the same.
pub fn render(
    d: &MapData,
    q: Option<Quantity>,
    png: bool,
    svg: bool,
) -> Result<(Option<Vec<u8>>, Option<String>), Err> {
    super::draw_figure((WIDTH, HEIGHT), png, svg, |root| draw(root, d, q))
}

/// Writes the figure as PNG and/or SVG files.
pub fn write(
    d: &MapData,
    q: Option<Quantity>,
    png: Option<&Path>,
    svg: Option<&Path>,
) -> Result<(), Err> {
    let (png_bytes, svg_text) = render(d, q, png.is_some(), svg.is_some())?;
    if let (Some(p), Some(b)) = (png, png_bytes) {
        crate::io::write_output(p, &b)?;
    }
    if let (Some(p), Some(s)) = (svg, svg_text) {
        crate::io::write_output(p, s.as_bytes())?;
    }
    Ok(())
}

/// The y-axis description as pieces, `true` for a piece drawn with an overbar (plotters' font
/// layout cannot place combining marks, so the bar is drawn as a line).
fn y_label(axis: LoadAxis) -> Vec<(&'static str, bool)> {
    match axis {
        LoadAxis::AbovePulloff => vec![
            ("load above pull-off  ", false),
            ("P", true),
            (" − ", false),
            ("P", true),
            ("c", false),
        ],
        _ => vec![("load  ", false), ("P", true), (" = P / (π w R)", false)],
    }
}

/// Draws `pieces` rotated (reading upwards), centred at height `cy`, with bars over the barred
/// pieces.
fn draw_rotated_label<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    pieces: &[(&str, bool)],
    x: i32,
    cy: i32,
    size: f64,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    use plotters::style::FontTransform;
    let flat: TextStyle = ("sans-serif", size).into_font().into();
    let all: String = pieces.iter().map(|p| p.0).collect();
    let (w, _) = area.estimate_text_size(&all, &flat)?;
    let y0 = cy + w as i32 / 2;
    let style = ("sans-serif", size)
        .into_font()
        .transform(FontTransform::Rotate270)
        .color(&BLACK);
    area.draw(&Text::new(all.clone(), (x, y0), style))?;
    let mut prefix = String::new();
    for (text, barred) in pieces {
        let (a, _) = area.estimate_text_size(&prefix, &flat).unwrap_or((0, 0));
        prefix.push_str(text);
        if *barred {
            let (b, _) = area.estimate_text_size(&prefix, &flat)?;
            area.draw(&PathElement::new(
                vec![(x + 1, y0 - a as i32 - 2), (x + 1, y0 - b as i32 + 2)],
                BLACK.stroke_width(2),
            ))?;
        }
    }
    Ok(())
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
    let (upper, caption_area) = root.split_vertically(HEIGHT - 70);
    let (plot_area, bar_area) = if q.is_some() {
        upper.split_horizontally(WIDTH - 190)
    } else {
        (upper.clone(), upper.clone())
    };
    let sp = &d.spec;
    let title = match q {
        None => format!(
            "Adhesion map: simplest adequate model (tolerance {}%)",
            sp.tolerance * 100.0
        ),
        Some(q) => q.title().to_string(),
    };
    let x_range = (sp.lambda_min..sp.lambda_max).log_scale();
    if sp.load_axis == LoadAxis::Linear {
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 34))
            .margin(24)
            .x_label_area_size(80)
            .y_label_area_size(110)
            .build_cartesian_2d(x_range, sp.load_min..sp.load_max)?;
        body(&mut chart, d, q)?;
    } else {
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 34))
            .margin(24)
            .x_label_area_size(80)
            .y_label_area_size(110)
            .build_cartesian_2d(x_range, (sp.load_min..sp.load_max).log_scale())?;
        body(&mut chart, d, q)?;
    }
    let (_, ph) = plot_area.dim_in_pixel();
    draw_rotated_label(
        &plot_area,
        &y_label(sp.load_axis),
        14,
        (ph as i32 - 60) / 2 + 40,
        28.0,
    )?;
    if let Some(q) = q {
        colorbar(&bar_area, d, q)?;
    }
    let tol = format!("{}%", sp.tolerance * 100.0);
    let lines = [
        format!("Regions: the first model whose contact radius A is within {tol} of the exact Maugis-Dugdale (MD) one: Hertz |A_H/A − 1| ≤ {tol} (loads ≥ 0);"),
        format!("Bradley (rigid) (πλ/2)·max(A², |approach|) ≤ {tol};  DMT |A_DMT/A − 1| ≤ {tol};  JKR |A_JKR/A − 1| ≤ {tol};  else MD.  White: below the pull-off, no contact.  Dashed: a/R = 0.1."),
    ];
    for (k, l) in lines.iter().enumerate() {
        caption_area.draw(&Text::new(
            l.as_str(),
            (30, 8 + 28 * k as i32),
            ("sans-serif", 19).into_font().color(&BLACK),
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
    for i in 0..d.states.len() {
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

use super::viridis;

fn body<'a, DB: DrawingBackend + 'a, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<plotters::coord::combinators::LogCoord<f64>, Y>>,
    d: &MapData,
    q: Option<Quantity>,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let sp = &d.spec;
    let y_log = sp.load_axis != LoadAxis::Linear;
    // The raster: one pixel of the plotting area per bitmap pixel, nearest grid point.
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (w, h) = ((px.end - px.start) as u32, (py.end - py.start) as u32);
    let range = q.map(|q| quantity_range(d, q));
    let mut buf = vec![0u8; (w * h * 3) as usize];
    for r in 0..h {
        let iy = ((1.0 - (r as f64 + 0.5) / h as f64) * (sp.ny - 1) as f64).round() as usize;
        for c in 0..w {
            let ix = (((c as f64 + 0.5) / w as f64) * (sp.nx - 1) as f64).round() as usize;
            let i = iy * sp.nx + ix;
            let col = match (q, range) {
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
            };
            let k = ((r * w + c) * 3) as usize;
            buf[k..k + 3].copy_from_slice(&[col.0, col.1, col.2]);
        }
    }
    let top_left = (sp.lambda_min, sp.load_max);
    if let Some(el) = BitMapElement::with_owned_buffer(top_left, (w, h), buf) {
        chart.draw_series(std::iter::once(el))?;
    }
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("Maugis parameter  λ")
        .axis_desc_style(("sans-serif", 28))
        .label_style(("sans-serif", 22))
        .x_label_formatter(&|v| log_label(*v))
        .y_label_formatter(&|v| {
            if y_log {
                log_label(*v)
            } else {
                super::linear_label(*v)
            }
        })
        .draw()?;

    // Criteria lines at the tolerance, and the pull-off (edge of the no-contact region), traced
    // on a grid strided to about the plot's pixel resolution: finer lines would not show.
    let (nx, ny) = (sp.nx, sp.ny);
    let k = nx.max(ny).div_ceil(800).max(1);
    let (mx, my) = ((nx - 1) / k + 1, (ny - 1) / k + 1);
    let fields: Vec<[f64; 5]> = (0..mx * my)
        .into_par_iter()
        .map(|j| {
            let i = (j / mx) * k * nx + (j % mx) * k;
            let s = &d.states[i];
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
    let names = ["Hertz", "Bradley (rigid)", "DMT", "JKR"];
    // A legend only for lines that were drawn (none where no point is in contact).
    let mut labelled = false;
    for (c, name) in names.iter().enumerate() {
        let field: Vec<f64> = fields.iter().map(|f| f[c]).collect();
        let style = ShapeStyle::from(&line_color(c)).stroke_width(3);
        let mut first = true;
        for path in contour_paths(&field, mx, my, sp.tolerance) {
            let series = chart.draw_series(LineSeries::new(scaled(path), style))?;
            if first {
                labelled = true;
                series
                    .label(format!("{name} within {}%", sp.tolerance * 100.0))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], style));
                first = false;
            }
        }
    }
    let contact: Vec<f64> = fields.iter().map(|f| f[4]).collect();
    let mut first = true;
    let has_edge = contact.contains(&0.0) && contact.contains(&1.0);
    for path in contour_paths(&contact, mx, my, 0.5)
        .into_iter()
        .filter(|_| has_edge)
    {
        let s = chart.draw_series(LineSeries::new(scaled(path), BLACK.stroke_width(3)))?;
        if first {
            labelled = true;
            s.label("pull-off (load control)").legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 30, y)], BLACK.stroke_width(3))
            });
            first = false;
        }
    }
    for (k, line) in d.large_deformation.iter().enumerate() {
        if line.points.len() < 2 {
            continue;
        }
        let style = ShapeStyle::from(&BLACK).stroke_width(2);
        chart.draw_series(DashedLineSeries::new(line.points.clone(), 12, 8, style))?;
        let (lx, ly) = line.points[line.points.len() * (7 - 2 * k.min(2)) / 10];
        chart.draw_series(std::iter::once(Text::new(
            format!("a/R = 0.1, σ0/K = {}", line.strength_ratio),
            (lx, ly),
            ("sans-serif", 20).into_font(),
        )))?;
    }
    if q.is_none() {
        region_labels(chart, d)?;
    }
    if labelled {
        super::legend(chart, SeriesLabelPosition::LowerRight, 20)?;
    }
    Ok(())
}

/// Region names at each region's pole of inaccessibility, found on a coarse grid: the cell of
/// the region farthest from any other region (and from the frame).
fn region_labels<'a, DB: DrawingBackend + 'a, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<plotters::coord::combinators::LogCoord<f64>, Y>>,
    d: &MapData,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64>,
{
    // All-pairs distances on a C x C grid: 48 keeps it to ~5M per region.
    const C: usize = 48;
    let (nx, ny) = (d.spec.nx, d.spec.ny);
    let coarse: Vec<Region> = (0..C * C)
        .map(|k| {
            let (cx, cy) = (k % C, k / C);
            d.region_at(
                (cx * 2 + 1) * (nx - 1) / (2 * C - 1),
                (cy * 2 + 1) * (ny - 1) / (2 * C - 1),
            )
        })
        .collect();
    for r in Region::ALL {
        if r == Region::NoContact || coarse.iter().filter(|&&x| x == r).count() < 12 {
            continue;
        }
        let mid_y = {
            let ys: Vec<f64> = (0..C * C)
                .filter(|&k| coarse[k] == r)
                .map(|k| (k / C) as f64)
                .collect();
            ys.iter().sum::<f64>() / ys.len() as f64
        };
        let mut best = (f64::NEG_INFINITY, 0usize);
        for k in 0..C * C {
            if coarse[k] != r {
                continue;
            }
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
            let score = dist.min(6.0) - 0.01 * (y - mid_y).abs();
            if score > best.0 {
                best = (score, k);
            }
        }
        let (cx, cy) = (best.1 % C, best.1 / C);
        let fx = ((cx * 2 + 1) * (nx - 1)) as f64 / (2 * C - 1) as f64;
        let fy = ((cy * 2 + 1) * (ny - 1)) as f64 / (2 * C - 1) as f64;
        let style = ("sans-serif", 30).into_font().color(&BLACK).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        chart.draw_series(std::iter::once(Text::new(
            r.label().to_string(),
            to_chart(d, fx, fy),
            style,
        )))?;
    }
    Ok(())
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
    let log = q.log();
    super::colorbar(area, lo, hi, &|v| {
        if log {
            format!("1e{:.1}", v).replace(".0", "")
        } else {
            format!("{:.2}", q.inverse(v))
        }
    })
}
