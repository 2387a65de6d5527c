//! Line plots for the gallery: pull-off against lambda, and A(P) curves.

use super::log_label;
use crate::physics::closed::{
    cos_pulloff, dmt_radius, hertz_radius, jkr_radius, JKR_PULLOFF_DISPLACEMENT, JKR_PULLOFF_LOAD,
};
use crate::physics::md::LAMBDA_D;
use crate::physics::model::ContactModel;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

type Err = Box<dyn std::error::Error + Send + Sync>;
/// A chart with linear axes.
type Chart2d<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

use super::map::{MARGIN, X_AREA, Y_AREA};
pub use super::DrawSvg;
use super::{house_mesh, sample, sample_dashed, Kind, Outputs, Print, AXIS, NOTE, TICK, TITLE};

/// Draws a figure of `kind` with `g` and writes it to the files in `out`.
pub fn save(kind: Kind, print: &Print, out: &Outputs, g: DrawSvg) -> anyhow::Result<()> {
    super::save(kind, print, out, g)
}

/// A chart builder with the common layout: title, margin, and room for ticks and axis names.
pub(crate) fn builder<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
) -> ChartBuilder<'a, 'b, DB> {
    let mut b = ChartBuilder::on(area);
    if !title.is_empty() {
        // A long title shrinks to the figure's width rather than being cut at both ends.
        let room = 0.96 * area.dim_in_pixel().0 as f64;
        let wide = super::text_width(area, title, TITLE) as f64;
        let size = if wide > room {
            TITLE * room / wide
        } else {
            TITLE
        };
        b.caption(title, ("sans-serif", size));
    }
    // On the right, room for half of the last tick label.
    b.margin(MARGIN)
        .margin_top(MARGIN + (TICK * 0.5) as i32)
        .margin_right(MARGIN + (TICK * 0.9) as i32)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA);
    b
}

/// Splits a two-panel figure: side by side when wide, stacked when narrow (one column).
pub(crate) fn two_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
) -> (DrawingArea<DB, Shift>, DrawingArea<DB, Shift>) {
    let (w, h) = root.dim_in_pixel();
    if w as f64 / h as f64 > 1.2 {
        root.split_horizontally(w * 3 / 5)
    } else {
        root.split_vertically(h * 11 / 20)
    }
}

pub(crate) const BLUE_: RGBColor = RGBColor(0, 114, 178);
pub(crate) const ORANGE_: RGBColor = RGBColor(213, 94, 0);
pub(crate) const GREEN_: RGBColor = RGBColor(0, 158, 115);
pub(crate) const GRAY_: RGBColor = RGBColor(120, 120, 120);
pub(crate) const PURPLE_: RGBColor = RGBColor(204, 121, 167);

/// A model's colour in every line figure, the hues of the map's regions (DMT blue, JKR orange),
/// so that a model reads the same across figures; its name is [`ContactModel::label`].
pub(crate) fn model_colour(m: ContactModel) -> RGBColor {
    match m {
        ContactModel::Hertz | ContactModel::Rigid => GRAY_,
        ContactModel::Dmt => BLUE_,
        ContactModel::Jkr => ORANGE_,
        ContactModel::Md => GREEN_,
        ContactModel::SolidAndMeniscus => PURPLE_,
    }
}

/// Pull-off force against lambda under load and displacement control, with the DMT/Bradley and
/// JKR limits and the Carpick-Ogletree-Salmeron fit.
pub fn pulloff<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &crate::figure_data::PulloffData,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (lambdas, ctx) = (&data.lambdas, &data.contexts);
    let mut chart = builder(root, "Pull-off force").build_cartesian_2d(
        (1e-4..1e4f64)
            .log_scale()
            .with_key_points(vec![1e-4, 1e-2, 1.0, 1e2, 1e4]),
        -2.1..-0.7f64,
    )?;
    house_mesh(
        chart.configure_mesh(),
        "Maugis parameter  λ",
        "pull-off load  \\bar{P}_{c} = P_{c}/(πwR)",
    )
    .x_label_formatter(&|v| log_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    let thick = |c: RGBColor| ShapeStyle::from(&c).stroke_width(8);
    chart
        .draw_series(LineSeries::new(
            lambdas
                .iter()
                .zip(ctx)
                .map(|(&l, c)| (l, c.load_pulloff.load)),
            thick(BLUE_),
        ))?
        .label("MD, load control")
        .legend(sample(thick(BLUE_)));
    chart
        .draw_series(LineSeries::new(
            lambdas
                .iter()
                .zip(ctx)
                .map(|(&l, c)| (l, c.disp_pulloff().load)),
            thick(ORANGE_),
        ))?
        .label("MD, rigid grips")
        .legend(sample(thick(ORANGE_)));
    let cos = ShapeStyle::from(&GREEN_).stroke_width(6);
    chart
        .draw_series(DashedLineSeries::new(
            lambdas.iter().map(|&l| (l, cos_pulloff(l))),
            20,
            16,
            cos,
        ))?
        .label("COS fit (Carpick 1999)")
        .legend(sample_dashed(cos));
    let gray = ShapeStyle::from(&GRAY_).stroke_width(4);
    for (y, text) in [
        (-2.0, "DMT, Bradley: −2"),
        (JKR_PULLOFF_LOAD, "JKR, load control: −3/2"),
        (JKR_PULLOFF_DISPLACEMENT, "JKR, displacement control: −5/6"),
    ] {
        chart.draw_series(DashedLineSeries::new(
            vec![(1e-4, y), (1e4, y)],
            12,
            12,
            gray,
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            text,
            (1.6e-4, y + 0.02),
            ("sans-serif", NOTE)
                .into_font()
                .color(&GRAY_)
                .pos(Pos::new(HPos::Left, VPos::Bottom)),
        )))?;
    }
    chart.draw_series(DashedLineSeries::new(
        vec![(LAMBDA_D, -2.1), (LAMBDA_D, -0.7)],
        8,
        12,
        ShapeStyle::from(&BLACK).stroke_width(2),
    ))?;
    chart.draw_series(std::iter::once(Text::new(
        "λ_{D} = 0.938",
        (LAMBDA_D * 1.25, -1.25),
        ("sans-serif", NOTE)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Center)),
    )))?;
    // In the empty band between the two JKR limits, right of the transition.
    let (x0, y0) = chart.backend_coord(&(1.2, -0.93));
    let (px, py) = chart.plotting_area().get_pixel_range();
    let at = SeriesLabelPosition::Coordinate(x0 - px.start, y0 - py.start);
    super::legend(&mut chart, at, NOTE)?;
    Ok(())
}

/// Most curves [`curves`] names one by one in its legend.
pub const MAX_CURVE_ENTRIES: usize = 6;

/// A curve's legend label: lambda in at most six significant digits (`0.1 + 0.2` is shown
/// as 0.3, not 0.30000000000000004).
pub fn curve_label(lambda: f64) -> String {
    format!("MD, λ = {}", crate::physics::domain::short(lambda))
}

/// A(P) for several lambda: the exact MD curve (stable under load control solid, unstable
/// dashed) with Hertz, DMT and JKR.
pub fn curves<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    series: &[crate::figure_data::CurveSeries],
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let mut chart = builder(root, "Contact radius against load")
        .build_cartesian_2d(-2.2..4.0f64, 0.0..2.6f64)?;
    house_mesh(
        chart.configure_mesh(),
        "load  \\bar{P} = P/(πwR)",
        "contact radius  A = a (K/πwR²)^{1/3}",
    )
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    let grid: Vec<f64> = (0..=600).map(|i| -2.2 + 6.2 * i as f64 / 600.0).collect();
    let closed = [
        ("Hertz", GRAY_, hertz_radius as fn(f64) -> Option<f64>),
        ("DMT", BLUE_, dmt_radius),
        ("JKR", ORANGE_, jkr_radius),
    ];
    for (name, col, f) in closed {
        let st = ShapeStyle::from(&col).stroke_width(4);
        chart
            .draw_series(DashedLineSeries::new(
                grid.iter().filter_map(|&p| f(p).map(|a| (p, a))),
                16,
                12,
                st,
            ))?
            .label(name)
            .legend(sample_dashed(st));
    }
    let palette = [
        RGBColor(0, 0, 0),
        GREEN_,
        RGBColor(204, 121, 167),
        RGBColor(86, 180, 233),
        RGBColor(230, 159, 0),
    ];
    // One legend entry per curve while they fit beside the axes; beyond that one entry says how
    // many and over which lambda (201 entries overflowed the figure).
    let each = series.len() <= MAX_CURVE_ENTRIES;
    for (k, cs) in series.iter().enumerate() {
        let (l, pts) = (cs.lambda, &cs.points);
        let col = palette[k % palette.len()];
        let stable: Vec<(f64, f64)> = pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect();
        let unstable: Vec<(f64, f64)> = pts.iter().filter(|p| !p.2).map(|p| (p.0, p.1)).collect();
        let st = ShapeStyle::from(&col).stroke_width(8);
        let drawn = chart.draw_series(LineSeries::new(stable, st))?;
        if each {
            drawn.label(curve_label(l)).legend(sample(st));
        }
        chart.draw_series(DashedLineSeries::new(
            unstable,
            10,
            10,
            ShapeStyle::from(&col).stroke_width(4),
        ))?;
        chart.draw_series(std::iter::once(Circle::new(cs.pulloff, 14, col.filled())))?;
    }
    if !each {
        let (lo, hi) = series
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
                (a.min(c.lambda), b.max(c.lambda))
            });
        let st = ShapeStyle::from(&palette[0]).stroke_width(8);
        chart
            .draw_series(LineSeries::new(Vec::<(f64, f64)>::new(), st))?
            .label(format!(
                "MD, {} curves, λ = {}…{}",
                series.len(),
                crate::physics::domain::short(lo),
                crate::physics::domain::short(hi)
            ))
            .legend(sample(st));
    }
    chart.draw_series(std::iter::once(Text::new(
        "dots: pull-off; thin dashes: unstable",
        (3.9, 0.06),
        ("sans-serif", NOTE)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Right, VPos::Bottom)),
    )))?;
    super::legend(&mut chart, SeriesLabelPosition::UpperLeft, NOTE)?;
    Ok(())
}

/// Throughput against max relative error of A, one marker per variant, the Pareto front drawn.
/// Hollow markers: variants with failures.
pub fn bench_chart<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    results: &[crate::bench::VariantResult],
    front: &[usize],
    title: &str,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let err = |r: &crate::bench::VariantResult| r.max_rel_err.clamp(1e-13, 1.0);
    let speeds: Vec<f64> = results
        .iter()
        .map(|r| r.points_per_second)
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    // Bounded whatever the input: a log axis over no speeds, or up to 1e308, would have no end.
    if speeds.is_empty() {
        return Err("no variant has a positive speed: nothing to draw".into());
    }
    let (smin, smax) = (
        speeds.iter().cloned().fold(f64::INFINITY, f64::min),
        speeds.iter().cloned().fold(0.0, f64::max),
    );
    let mut chart = builder(root, title).build_cartesian_2d(
        (1e-13..3.0f64).log_scale(),
        ((smin / 3.0).clamp(1.0, 1e18)..(smax * 5.0).clamp(10.0, 1e19)).log_scale(),
    )?;
    house_mesh(
        chart.configure_mesh(),
        "max relative error of A against the exact solution",
        "throughput (solves per second)",
    )
    .x_label_formatter(&|v| log_label(*v))
    .y_label_formatter(&|v| log_label(*v))
    .draw()?;
    let pf: Vec<(f64, f64)> = front
        .iter()
        .map(|&i| (err(&results[i]), results[i].points_per_second))
        .collect();
    chart
        .draw_series(LineSeries::new(
            pf,
            ShapeStyle::from(&GREEN_).stroke_width(6),
        ))?
        .label("Pareto front")
        .legend(sample(ShapeStyle::from(&GREEN_).stroke_width(6)));
    // Markers first; then each label at the first nearby spot that overlaps no marker and no
    // label placed before it (boxes in pixels; the text width is estimated from the font size).
    let mut placer = super::Placer::default();
    for r in results {
        let (x, y) = (err(r), r.points_per_second);
        chart.draw_series(std::iter::once(Circle::new((x, y), 18, bench_marker(r))))?;
        let (px, py) = chart.backend_coord(&(x, y));
        placer.boxes.push((px - 22, py - 22, px + 22, py + 22));
    }
    // The Pareto front is a line labels must not cross.
    placer.lines.push(
        front
            .iter()
            .map(|&i| chart.backend_coord(&(err(&results[i]), results[i].points_per_second)))
            .collect(),
    );
    let plot = chart.plotting_area().get_pixel_range();
    let frame = (plot.0.start, plot.1.start, plot.0.end, plot.1.end);
    // Labels from the fastest variant down: in a column of markers the labels then stack in the
    // markers' order.
    let mut by_speed: Vec<&crate::bench::VariantResult> = results.iter().collect();
    by_speed.sort_by(|a, b| b.points_per_second.total_cmp(&a.points_per_second));
    for r in by_speed {
        let (x, y) = (err(r), r.points_per_second);
        let label = if r.failures > 0 {
            format!("{} ({} failed)", r.name, r.failures)
        } else {
            r.name.clone()
        };
        let marker = chart.backend_coord(&(x, y));
        bench_label(root, &mut placer, frame, marker, x <= 1e-2, label)?;
    }
    chart.draw_series(std::iter::once(Text::new(
        "orange: GPU; blue: CPU; gray: closed forms; hollow: some points failed",
        (2e-13, smin / 2.2),
        ("sans-serif", NOTE).into_font(),
    )))?;
    super::legend(&mut chart, SeriesLabelPosition::UpperRight, NOTE)?;
    Ok(())
}

/// Draws `label` at the first spot beside the marker at pixel `(px, py)` that the placer finds
/// free (else the one crossing fewest lines), with a thin leader where it left the marker's
/// level, so that a crowded column of markers can still be read.
fn bench_label<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    placer: &mut super::Placer,
    frame: (i32, i32, i32, i32),
    (px, py): (i32, i32),
    right_first: bool,
    label: String,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let size = (
        super::text_width(root, &label, NOTE),
        super::line_height(NOTE),
    );
    let spots = label_spots((px, py), size, right_first);
    let spot = placer
        .take(spots.iter().copied(), frame)
        .or_else(|| placer.take_least_crossing(spots.iter().copied(), frame))
        .unwrap_or(spots[0]);
    let mid = (spot.1 + spot.3) / 2;
    if (mid - py).abs() > size.1 / 2 {
        let (from, to) = if spot.0 > px {
            ((px + 20, py), (spot.0 - 4, mid))
        } else {
            ((px - 20, py), (spot.2 + 4, mid))
        };
        root.draw(&PathElement::new(
            vec![from, to],
            ShapeStyle::from(&GRAY_).stroke_width(2),
        ))?;
    }
    let style = ("sans-serif", NOTE)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    root.draw(&Text::new(label, (spot.0, mid), style))?;
    Ok(())
}

/// A variant's marker: orange for the GPU, blue for the CPU solvers, grey for the closed
/// forms; hollow where some points failed.
fn bench_marker(r: &crate::bench::VariantResult) -> ShapeStyle {
    let col = if r.name.starts_with("gpu") {
        ORANGE_
    } else if r.name.starts_with("cpu") || r.name.starts_with("naive") {
        BLUE_
    } else {
        GRAY_
    };
    if r.failures > 0 {
        ShapeStyle::from(&col).stroke_width(6)
    } else {
        col.filled()
    }
}

/// Candidate boxes for a label of size `(w, h)` beside a marker at `(px, py)`: level with it,
/// then one to five lines up and down, on the preferred side first.
fn label_spots(
    (px, py): (i32, i32),
    (w, h): (i32, i32),
    right_first: bool,
) -> Vec<(i32, i32, i32, i32)> {
    let mut spots = Vec::new();
    for dy in [0, -1, 1, -2, 2, -3, 3, -4, 4, -5, 5].map(|k| k * (h + 4)) {
        for right in [right_first, !right_first] {
            let x0 = if right { px + 28 } else { px - 28 - w };
            spots.push((x0, py + dy - h / 2, x0 + w, py + dy + h / 2));
        }
    }
    spots
}

/// A scene: a(P) in SI units with engineering prefixes (MD bold, the recommended model dashed,
/// the others faint) and the scene's lambda and loads on the adhesion map.
pub fn scene<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &crate::scene::SceneResult,
    fig: &crate::figure_data::SceneFigure,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (left, right) = two_panels(root);
    let fs = fig.force_scale;
    let (pc, pmax) = fig.loads;
    let md = &fig.md;
    let amax = md
        .iter()
        .chain(fig.wet.iter().flatten())
        .map(|q| q.1)
        .fold(0.0, f64::max)
        * if fig.wet.is_some() { 1.25 } else { 1.1 };
    // Display units: the prefix that keeps the ticks between 1 and 1000.
    let (fu, fp) = super::si_prefix(pmax.max(pc.abs() * 1.4));
    let (au, ap) = super::si_prefix(amax);
    let p_lo = pc * 1.4;
    let mut chart =
        builder(&left, &r.name).build_cartesian_2d(p_lo / fu..pmax / fu, 0.0..amax / au)?;
    house_mesh(
        chart.configure_mesh(),
        format!("load  P ({fp}N)"),
        format!("contact radius  a ({ap}m)"),
    )
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    scene_closed_forms(&mut chart, r, fig, (p_lo, pmax), (fu, au), amax)?;
    let st = ShapeStyle::from(&BLACK).stroke_width(6);
    let (md_style, md_label) = match &fig.wet {
        None => (st, "Maugis-Dugdale (exact)"),
        Some(_) => (
            ShapeStyle::from(&GRAY_).stroke_width(5),
            "dry: Maugis-Dugdale (exact)",
        ),
    };
    chart
        .draw_series(LineSeries::new(
            md.iter().map(|&(p, a)| (p / fu, a / au)),
            md_style,
        ))?
        .label(md_label)
        .legend(sample(md_style));
    if let Some(wet) = &fig.wet {
        chart
            .draw_series(LineSeries::new(
                wet.iter().map(|&(p, a)| (p / fu, a / au)),
                st,
            ))?
            .label(format!(
                "solid + meniscus, RH {:.0}% (exact)",
                100.0 * r.relative_humidity.unwrap_or(f64::NAN)
            ))
            .legend(sample(st));
    }
    for l in &r.loads {
        if let Some(a) = l.contact_radius_m {
            chart.draw_series(std::iter::once(Circle::new(
                (l.load_n / fu, a / au),
                12,
                BLACK.filled(),
            )))?;
        }
    }
    // A wet scene's legend above its curves, clear of the dry curve's pull-off.
    let corner = if fig.wet.is_some() {
        SeriesLabelPosition::UpperLeft
    } else {
        SeriesLabelPosition::LowerRight
    };
    super::legend(&mut chart, corner, NOTE)?;

    // Where the scene sits on the map (normalised loads), drawn as `tabor map` draws; a wet
    // scene's dry contact (its loads in the solid's units), the map being single-zone MD.
    let loads: Vec<f64> = match &fig.wet {
        None => r.loads.iter().map(|l| l.load_normalised).collect(),
        // Only where the dry contact holds: above its own pull-off.
        Some(_) => r
            .loads
            .iter()
            .map(|l| l.load_n / fs)
            .filter(|&p| p >= r.dry_pulloff_force_load_control_N.unwrap_or(pc) / fs)
            .collect(),
    };
    let title = if fig.wet.is_some() {
        "the dry contact on the map"
    } else {
        "on the adhesion map"
    };
    scene_on_map(&right, r, &fig.map, &loads, title)
}

/// The closed forms' a(P) of a dry scene, dashed: the recommended one bold, the others faint.
fn scene_closed_forms<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    r: &crate::scene::SceneResult,
    fig: &crate::figure_data::SceneFigure,
    (p_lo, pmax): (f64, f64),
    (fu, au): (f64, f64),
    amax: f64,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let (fs, rs) = (fig.force_scale, fig.radius_scale);
    let closed = [
        (
            "hertz",
            "Hertz",
            GRAY_,
            hertz_radius as fn(f64) -> Option<f64>,
        ),
        ("dmt", "DMT", BLUE_, dmt_radius),
        ("jkr", "JKR", ORANGE_, jkr_radius),
    ];
    // A wet scene: the closed forms are the dry contact's, and the MD curve is drawn against
    // the curve of solid and meniscus instead.
    for (key, name, col, f) in closed.into_iter().filter(|_| fig.wet.is_none()) {
        let rec = r.recommended_model.name() == key;
        let st = if rec {
            ShapeStyle::from(&col).stroke_width(8)
        } else {
            ShapeStyle::from(&col.mix(0.35)).stroke_width(4)
        };
        let pts: Vec<(f64, f64)> = (0..=300)
            .filter_map(|i| {
                let p = p_lo + (pmax - p_lo) * i as f64 / 300.0;
                f(p / fs)
                    .map(|a| (p / fu, a * rs / au))
                    .filter(|q| q.1 <= amax / au)
            })
            .collect();
        chart
            .draw_series(DashedLineSeries::new(pts, 16, 12, st))?
            .label(if rec {
                format!("{name} (recommended)")
            } else {
                name.to_string()
            })
            .legend(sample_dashed(st));
    }
    Ok(())
}

/// The scene's lambda and loads as crosses on an inset adhesion map.
fn scene_on_map<DB: DrawingBackend>(
    right: &DrawingArea<DB, Shift>,
    r: &crate::scene::SceneResult,
    d: &crate::map::MapData,
    loads: &[f64],
    title: &str,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let mut ch = super::map::inset(right, d, title)?;
    let l = r.lambda.clamp(d.spec.lambda_min, d.spec.lambda_max);
    for &ld in loads {
        let y = ld.clamp(d.spec.load_min, d.spec.load_max);
        ch.draw_series(std::iter::once(Cross::new(
            (l, y),
            16,
            BLACK.stroke_width(6),
        )))?;
    }
    let right_half = l > (d.spec.lambda_min * d.spec.lambda_max).sqrt();
    ch.draw_series(std::iter::once(Text::new(
        format!(
            "λ = {}",
            crate::physics::domain::short((r.lambda * 1e3).round() / 1e3)
        ),
        (
            l * if right_half { 0.8 } else { 1.25 },
            d.spec.load_max - 0.04 * (d.spec.load_max - d.spec.load_min),
        ),
        ("sans-serif", NOTE).into_font().color(&BLACK).pos(Pos::new(
            if right_half { HPos::Right } else { HPos::Left },
            VPos::Top,
        )),
    )))?;
    ch.draw_series(DashedLineSeries::new(
        vec![(l, d.spec.load_min), (l, d.spec.load_max)],
        8,
        12,
        ShapeStyle::from(&BLACK.mix(0.6)).stroke_width(2),
    ))?;
    Ok(())
}

/// An approach-retract cycle: load against approach (the equilibrium path faint, approach blue,
/// retract orange, jumps as arrows) and contact radius against load.
pub fn cycle<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    c: &crate::cycle::Cycle,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (left, right) = two_panels(root);
    let steps = |ph: crate::cycle::Phase| -> Vec<&crate::cycle::Step> {
        c.steps.iter().filter(|s| s.phase == ph).collect()
    };
    let ((xmin, xmax), (ymin, ymax)) = cycle_ranges(c);
    let pad = 0.08 * (xmax - xmin);
    let drive = match c.drive {
        crate::cycle::Drive::RigidGrips => "rigid grips".to_string(),
        crate::cycle::Drive::DeadLoad => "dead load".to_string(),
        crate::cycle::Drive::Spring(k) => format!("spring, k = {k:.3}"),
    };
    let mut chart = builder(
        &left,
        &format!("Approach and retract, λ = {}, {drive}", c.lambda),
    )
    .build_cartesian_2d(
        xmin - pad..xmax + pad,
        ymin * 1.15 - 0.05..ymax * 1.05 + 0.05,
    )?;
    house_mesh(
        chart.configure_mesh(),
        "approach  Δ = δ (K²/π²w²R)^{1/3}",
        "load  \\bar{P} = P/(πwR)",
    )
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    let eq: Vec<(f64, f64)> = c
        .path
        .iter()
        .filter(|p| p.approach >= xmin - pad)
        .map(|p| (p.approach, p.load))
        .collect();
    let faint = ShapeStyle::from(&RGBColor(170, 170, 170)).stroke_width(12);
    chart
        .draw_series(LineSeries::new(eq, faint))?
        .label("equilibrium path")
        .legend(sample(faint));
    // Retract first and wide, approach on top and thin: where they coincide both stay visible.
    use crate::cycle::Phase;
    for (ph, col, width) in [(Phase::Retract, ORANGE_, 12), (Phase::Approach, BLUE_, 4)] {
        let st = ShapeStyle::from(&col).stroke_width(width);
        let mut seg: Vec<(f64, f64)> = Vec::new();
        let mut first = true;
        for s in steps(ph) {
            if s.jump && !seg.is_empty() {
                let s2 = chart.draw_series(LineSeries::new(std::mem::take(&mut seg), st))?;
                if first {
                    s2.label(ph.to_string()).legend(sample(st));
                    first = false;
                }
            }
            if s.point.approach >= xmin - pad {
                seg.push((s.point.approach, s.point.load));
            }
        }
        if !seg.is_empty() {
            let s2 = chart.draw_series(LineSeries::new(seg, st))?;
            if first {
                s2.label(ph.to_string()).legend(sample(st));
            }
        }
    }
    cycle_jumps(root, &mut chart, c, ymax)?;
    super::legend(&mut chart, SeriesLabelPosition::UpperLeft, NOTE)?;
    let energy = match c.hysteresis {
        Some(w) => format!("energy lost: {w:.4}"),
        None => "no closed cycle".into(),
    };
    cycle_energy(root, &chart, c, energy)?;
    cycle_radius(&right, c, (ymin, ymax), faint)
}

/// The ranges of a cycle's approach (its states off the free branch) and load (from 0), each
/// holding every jump's landing too, so that each arrow ends inside the axes.
fn cycle_ranges(c: &crate::cycle::Cycle) -> ((f64, f64), (f64, f64)) {
    let xs: Vec<f64> = c
        .path
        .iter()
        .filter(|p| p.branch != crate::cycle::Branch::Free)
        .map(|p| p.approach)
        .collect();
    let landings = c
        .jumps
        .iter()
        .filter_map(|j| j.to.as_ref().map(|t| t.approach));
    let (xmin, xmax) = xs
        .iter()
        .cloned()
        .chain(landings)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    let (ymin, ymax) = c
        .path
        .iter()
        .map(|p| p.load)
        .chain(c.jumps.iter().filter_map(|j| j.to.as_ref().map(|t| t.load)))
        .fold((0.0f64, 0.0f64), |(lo, hi), y| (lo.min(y), hi.max(y)));
    ((xmin, xmax), (ymin, ymax))
}

/// A cycle's jumps: dashed lines with an arrowhead drawn in pixel space.
fn cycle_jumps<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &mut Chart2d<'_, DB>,
    c: &crate::cycle::Cycle,
    ymax: f64,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    for j in &c.jumps {
        let col = if j.phase == crate::cycle::Phase::Approach {
            BLUE_
        } else {
            ORANGE_
        };
        let from = (j.from.approach, j.from.load);
        let to = match &j.to {
            Some(t) => (t.approach, t.load),
            None => (j.from.approach, ymax * 1.05 + 0.05),
        };
        chart.draw_series(DashedLineSeries::new(
            vec![from, to],
            12,
            8,
            ShapeStyle::from(&col).stroke_width(4),
        ))?;
        let (p0, p1) = (chart.backend_coord(&from), chart.backend_coord(&to));
        let (dx, dy) = ((p1.0 - p0.0) as f64, (p1.1 - p0.1) as f64);
        let len = (dx * dx + dy * dy).sqrt().max(1.0);
        let (ux, uy) = (dx / len, dy / len);
        let tip = p1;
        let base = (tip.0 as f64 - 32.0 * ux, tip.1 as f64 - 32.0 * uy);
        let wing = |s: f64| {
            (
                (base.0 - 14.0 * uy * s) as i32,
                (base.1 + 14.0 * ux * s) as i32,
            )
        };
        root.draw(&Polygon::new(
            vec![tip, wing(1.0), wing(-1.0)],
            col.filled(),
        ))?;
    }
    Ok(())
}

/// The energy lost, in a corner that no curve crosses (the legend holds the upper left).
fn cycle_energy<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart2d<'_, DB>,
    c: &crate::cycle::Cycle,
    energy: String,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let (px, py) = chart.plotting_area().get_pixel_range();
    let mut placer = super::Placer::default();
    placer.lines.push(
        c.path
            .iter()
            .map(|p| chart.backend_coord(&(p.approach, p.load)))
            .collect(),
    );
    let (tw, th) = (
        super::text_width(root, &energy, NOTE),
        super::line_height(NOTE),
    );
    let frame = (px.start, py.start, px.end, py.end);
    let corners = [
        (px.end - 20 - tw, py.end - 20 - th),
        (px.start + 20, py.end - 20 - th),
        (px.end - 20 - tw, py.start + 20),
        (px.start + 20, (py.start + py.end) / 2),
    ]
    // Padded by the half-width of the thick curves.
    .map(|(x, y)| (x - 12, y - 12, x + tw + 12, y + th + 12));
    let b = placer
        .take(corners, frame)
        .or_else(|| placer.take_least_crossing(corners, frame))
        .unwrap_or(corners[0]);
    root.draw(&Text::new(
        energy,
        (b.0 + 12, b.1 + 12),
        ("sans-serif", NOTE)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Top)),
    ))?;
    Ok(())
}

/// The right panel of a cycle: contact radius against load, the steps as dots.
fn cycle_radius<DB: DrawingBackend>(
    right: &DrawingArea<DB, Shift>,
    c: &crate::cycle::Cycle,
    (ymin, ymax): (f64, f64),
    faint: ShapeStyle,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    use crate::cycle::Phase;
    let steps = |ph: Phase| -> Vec<&crate::cycle::Step> {
        c.steps.iter().filter(|s| s.phase == ph).collect()
    };
    let contact: Vec<&crate::cycle::PathPoint> = c
        .path
        .iter()
        .filter(|p| p.branch == crate::cycle::Branch::Contact)
        .collect();
    let amax = contact.iter().map(|p| p.a).fold(0.0, f64::max) * 1.05;
    let mut ch = builder(right, "contact radius against load")
        .build_cartesian_2d(ymin * 1.15 - 0.05..ymax * 1.05 + 0.05, 0.0..amax)?;
    house_mesh(ch.configure_mesh(), "load  \\bar{P}", "contact radius  A")
        .x_label_formatter(&|v| super::linear_label(*v))
        .y_label_formatter(&|v| super::linear_label(*v))
        .draw()?;
    ch.draw_series(LineSeries::new(
        contact.iter().map(|p| (p.load, p.a)),
        faint,
    ))?;
    for (ph, col, r) in [(Phase::Retract, ORANGE_, 8), (Phase::Approach, BLUE_, 4)] {
        let pts: Vec<(f64, f64)> = steps(ph)
            .iter()
            .filter(|s| s.point.branch == crate::cycle::Branch::Contact)
            .map(|s| (s.point.load, s.point.a))
            .collect();
        ch.draw_series(pts.iter().map(|&p| Circle::new(p, r, col.filled())))?;
    }
    Ok(())
}

/// Pressure (top) and surface gap (bottom) against r for the models of a profile: MD bold
/// black, Hertz, DMT and JKR in colour; the Dugdale zone's edge c and range h0 dashed.
pub fn profile<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    p: &crate::profile::Profile,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let si = p.units == "SI";
    let md = &p.models[0];
    let (top, bottom) = root.split_vertically(root.dim_in_pixel().1 / 2);
    let r_max = md.r.last().copied().unwrap_or(1.0);
    let (ru, pu, gu) = if si {
        ("r (m)", "pressure p (Pa)", "gap h (m)")
    } else {
        (
            "r/(πwR²/K)^{1/3}",
            "pressure  p/(πwK²/R)^{1/3}",
            "gap  h/(π²w²R/K²)^{1/3}",
        )
    };
    let colour = profile_style;
    // Pressure range: the MD and closed-form values; JKR's singular tension (infinite at r = a)
    // leaves the axes a little below the Dugdale stress.
    let finite = |m: &crate::profile::ModelProfile| -> Vec<f64> {
        m.pressure.iter().flatten().copied().collect()
    };
    let p_hi = p.models.iter().flat_map(finite).fold(0.0f64, f64::max) * 1.1;
    let p_lo = -1.4 * p.dugdale_stress.max(0.3 * p_hi);
    let title = if si {
        format!(
            "Inside the contact: λ = {:.4}, load {:.3e} N",
            p.lambda, md.load
        )
    } else {
        format!(
            "Inside the contact: λ = {}, load {}",
            crate::solver::domain::short(p.lambda),
            crate::solver::domain::short(md.load)
        )
    };
    let mut chart = builder(&top, &title).build_cartesian_2d(0.0..r_max, p_lo..p_hi)?;
    house_mesh(chart.configure_mesh(), ru, pu)
        .y_label_formatter(&|v| super::linear_label(*v))
        .x_label_formatter(&|v| super::linear_label(*v))
        .draw()?;
    for m in p
        .models
        .iter()
        .filter(|m| m.status == crate::profile::ProfileStatus::Ok)
    {
        let (col, w) = colour(m.model);
        let st = ShapeStyle::from(&col).stroke_width(w);
        // Split at missing values (JKR's singular point), clamp into the plotted range.
        let mut seg: Vec<(f64, f64)> = Vec::new();
        let mut segs = Vec::new();
        for (&r, q) in m.r.iter().zip(&m.pressure) {
            match q {
                Some(q) if (p_lo..=p_hi).contains(q) => seg.push((r, *q)),
                _ => segs.push(std::mem::take(&mut seg)),
            }
        }
        segs.push(seg);
        let mut first = true;
        for s in segs.into_iter().filter(|s| s.len() > 1) {
            let series = chart.draw_series(LineSeries::new(s, st))?;
            if first {
                series.label(m.model.label()).legend(sample(st));
                first = false;
            }
        }
    }
    if let Some(c) = md.c {
        chart.draw_series(DashedLineSeries::new(
            vec![(c, p_lo), (c, p_hi)],
            16,
            12,
            ShapeStyle::from(&BLACK.mix(0.5)).stroke_width(2),
        ))?;
    }
    super::legend(&mut chart, SeriesLabelPosition::UpperRight, NOTE)?;

    profile_gaps(&bottom, p, r_max, (ru, gu))
}

/// The line of a model in the profile figure: MD (or two zones) bold black, the closed forms
/// thin in colour.
fn profile_style(m: ContactModel) -> (RGBColor, u32) {
    match m {
        ContactModel::Md | ContactModel::SolidAndMeniscus => (BLACK, 4),
        m => (model_colour(m), 2),
    }
}

/// The profile figure's lower panel: the gap of each model against r, the Dugdale range and the
/// MD zone's edge c dashed.
fn profile_gaps<DB: DrawingBackend>(
    bottom: &DrawingArea<DB, Shift>,
    p: &crate::profile::Profile,
    r_max: f64,
    (ru, gu): (&str, &str),
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let md = &p.models[0];
    let colour = profile_style;
    let g_hi = p
        .models
        .iter()
        .flat_map(|m| m.gap.iter().copied())
        .fold(p.dugdale_range * 1.5, f64::max)
        * 1.05;
    let mut chart = builder(bottom, "").build_cartesian_2d(0.0..r_max, 0.0..g_hi)?;
    house_mesh(chart.configure_mesh(), ru, gu)
        .y_label_formatter(&|v| super::linear_label(*v))
        .x_label_formatter(&|v| super::linear_label(*v))
        .draw()?;
    for m in p
        .models
        .iter()
        .filter(|m| m.status == crate::profile::ProfileStatus::Ok)
    {
        let (col, w) = colour(m.model);
        let st = ShapeStyle::from(&col).stroke_width(w);
        chart.draw_series(LineSeries::new(
            m.r.iter().copied().zip(m.gap.iter().copied()),
            st,
        ))?;
    }
    let dashed = ShapeStyle::from(&BLACK.mix(0.5)).stroke_width(2);
    chart.draw_series(DashedLineSeries::new(
        vec![(0.0, p.dugdale_range), (r_max, p.dugdale_range)],
        16,
        12,
        dashed,
    ))?;
    chart.draw_series(std::iter::once(Text::new(
        "Dugdale range h_{0}",
        (0.02 * r_max, p.dugdale_range + 0.06 * g_hi),
        ("sans-serif", NOTE).into_font(),
    )))?;
    if let Some(c) = md.c {
        chart.draw_series(DashedLineSeries::new(
            vec![(c, 0.0), (c, g_hi)],
            16,
            12,
            dashed,
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            "c (MD)",
            (c, 0.92 * g_hi),
            ("sans-serif", NOTE).into_font(),
        )))?;
    }
    Ok(())
}

/// One measured force curve (baseline removed) with the Maugis-Dugdale, Hertz, DMT and JKR fits,
/// and below it the residuals of each.
pub fn fit<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curve: &crate::fit::Curve,
    r: &crate::fit::CurveFit,
    opt: &crate::fit::FitOptions,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let d = crate::fit::prepare(curve, opt).map_err(|(_, m)| m)?;
    let md = r.md.as_ref().ok_or("no Maugis-Dugdale fit")?;
    let (top, bottom) = root.split_vertically(root.dim_in_pixel().1 * 2 / 3);
    let v = FitView::new(&d, md);
    let (hs, dirs): (Vec<f64>, Vec<crate::fit::Direction>) = model_heights(&d, 600)
        .into_iter()
        .filter(|(hh, _)| v.x(*hh) <= v.xmax)
        .unzip();
    let (lo, hi) = fit_force_range(md, opt, (&hs, &dirs), &v);
    let mut chart = builder(&top, "").build_cartesian_2d(v.xmin..v.xmax, lo * 1e9..hi * 1e9)?;
    house_mesh(chart.configure_mesh(), "", "force F (nN)")
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| super::linear_label(*v))
        .y_label_formatter(&|v| super::linear_label(*v))
        .draw()?;
    let dot = ShapeStyle::from(&RGBColor(150, 150, 150)).filled();
    chart
        .draw_series(
            d.height
                .iter()
                .zip(&d.force)
                .filter(|(&hh, _)| v.x(hh) <= v.xmax)
                .map(|(&hh, &f)| Circle::new((v.x(hh), f * 1e9), 5, dot)),
        )?
        .label("measured")
        .legend(move |(x, y)| Circle::new((x + 20, y), 6, dot));
    let mut residuals: Vec<(Vec<(f64, f64)>, RGBColor)> = Vec::new();
    for (m, col, label) in fitted_models(md, r, opt.tip.is_some()).iter().rev() {
        let p = m.params();
        let model = |h: &[f64], dir: &[crate::fit::Direction], side| {
            crate::fit::fitted_forces(m, opt, h, dir, side).map(|(f, _, _, _)| f)
        };
        let Some(f) = model(&hs, &dirs, None) else {
            continue;
        };
        let md_line = m.model == crate::fit::Model::Md;
        let st = ShapeStyle::from(col).stroke_width(if md_line { 6 } else { 4 });
        let rms = format!("{label}: rms {:.2e} N", m.rms_residual_n);
        let pts = |dir| -> Vec<(f64, f64)> {
            let by_dir = hs
                .iter()
                .zip(&dirs)
                .zip(&f)
                .filter(|((_, &dd), _)| dd == dir);
            by_dir
                .map(|((&hh, _), &ff)| (v.x(hh), (ff + p.f0) * 1e9))
                .collect()
        };
        let mut label = Some(rms);
        for dir in [
            crate::fit::Direction::Approach,
            crate::fit::Direction::Retract,
        ] {
            let pts = pts(dir);
            if pts.is_empty() {
                continue;
            }
            // Maugis-Dugdale solid, the closed forms dashed; one legend entry per model.
            match (md_line, label.take()) {
                (true, l) => {
                    let s = chart.draw_series(LineSeries::new(pts, st))?;
                    if let Some(l) = l {
                        s.label(l).legend(sample(st));
                    }
                }
                (false, l) => {
                    let s = chart.draw_series(DashedLineSeries::new(pts, 14, 8, st))?;
                    if let Some(l) = l {
                        s.label(l).legend(sample_dashed(st));
                    }
                }
            }
        }
        if let Some(fd) = model(&d.height, &d.dir, Some(&d.side)) {
            let res = d.height.iter().zip(&fd).zip(&d.force);
            let res = res.map(|((&hh, &fm), &fo)| (v.x(hh), (fo - fm - p.f0) * 1e9));
            residuals.push((res.collect(), *col));
        }
    }
    super::legend(&mut chart, SeriesLabelPosition::UpperRight, NOTE)?;
    fit_residuals(&bottom, &v, &residuals, md.rms_residual_n)
}

/// The force axis of a fit's figure (N): the data, padded, and the fitted MD curve where it
/// reaches beyond them (a model jump-out later than the measured one), so that no line runs
/// along the frame.
fn fit_force_range(
    md: &crate::fit::ModelFit,
    opt: &crate::fit::FitOptions,
    (hs, dirs): (&[f64], &[crate::fit::Direction]),
    v: &FitView,
) -> (f64, f64) {
    let pad = 0.06 * (v.fmax - v.fmin);
    let p = md.params();
    let md_f = crate::fit::model_forces(md.model, &p, opt.geometry(), opt.spring, hs, dirs, None);
    let (lo, hi) = md_f.map_or((v.fmin, v.fmax), |(f, _, _, _)| {
        f.iter()
            .filter(|x| x.is_finite())
            .fold((v.fmin, v.fmax), |(a, b), &x| {
                (a.min(x + p.f0), b.max(x + p.f0))
            })
    });
    (lo.min(v.fmin - pad), hi.max(v.fmax + pad))
}

/// The plotted window of a fitted curve: heights relative to the fitted contact point in nm,
/// forces in N.
struct FitView {
    zc: f64,
    xmin: f64,
    xmax: f64,
    fmin: f64,
    fmax: f64,
}

impl FitView {
    /// The contact and the jump fill the width: the far baseline is cut to half the width of
    /// the part where the force is off zero (beyond 5% of its range).
    fn new(d: &crate::fit::Prepared, md: &crate::fit::ModelFit) -> FitView {
        let zc = md.contact_point_m;
        let x = |hgt: f64| (hgt - zc) * 1e9;
        let span = |it: &mut dyn Iterator<Item = f64>| {
            it.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            })
        };
        let (xmin, xall) = span(&mut d.height.iter().map(|&v| x(v)));
        let off = |f: f64| (f - md.force_offset_n).abs();
        let frange = d.force.iter().fold(0.0f64, |m, &f| m.max(off(f)));
        let active = d
            .height
            .iter()
            .zip(&d.force)
            .filter(|(_, &f)| off(f) > 0.05 * frange)
            .map(|(&hh, _)| x(hh))
            .fold(xmin, f64::max);
        let xmax = xall.min(active + 0.6 * (active - xmin).max(1e-3));
        let (fmin, fmax) = span(&mut d.force.iter().copied());
        FitView {
            zc,
            xmin,
            xmax,
            fmin,
            fmax,
        }
    }

    fn x(&self, height: f64) -> f64 {
        (height - self.zc) * 1e9
    }
}

/// A dense grid of `n` heights along each fitted segment, in time order (the approach descends,
/// the retract climbs), for the model curves.
fn model_heights(d: &crate::fit::Prepared, n: usize) -> Vec<(f64, crate::fit::Direction)> {
    use crate::fit::Direction;
    let mut out = Vec::new();
    for dir in [Direction::Approach, Direction::Retract] {
        if !d.dir.contains(&dir) {
            continue;
        }
        let (lo, hi) = d
            .height
            .iter()
            .zip(&d.dir)
            .filter(|(_, &dd)| dd == dir)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (&v, _)| {
                (a.min(v), b.max(v))
            });
        for i in 0..n {
            let t = i as f64 / (n - 1) as f64;
            let h = if dir == Direction::Approach {
                hi - t * (hi - lo)
            } else {
                lo + t * (hi - lo)
            };
            out.push((h, dir));
        }
    }
    out
}

/// The fits drawn, Maugis-Dugdale first (black), then each closed form that fitted, with its
/// colour and name.
fn fitted_models<'a>(
    md: &'a crate::fit::ModelFit,
    r: &'a crate::fit::CurveFit,
    tip: bool,
) -> Vec<(&'a crate::fit::ModelFit, RGBColor, &'static str)> {
    let ok = r
        .models
        .iter()
        .filter(|m| m.status == crate::fit::FitStatus::Ok);
    // The two-zone law fitted to a humid curve's shape, where it was.
    let wet = r
        .humidity
        .as_ref()
        .and_then(|h| h.shape_fit.as_ref())
        .map(|s| &s.fit)
        .filter(|m| m.status == crate::fit::FitStatus::Ok);
    // A tip's closed forms are its own: Sneddon's punch and the JKR-type law.
    let label = |m: crate::fit::Model| match (tip, m) {
        (true, crate::fit::Model::Hertz) => "Sneddon's punch",
        (true, crate::fit::Model::Jkr) => "JKR-type",
        _ => m.label(),
    };
    let closed = ok
        .chain(wet)
        .map(|m| (m, model_colour(m.model.into()), label(m.model)));
    std::iter::once((md, RGBColor(0, 0, 0), "Maugis-Dugdale"))
        .chain(closed)
        .collect()
}

/// The residuals panel below a fit: Maugis-Dugdale's (black, last) over those of the closed
/// forms, the axis spanning MD's residuals and at least three of its rms.
fn fit_residuals<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    v: &FitView,
    residuals: &[(Vec<(f64, f64)>, RGBColor)],
    md_rms: f64,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let md_res = &residuals.last().ok_or("no residuals")?.0;
    let span = md_res
        .iter()
        .fold(0.0f64, |m, p| m.max(p.1.abs()))
        .max(1e-30)
        * 1.3;
    let span = span.max(3.0 * md_rms * 1e9);
    let mut rc = builder(area, "").build_cartesian_2d(v.xmin..v.xmax, -span..span)?;
    house_mesh(
        rc.configure_mesh(),
        "base height above the contact point (nm)",
        "residual (nN)",
    )
    .x_labels(6)
    .y_labels(4)
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    for (pts, col) in residuals {
        let st = ShapeStyle::from(col).filled();
        let r = if *col == RGBColor(0, 0, 0) { 4 } else { 3 };
        rc.draw_series(
            pts.iter()
                .filter(|p| p.1.abs() <= span && p.0 <= v.xmax)
                .map(|&p| Circle::new(p, r, st)),
        )?;
    }
    Ok(())
}

/// One quantity of a force map: a pixel per curve, coloured with viridis (log10 where `log`),
/// grey where the curve was not fitted, with its colorbar.
pub fn force_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    values: &[f64],
    nx: usize,
    ny: usize,
    title: &str,
    log: bool,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let t = |v: f64| if log { v.log10() } else { v };
    let shown: Vec<f64> = values
        .iter()
        .map(|&v| {
            if v.is_finite() && (!log || v > 0.0) {
                t(v)
            } else {
                f64::NAN
            }
        })
        .collect();
    let (mut lo, mut hi) = shown
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (0.0, 1.0);
    }
    if hi - lo < 1e-12 * lo.abs().max(1e-300) || hi == lo {
        let d = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
        (lo, hi) = (lo - d, hi + d);
    }
    let (w, _) = root.dim_in_pixel();
    let bar_w = (TICK * 5.4) as u32;
    let (left, bar) = root.split_horizontally(w - bar_w);
    pixel_grid(&left, title, nx, ny, |k| {
        let v = shown[k];
        if v.is_finite() {
            super::viridis((v - lo) / (hi - lo))
        } else {
            RGBColor(200, 200, 200)
        }
    })?;
    // Log scale over a decade or more: powers of ten; over less, round values at their places.
    let ticks: Vec<(f64, String)> = if log && hi - lo >= 1.0 {
        super::round_ticks(lo, hi)
            .into_iter()
            .map(|v| (v, super::power_label(v)))
            .collect()
    } else if log {
        let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
        let unit = 10f64.powf(b.log10().floor());
        super::round_ticks(a / unit, b / unit)
            .into_iter()
            .filter(|&v| v > 0.0)
            .map(|v| ((v * unit).log10(), compact(v * unit)))
            .collect()
    } else {
        // round_ticks works on values of order one: scale by the power of ten of the range.
        let unit = 10f64.powf(lo.abs().max(hi.abs()).log10().floor());
        super::round_ticks(lo / unit, hi / unit)
            .into_iter()
            .map(|v| (v * unit, compact(v * unit)))
            .collect()
    };
    super::colorbar(&bar, lo, hi, &ticks)
}

/// A force map's chart: one cell a pixel (row-major, row 0 at the bottom), coloured by
/// `colour(k)`, with pixel-index axes.
fn pixel_grid<'a, DB: DrawingBackend + 'a>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    nx: usize,
    ny: usize,
    colour: impl Fn(usize) -> RGBColor,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    Err,
>
where
    DB::ErrorType: 'static,
{
    let mut chart = builder(area, title).build_cartesian_2d(0.0..nx as f64, 0.0..ny as f64)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x (pixel)")
        .y_desc("y (pixel)")
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK))
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| format!("{v:.0}"))
        // The top label would run into the title.
        .y_label_formatter(&|v| {
            if *v >= ny as f64 {
                String::new()
            } else {
                format!("{v:.0}")
            }
        })
        .draw()?;
    chart.draw_series((0..nx * ny).map(|k| {
        let (x, y) = ((k % nx) as f64, (k / nx) as f64);
        Rectangle::new([(x, y), (x + 1.0, y + 1.0)], colour(k).filled())
    }))?;
    Ok(chart)
}

/// A colorbar label, short: 0.055, 120, 4.5e-9, 1.995e9.
fn compact(v: f64) -> String {
    let a = v.abs();
    let s = if v == 0.0 {
        "0".to_string()
    } else if (1e-2..1e4).contains(&a) {
        let t = format!("{v:.3}");
        let t = t.trim_end_matches('0').trim_end_matches('.').to_string();
        t
    } else {
        // Enough digits to tell neighbouring round ticks apart (1.995e9, 2e9), no more.
        let t = format!("{v:.4e}");
        let (m, e) = t.split_once('e').unwrap_or((&t, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{m}e{e}")
    };
    super::minus(&s)
}

/// The adequate model of each curve of a force map, in the adhesion map's region colours.
pub fn model_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    models: &[Option<crate::fit::Model>],
    nx: usize,
    ny: usize,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    use crate::fit::Model;
    use crate::map::Region;
    root.fill(&WHITE)?;
    let colour = |m: Model| {
        let region = Region::ALL
            .into_iter()
            .find(|r| r.model() == Some(m.into()));
        super::map::region_color(region.unwrap_or(Region::Failed))
    };
    let mut chart = pixel_grid(
        root,
        "The simplest adequate model of each curve",
        nx,
        ny,
        |k| models[k].map_or(RGBColor(255, 255, 255), colour),
    )?;
    for m in Model::ALL {
        let c = colour(m);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(m.label())
            .legend(move |(x, y)| Rectangle::new([(x + 4, y - 12), (x + 34, y + 12)], c.filled()));
    }
    super::legend(&mut chart, SeriesLabelPosition::UpperRight, NOTE)?;
    Ok(())
}

/// The colour of each pixel status ([`crate::fit::PIXEL_STATUSES`]): fitted blue, each
/// failure its own hue, an empty pixel white.
const STATUS_COLOURS: [RGBColor; 5] = [
    BLUE_,
    PURPLE_,
    RGBColor(190, 190, 190),
    ORANGE_,
    RGBColor(255, 255, 255),
];

/// How each curve of a force map ended (the index of [`crate::fit::PIXEL_STATUSES`] per
/// pixel), with the count of each status in the legend.
pub fn status_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    statuses: &[usize],
    nx: usize,
    ny: usize,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let mut chart = pixel_grid(root, "How each curve's fit ended", nx, ny, |k| {
        STATUS_COLOURS[statuses[k]]
    })?;
    for (i, name) in crate::fit::PIXEL_STATUSES.iter().enumerate() {
        let n = statuses.iter().filter(|&&s| s == i).count();
        if n == 0 {
            continue;
        }
        let c = STATUS_COLOURS[i];
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(format!("{} ({n})", name.replace('_', " ")))
            .legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + Rectangle::new([(4, -12), (34, 12)], c.filled())
                    + Rectangle::new([(4, -12), (34, 12)], BLACK.mix(0.5))
            });
    }
    super::legend(&mut chart, SeriesLabelPosition::UpperRight, NOTE)?;
    Ok(())
}

/// A force map's summary in six panels: each quantity's histogram over the fitted pixels (log
/// bins drawn on a log10 axis), then the pixels of each adequate model and each status.
pub fn map_histograms<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    summary: &crate::fit::MapSummary,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    // The statuses of every pixel head the figure.
    let statuses = crate::fit::PIXEL_STATUSES
        .iter()
        .filter(|s| summary.status[*s] > 0)
        .map(|s| format!("{} {}", summary.status[s], s.replace('_', " ")))
        .collect::<Vec<_>>()
        .join(", ");
    let root = root.titled(
        &format!("{} x {} pixels: {statuses}", summary.nx, summary.ny),
        ("sans-serif", TITLE),
    )?;
    let (w, h) = root.dim_in_pixel();
    let (rows, cols) = if w as f64 / h as f64 > 1.2 {
        (2, 3)
    } else {
        (3, 2)
    };
    let panels = root.split_evenly((rows, cols));
    for (q, area) in summary.quantities.iter().zip(&panels) {
        let m = crate::fit::MAP_QUANTITIES
            .iter()
            .find(|m| m.name == q.name)
            .expect("a map quantity");
        // The maps' labels without their notes on grey pixels.
        let label = m.label.split(" (").next().unwrap_or(m.label);
        let title = if m.needs_lambda {
            format!(
                "{label} ({} of {} determined)",
                q.count,
                q.count + q.missing
            )
        } else {
            label.to_string()
        };
        histogram_panel(area, &title, m.unit, m.prefixed, q)?;
    }
    let models: Vec<(String, usize, RGBColor)> = crate::fit::Model::ALL
        .iter()
        .map(|m| {
            let region = crate::map::Region::ALL
                .into_iter()
                .find(|r| r.model() == Some((*m).into()));
            // Short names: five bars share a narrow panel.
            let short = match m {
                crate::fit::Model::Hertz => "Hertz",
                crate::fit::Model::Dmt => "DMT",
                crate::fit::Model::Jkr => "JKR",
                _ => "MD",
            };
            (
                short.to_string(),
                summary.adequate_model[m.name()],
                super::map::region_color(region.unwrap_or(crate::map::Region::Failed)),
            )
        })
        .chain([("none".to_string(), summary.adequate_model["none"], GRAY_)])
        .collect();
    count_panel(&panels[5], "adequate model (fitted pixels)", &models)?;
    Ok(())
}

/// One quantity's histogram: bars over its bins, the x axis in log10 where the bins are (else
/// in the unit with an SI prefix suited to the values, where it takes one), the median a line.
fn histogram_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    unit: &str,
    prefixed: bool,
    q: &crate::fit::QuantitySummary,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let largest = q.edges.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (scale, si) = if prefixed && !q.log_bins {
        crate::render::si_prefix(largest)
    } else {
        (1.0, "")
    };
    let log = q.log_bins;
    let t = move |v: f64| if log { v.log10() } else { v / scale };
    let (lo, hi) = match (q.edges.first(), q.edges.last()) {
        (Some(&a), Some(&b)) => (t(a), t(b)),
        _ => (0.0, 1.0),
    };
    let top = q.counts.iter().copied().max().unwrap_or(0).max(1) as f64 * 1.1;
    let desc = if unit.is_empty() {
        String::new()
    } else {
        format!("{si}{unit}")
    };
    let mut chart = builder(area, title).build_cartesian_2d(lo..hi, 0.0..top)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(desc)
        .y_desc("pixels")
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK))
        .x_labels(3)
        .y_labels(4)
        .x_label_formatter(&|v| {
            if log {
                super::power_label(*v)
            } else {
                compact(*v)
            }
        })
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    if q.counts.is_empty() {
        chart.draw_series(std::iter::once(Text::new(
            "no fitted pixel",
            (lo + 0.3 * (hi - lo), 0.5 * top),
            ("sans-serif", NOTE).into_font(),
        )))?;
        return Ok(());
    }
    chart.draw_series(q.counts.iter().enumerate().map(|(i, &n)| {
        let (a, b) = (t(q.edges[i]), t(q.edges[i + 1]));
        Rectangle::new([(a, 0.0), (b, n as f64)], BLUE_.mix(0.75).filled())
    }))?;
    if let Some(m) = q.quantiles {
        let x = t(m.median);
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(x, 0.0), (x, top)],
            BLACK.stroke_width(2),
        )))?;
    }
    Ok(())
}

/// Counts of named classes as coloured bars, one a row (the names read across).
fn count_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    bars: &[(String, usize, RGBColor)],
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let top = bars.iter().map(|b| b.1).max().unwrap_or(0).max(1) as f64 * 1.15;
    let n = bars.len();
    let mut chart =
        builder(area, title).build_cartesian_2d(0.0..top, (0..n - 1).into_segmented())?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("pixels")
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK))
        .x_labels(4)
        .y_labels(n)
        .x_label_formatter(&|v| format!("{v:.0}"))
        // The first bar at the top.
        .y_label_formatter(&|v| match v {
            SegmentValue::CenterOf(i) if *i < n => bars[n - 1 - *i].0.clone(),
            _ => String::new(),
        })
        .draw()?;
    chart.draw_series(bars.iter().enumerate().map(|(i, b)| {
        let row = n - 1 - i;
        Rectangle::new(
            [
                (0.0, SegmentValue::Exact(row)),
                (b.1 as f64, SegmentValue::Exact(row + 1)),
            ],
            b.2.filled(),
        )
    }))?;
    Ok(())
}

/// Every fitted curve on the adhesion map: at its lambda, a bar over the normalised loads its
/// fitted segment spans in contact, coloured by its adequate model.
pub fn fits_on_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &crate::map::MapData,
    results: &[crate::fit::CurveFit],
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let n = results
        .iter()
        .filter(|r| r.status == crate::fit::FitStatus::Ok)
        .count();
    let mut ch = super::map::inset(
        root,
        d,
        &format!("{n} fitted curves on the map (grey: λ not determined)"),
    )?;
    let sp = &d.spec;
    // Curves whose lambda the data do not determine (standard error above lambda) in grey,
    // under the others.
    let sure = ShapeStyle::from(&BLACK.mix(0.7)).stroke_width(3);
    let unsure = ShapeStyle::from(&RGBColor(150, 150, 150).mix(0.6)).stroke_width(2);

    let mut ok: Vec<&crate::fit::CurveFit> = results
        .iter()
        .filter(|r| r.status == crate::fit::FitStatus::Ok)
        .collect();
    ok.sort_by_key(|r| r.lambda_determined());
    for r in ok {
        let (Some(l), Some([a, b])) = (r.lambda, r.load_range_normalised) else {
            continue;
        };
        let l = l.clamp(sp.lambda_min, sp.lambda_max);
        let (a, b) = (
            a.clamp(sp.load_min, sp.load_max),
            b.clamp(sp.load_min, sp.load_max),
        );
        let st = if r.lambda_determined() { sure } else { unsure };
        ch.draw_series(LineSeries::new(vec![(l, a), (l, b)], st))?;
        ch.draw_series(std::iter::once(Circle::new((l, b), 6, st.color.filled())))?;
    }
    Ok(())
}

/// Pull-off force (magnitude, load control) against relative humidity: the dry solid, the
/// meniscus alone and both together (two Dugdale zones), with the humidity above which the
/// meniscus adds more than half.
pub fn humidity<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &crate::scene::humidity::HumiditySweep,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let pts = &r.points;
    let (x0, x1) = (
        100.0 * pts[0].relative_humidity,
        100.0 * pts[pts.len() - 1].relative_humidity,
    );
    let fmax = pts
        .iter()
        .map(|p| {
            p.pulloff_total_N
                .abs()
                .max(p.pulloff_solid_N.abs())
                .max(p.pulloff_meniscus_N.abs())
        })
        .fold(0.0, f64::max)
        * 1.5;
    let (fu, fp) = super::si_prefix(fmax);
    let mut chart = builder(root, &r.name).build_cartesian_2d(x0..x1, 0.0..fmax / fu)?;
    house_mesh(
        chart.configure_mesh(),
        "relative humidity  (%)",
        format!("pull-off force  |P_{{c}}| ({fp}N)"),
    )
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    let thick = |c: RGBColor| ShapeStyle::from(&c).stroke_width(8);
    for (label, color, f) in [
        (
            "solid and meniscus",
            BLUE_,
            &(|p: &crate::scene::humidity::HumidityPoint| p.pulloff_total_N)
                as &dyn Fn(&crate::scene::humidity::HumidityPoint) -> f64,
        ),
        ("meniscus alone", GREEN_, &|p| p.pulloff_meniscus_N),
        ("solid alone (dry)", ORANGE_, &|p| p.pulloff_solid_N),
    ] {
        chart
            .draw_series(LineSeries::new(
                pts.iter()
                    .map(|p| (100.0 * p.relative_humidity, f(p).abs() / fu)),
                thick(color),
            ))?
            .label(label)
            .legend(sample(thick(color)));
    }
    if let Some(rh) = r.meniscus_dominates_above_rh {
        let x = 100.0 * rh;
        if x > x0 {
            chart.draw_series(DashedLineSeries::new(
                vec![(x, 0.0), (x, fmax / fu)],
                8,
                12,
                ShapeStyle::from(&GRAY_).stroke_width(3),
            ))?;
            chart.draw_series(std::iter::once(Text::new(
                "meniscus > half",
                (x + 0.01 * (x1 - x0), 0.05 * fmax / fu),
                ("sans-serif", NOTE)
                    .into_font()
                    .color(&GRAY_)
                    .pos(Pos::new(HPos::Left, VPos::Bottom)),
            )))?;
        }
    }
    // The legend in the band above the curves (the axis reaches 1.5 times the largest force).
    let (lx, ly) = chart.backend_coord(&(x0 + 0.03 * (x1 - x0), 0.98 * fmax / fu));
    let (px, py) = chart.plotting_area().get_pixel_range();
    let at = SeriesLabelPosition::Coordinate(lx - px.start, ly - py.start);
    super::legend(&mut chart, at, NOTE)?;
    Ok(())
}
