//! Line plots for the gallery: pull-off against lambda, and A(P) curves.

use super::log_label;
use crate::physics::closed::{
    cos_pulloff, dmt_radius, hertz_radius, jkr_radius, JKR_PULLOFF_DISPLACEMENT, JKR_PULLOFF_LOAD,
};
use crate::physics::md::LAMBDA_D;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

type Err = Box<dyn std::error::Error + Send + Sync>;
pub const W: u32 = 1400;
pub const H: u32 = 1000;

/// A figure's drawing code, on the SVG backend (the PNG is that SVG rasterised).
pub type DrawSvg<'a> = &'a dyn for<'b> Fn(&DrawingArea<SVGBackend<'b>, Shift>) -> Result<(), Err>;

/// Draws with `g` as an SVG document of W x H, and rasterises it with anti-aliasing into PNG
/// bytes, as asked.
pub fn render(png: bool, svg: bool, g: DrawSvg) -> Result<(Option<Vec<u8>>, Option<String>), Err> {
    super::draw_figure((W, H), png, svg, |root| g(root))
}

/// Draws with `g` into a PNG file and/or an SVG file of W x H.
pub fn save(png: Option<&Path>, svg: Option<&Path>, g: DrawSvg) -> Result<(), Err> {
    let (png_bytes, svg_text) = render(png.is_some(), svg.is_some(), g)?;
    if let (Some(p), Some(b)) = (png, png_bytes) {
        crate::io::write_output(p, &b)?;
    }
    if let (Some(p), Some(s)) = (svg, svg_text) {
        crate::io::write_output(p, s.as_bytes())?;
    }
    Ok(())
}

const BLUE_: RGBColor = RGBColor(0, 114, 178);
const ORANGE_: RGBColor = RGBColor(213, 94, 0);
const GREEN_: RGBColor = RGBColor(0, 158, 115);
const GRAY_: RGBColor = RGBColor(120, 120, 120);

/// Pull-off force against lambda under load and displacement control, with the DMT/Bradley and
/// JKR limits and the Johnson-Greenwood fit.
pub fn pulloff<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &crate::figure_data::PulloffData,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (lambdas, ctx) = (&data.lambdas, &data.contexts);
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Pull-off force against the Maugis parameter",
            ("sans-serif", 34),
        )
        .margin(24)
        .x_label_area_size(80)
        .y_label_area_size(100)
        .build_cartesian_2d((1e-4..1e4f64).log_scale(), -2.1..-0.7f64)?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc("Maugis parameter  λ")
        .y_desc("pull-off load  P / (π w R)")
        .axis_desc_style(("sans-serif", 28))
        .label_style(("sans-serif", 22))
        .x_label_formatter(&|v| log_label(*v))
        .draw()?;
    let thick = |c: RGBColor| ShapeStyle::from(&c).stroke_width(4);
    chart
        .draw_series(LineSeries::new(
            lambdas
                .iter()
                .zip(ctx)
                .map(|(&l, c)| (l, c.load_pulloff.load)),
            thick(BLUE_),
        ))?
        .label("Maugis-Dugdale, load control (dead load)")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], thick(BLUE_)));
    chart
        .draw_series(LineSeries::new(
            lambdas
                .iter()
                .zip(ctx)
                .map(|(&l, c)| (l, c.disp_pulloff.load)),
            thick(ORANGE_),
        ))?
        .label("Maugis-Dugdale, displacement control (rigid grips)")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], thick(ORANGE_)));
    chart
        .draw_series(DashedLineSeries::new(
            lambdas.iter().map(|&l| (l, cos_pulloff(l))),
            10,
            8,
            ShapeStyle::from(&GREEN_).stroke_width(3),
        ))?
        .label("Johnson-Greenwood fit (COS), load control")
        .legend(move |(x, y)| {
            PathElement::new(
                vec![(x, y), (x + 30, y)],
                ShapeStyle::from(&GREEN_).stroke_width(3),
            )
        });
    let gray = ShapeStyle::from(&GRAY_).stroke_width(2);
    for (y, text) in [
        (-2.0, "DMT / Bradley: −2"),
        (JKR_PULLOFF_LOAD, "JKR, load control: −3/2"),
        (JKR_PULLOFF_DISPLACEMENT, "JKR, displacement control: −5/6"),
    ] {
        chart.draw_series(DashedLineSeries::new(vec![(1e-4, y), (1e4, y)], 6, 6, gray))?;
        chart.draw_series(std::iter::once(Text::new(
            text,
            (2e-4, y + 0.045),
            ("sans-serif", 20).into_font().color(&GRAY_),
        )))?;
    }
    chart.draw_series(DashedLineSeries::new(
        vec![(LAMBDA_D, -2.1), (LAMBDA_D, -0.7)],
        4,
        6,
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    chart.draw_series(std::iter::once(Text::new(
        "λ_D = 0.938: below it, rigid grips lose contact at zero radius",
        (LAMBDA_D * 1.15, -0.75),
        ("sans-serif", 20).into_font(),
    )))?;
    super::legend(&mut chart, SeriesLabelPosition::LowerRight, 22)?;
    Ok(())
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
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Contact radius against load: Maugis-Dugdale and the closed forms",
            ("sans-serif", 32),
        )
        .margin(24)
        .x_label_area_size(80)
        .y_label_area_size(90)
        .build_cartesian_2d(-2.2..4.0f64, 0.0..2.6f64)?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc("load  P / (π w R)")
        .y_desc("contact radius  A = a (K / (π w R²))^(1/3)")
        .axis_desc_style(("sans-serif", 26))
        .label_style(("sans-serif", 22))
        .draw()?;
    let grid: Vec<f64> = (0..=600).map(|i| -2.2 + 6.2 * i as f64 / 600.0).collect();
    let closed = [
        ("Hertz", GRAY_, hertz_radius as fn(f64) -> Option<f64>),
        ("DMT", BLUE_, dmt_radius),
        ("JKR", ORANGE_, jkr_radius),
    ];
    for (name, col, f) in closed {
        let st = ShapeStyle::from(&col).stroke_width(2);
        chart
            .draw_series(DashedLineSeries::new(
                grid.iter().filter_map(|&p| f(p).map(|a| (p, a))),
                8,
                6,
                st,
            ))?
            .label(format!("{name} (closed form)"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
    }
    let palette = [
        RGBColor(0, 0, 0),
        GREEN_,
        RGBColor(204, 121, 167),
        RGBColor(86, 180, 233),
        RGBColor(230, 159, 0),
    ];
    for (k, cs) in series.iter().enumerate() {
        let (l, pts) = (cs.lambda, &cs.points);
        let col = palette[k % palette.len()];
        let stable: Vec<(f64, f64)> = pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect();
        let unstable: Vec<(f64, f64)> = pts.iter().filter(|p| !p.2).map(|p| (p.0, p.1)).collect();
        let st = ShapeStyle::from(&col).stroke_width(4);
        chart
            .draw_series(LineSeries::new(stable, st))?
            .label(format!("Maugis-Dugdale, λ = {l}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
        chart.draw_series(DashedLineSeries::new(
            unstable,
            5,
            5,
            ShapeStyle::from(&col).stroke_width(2),
        ))?;
        chart.draw_series(std::iter::once(Circle::new(cs.pulloff, 7, col.filled())))?;
    }
    chart.draw_series(std::iter::once(Text::new(
        "dots: pull-off under load control; thin dashes: unstable branch",
        (-2.1, 0.08),
        ("sans-serif", 20).into_font(),
    )))?;
    super::legend(&mut chart, SeriesLabelPosition::UpperLeft, 22)?;
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
    let (smin, smax) = (
        speeds.iter().cloned().fold(f64::INFINITY, f64::min),
        speeds.iter().cloned().fold(0.0, f64::max),
    );
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 30))
        .margin(24)
        .x_label_area_size(80)
        .y_label_area_size(110)
        .build_cartesian_2d(
            (1e-13..3.0f64).log_scale(),
            ((smin / 3.0).max(1.0)..smax * 5.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc("max relative error of A against the exact solution")
        .y_desc("throughput (solves per second)")
        .axis_desc_style(("sans-serif", 26))
        .label_style(("sans-serif", 20))
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
            ShapeStyle::from(&GREEN_).stroke_width(3),
        ))?
        .label("Pareto front (no variant is both faster and more accurate)")
        .legend(|(x, y)| {
            PathElement::new(
                vec![(x, y), (x + 30, y)],
                ShapeStyle::from(&GREEN_).stroke_width(3),
            )
        });
    // Markers first; then each label at the first nearby spot that overlaps no marker and no
    // label placed before it (boxes in pixels; the text width is estimated from the font size).
    let mut taken: Vec<(i32, i32, i32, i32)> = Vec::new();
    for r in results {
        let (x, y) = (err(r), r.points_per_second);
        let col = if r.name.starts_with("gpu") {
            ORANGE_
        } else if r.name.starts_with("cpu") || r.name.starts_with("naive") {
            BLUE_
        } else {
            GRAY_
        };
        let style = if r.failures > 0 {
            ShapeStyle::from(&col).stroke_width(3)
        } else {
            col.filled()
        };
        chart.draw_series(std::iter::once(Circle::new((x, y), 9, style)))?;
        let (px, py) = chart.backend_coord(&(x, y));
        taken.push((px - 11, py - 11, px + 11, py + 11));
    }
    let plot = chart.plotting_area().get_pixel_range();
    let overlaps = |b: (i32, i32, i32, i32), o: &(i32, i32, i32, i32)| {
        b.0 < o.2 && o.0 < b.2 && b.1 < o.3 && o.1 < b.3
    };
    let inside = |b: &(i32, i32, i32, i32)| {
        b.0 >= plot.0.start && b.2 <= plot.0.end && b.1 >= plot.1.start && b.3 <= plot.1.end
    };
    for r in results {
        let (x, y) = (err(r), r.points_per_second);
        let label = if r.failures > 0 {
            format!("{} ({} failed)", r.name, r.failures)
        } else {
            r.name.clone()
        };
        let (px, py) = chart.backend_coord(&(x, y));
        let (w, h) = ((label.chars().count() as f64 * 9.4) as i32, 20);
        let right_first = x <= 1e-2;
        let mut spots = Vec::new();
        for dy in [0, -22, 22, -44, 44, -66, 66] {
            for right in [right_first, !right_first] {
                let x0 = if right { px + 14 } else { px - 14 - w };
                spots.push((x0, py + dy - h / 2, x0 + w, py + dy + h / 2));
            }
        }
        let spot = spots
            .iter()
            .copied()
            .find(|b| inside(b) && !taken.iter().any(|o| overlaps(*b, o)))
            .unwrap_or(spots[0]);
        taken.push(spot);
        let style = ("sans-serif", 18).into_font().color(&BLACK).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        root.draw(&Text::new(label, (spot.0, (spot.1 + spot.3) / 2), style))?;
    }
    chart.draw_series(std::iter::once(Text::new(
        "orange: GPU kernels; blue: CPU solvers; gray: closed forms; hollow: some points failed",
        (2e-13, smin / 2.2),
        ("sans-serif", 18).into_font(),
    )))?;
    super::legend(&mut chart, SeriesLabelPosition::UpperRight, 20)?;
    Ok(())
}

/// A scene: a(P) in SI units (MD bold, the recommended model dashed, the others faint) and, right,
/// the scene's lambda and loads on a small adhesion map.
pub fn scene<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &crate::scene::SceneResult,
    fig: &crate::figure_data::SceneFigure,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(W * 3 / 5);
    let (fs, rs) = (fig.force_scale, fig.radius_scale);
    let (pc, pmax) = fig.loads;
    let md = &fig.md;
    let amax = md.iter().map(|q| q.1).fold(0.0, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&left)
        .caption(&r.name, ("sans-serif", 24))
        .margin(20)
        .x_label_area_size(70)
        .y_label_area_size(100)
        .build_cartesian_2d(pc * 1.4..pmax, 0.0..amax)?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc("load P (N)")
        .y_desc("contact radius a (m)")
        .axis_desc_style(("sans-serif", 22))
        .label_style(("sans-serif", 16))
        .x_label_formatter(&|v| {
            if v.abs() < 1e-6 * pmax {
                "0".into()
            } else {
                format!("{v:.2e}")
            }
        })
        .y_label_formatter(&|v| {
            if v.abs() < 1e-6 * amax {
                "0".into()
            } else {
                format!("{v:.2e}")
            }
        })
        .draw()?;
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
    for (key, name, col, f) in closed {
        let rec = r.recommended_model == key;
        let st = if rec {
            ShapeStyle::from(&col).stroke_width(4)
        } else {
            ShapeStyle::from(&col.mix(0.35)).stroke_width(2)
        };
        let pts: Vec<(f64, f64)> = (0..=300)
            .filter_map(|i| {
                let p = pc * 1.4 + (pmax - pc * 1.4) * i as f64 / 300.0;
                f(p / fs).map(|a| (p, a * rs)).filter(|q| q.1 <= amax)
            })
            .collect();
        chart
            .draw_series(DashedLineSeries::new(pts, 8, 6, st))?
            .label(if rec {
                format!("{name} (recommended)")
            } else {
                name.to_string()
            })
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
    }
    let st = ShapeStyle::from(&BLACK).stroke_width(3);
    chart
        .draw_series(LineSeries::new(md.iter().copied(), st))?
        .label("Maugis-Dugdale (exact)")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
    for l in &r.loads {
        if let Some(a) = l.contact_radius_m {
            chart.draw_series(std::iter::once(Circle::new(
                (l.load_n, a),
                6,
                BLACK.filled(),
            )))?;
        }
    }
    super::legend(&mut chart, SeriesLabelPosition::LowerRight, 18)?;

    // Right: where the scene sits on the map (normalised loads).
    let d = &fig.map;
    let mut ch = ChartBuilder::on(&right)
        .caption("on the adhesion map", ("sans-serif", 22))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(60)
        .build_cartesian_2d((1e-3..1e3f64).log_scale(), -2.0..10.0f64)?;
    let (px, py) = ch.plotting_area().get_pixel_range();
    let (w, h) = ((px.end - px.start) as u32, (py.end - py.start) as u32);
    let mut buf = vec![0u8; (w * h * 3) as usize];
    for rr in 0..h {
        let iy = ((1.0 - (rr as f64 + 0.5) / h as f64) * 159.0).round() as usize;
        for c in 0..w {
            let ix = (((c as f64 + 0.5) / w as f64) * 159.0).round() as usize;
            let col = crate::render::map::region_color(d.region_at(ix, iy));
            let k = ((rr * w + c) * 3) as usize;
            buf[k..k + 3].copy_from_slice(&[col.0, col.1, col.2]);
        }
    }
    if let Some(el) = BitMapElement::with_owned_buffer((1e-3, 10.0), (w, h), buf) {
        ch.draw_series(std::iter::once(el))?;
    }
    ch.configure_mesh()
        .disable_mesh()
        .x_desc("λ")
        .y_desc("P / (π w R)")
        .axis_desc_style(("sans-serif", 20))
        .label_style(("sans-serif", 16))
        .x_label_formatter(&|v| log_label(*v))
        .draw()?;
    let l = r.lambda.clamp(1e-3, 1e3);
    for ld in &r.loads {
        let y = ld.load_normalised.clamp(-2.0, 10.0);
        ch.draw_series(std::iter::once(Cross::new(
            (l, y),
            8,
            BLACK.stroke_width(3),
        )))?;
    }
    ch.draw_series(std::iter::once(Text::new(
        format!("λ = {:.3}", r.lambda),
        (l.clamp(2e-3, 50.0), 9.0),
        ("sans-serif", 20).into_font(),
    )))?;
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
    let (left, right) = root.split_horizontally(W * 3 / 5);
    let steps = |ph: crate::cycle::Phase| -> Vec<&crate::cycle::Step> {
        c.steps.iter().filter(|s| s.phase == ph).collect()
    };
    let xs: Vec<f64> = c
        .path
        .iter()
        .filter(|p| p.branch != crate::cycle::Branch::Free)
        .map(|p| p.approach)
        .collect();
    let (xmin, xmax) = (
        xs.iter().cloned().fold(f64::INFINITY, f64::min),
        xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
    );
    let pad = 0.08 * (xmax - xmin);
    let (ymin, ymax) = (
        c.path.iter().map(|p| p.load).fold(0.0, f64::min),
        c.path.iter().map(|p| p.load).fold(0.0, f64::max),
    );
    let drive = match c.drive {
        crate::cycle::Drive::RigidGrips => "rigid grips".to_string(),
        crate::cycle::Drive::DeadLoad => "dead load".to_string(),
        crate::cycle::Drive::Spring(k) => format!("spring, k = {k:.3}"),
    };
    let mut chart = ChartBuilder::on(&left)
        .caption(
            format!("Approach and retract, λ = {}, {drive}", c.lambda),
            ("sans-serif", 26),
        )
        .margin(20)
        .x_label_area_size(70)
        .y_label_area_size(90)
        .build_cartesian_2d(
            xmin - pad..xmax + pad,
            ymin * 1.15 - 0.05..ymax * 1.05 + 0.05,
        )?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc("approach  δ (K² / (π² w² R))^(1/3)")
        .y_desc("load  P / (π w R)")
        .axis_desc_style(("sans-serif", 22))
        .label_style(("sans-serif", 18))
        .draw()?;
    let eq: Vec<(f64, f64)> = c
        .path
        .iter()
        .filter(|p| p.approach >= xmin - pad)
        .map(|p| (p.approach, p.load))
        .collect();
    let faint = ShapeStyle::from(&RGBColor(170, 170, 170)).stroke_width(6);
    chart
        .draw_series(LineSeries::new(eq, faint))?
        .label("equilibrium path (all states)")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], faint));
    // Retract first and wide, approach on top and thin: where they coincide both stay visible.
    use crate::cycle::Phase;
    for (ph, col, width) in [(Phase::Retract, ORANGE_, 6), (Phase::Approach, BLUE_, 2)] {
        let st = ShapeStyle::from(&col).stroke_width(width);
        let mut seg: Vec<(f64, f64)> = Vec::new();
        let mut first = true;
        for s in steps(ph) {
            if s.jump && !seg.is_empty() {
                let s2 = chart.draw_series(LineSeries::new(std::mem::take(&mut seg), st))?;
                if first {
                    s2.label(ph.to_string())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
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
                s2.label(ph.to_string())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
            }
        }
    }
    // Jumps: dashed lines with an arrowhead drawn in pixel space.
    for j in &c.jumps {
        let col = if j.phase == crate::cycle::Phase::Approach {
            BLUE_
        } else {
            ORANGE_
        };
        let from = (j.from.approach, j.from.load);
        let to = match &j.to {
            Some(t) => (t.approach.max(xmin - pad), t.load),
            None => (j.from.approach, ymax * 1.05 + 0.05),
        };
        chart.draw_series(DashedLineSeries::new(
            vec![from, to],
            6,
            4,
            ShapeStyle::from(&col).stroke_width(2),
        ))?;
        let (p0, p1) = (chart.backend_coord(&from), chart.backend_coord(&to));
        let (dx, dy) = ((p1.0 - p0.0) as f64, (p1.1 - p0.1) as f64);
        let len = (dx * dx + dy * dy).sqrt().max(1.0);
        let (ux, uy) = (dx / len, dy / len);
        let tip = p1;
        let base = (tip.0 as f64 - 16.0 * ux, tip.1 as f64 - 16.0 * uy);
        let wing = |s: f64| {
            (
                (base.0 - 7.0 * uy * s) as i32,
                (base.1 + 7.0 * ux * s) as i32,
            )
        };
        root.draw(&Polygon::new(
            vec![tip, wing(1.0), wing(-1.0)],
            col.filled(),
        ))?;
    }
    super::legend(&mut chart, SeriesLabelPosition::UpperLeft, 18)?;
    let energy = match c.hysteresis {
        Some(w) => format!("energy lost per cycle: {w:.4}"),
        None => "the surfaces separate: no closed cycle".into(),
    };
    let (lw, lh) = left.dim_in_pixel();
    left.draw(&Text::new(
        energy,
        (lw as i32 - 400, lh as i32 - 120),
        ("sans-serif", 20).into_font(),
    ))?;

    let contact: Vec<&crate::cycle::PathPoint> = c
        .path
        .iter()
        .filter(|p| p.branch == crate::cycle::Branch::Contact)
        .collect();
    let amax = contact.iter().map(|p| p.a).fold(0.0, f64::max) * 1.05;
    let mut ch = ChartBuilder::on(&right)
        .caption("contact radius against load", ("sans-serif", 22))
        .margin(20)
        .x_label_area_size(70)
        .y_label_area_size(70)
        .build_cartesian_2d(ymin * 1.15 - 0.05..ymax * 1.05 + 0.05, 0.0..amax)?;
    ch.configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc("load  P / (π w R)")
        .y_desc("contact radius A")
        .axis_desc_style(("sans-serif", 20))
        .label_style(("sans-serif", 16))
        .draw()?;
    ch.draw_series(LineSeries::new(
        contact.iter().map(|p| (p.load, p.a)),
        faint,
    ))?;
    for (ph, col, r) in [(Phase::Retract, ORANGE_, 4), (Phase::Approach, BLUE_, 2)] {
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
    let (top, bottom) = root.split_vertically(H / 2);
    let r_max = md.r.last().copied().unwrap_or(1.0);
    let (ru, pu, gu) = if si {
        ("r (m)", "pressure p (Pa)", "gap h (m)")
    } else {
        (
            "r / (π w R²/K)^(1/3)",
            "pressure p / (π w K²/R)^(1/3)",
            "gap h / (π² w² R/K²)^(1/3)",
        )
    };
    let colour = |m: &str| match m {
        "md" => (BLACK, 4),
        "hertz" => (GRAY_, 2),
        "dmt" => (BLUE_, 2),
        _ => (ORANGE_, 2),
    };
    let label = |m: &str| match m {
        "md" => "Maugis-Dugdale",
        "hertz" => "Hertz",
        "dmt" => "DMT",
        _ => "JKR",
    };
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
    let mut chart = ChartBuilder::on(&top)
        .caption(title, ("sans-serif", 30))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(110)
        .build_cartesian_2d(0.0..r_max, p_lo..p_hi)?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc(ru)
        .y_desc(pu)
        .y_label_formatter(&|v| super::linear_label(*v))
        .x_label_formatter(&|v| super::linear_label(*v))
        .axis_desc_style(("sans-serif", 22))
        .label_style(("sans-serif", 18))
        .draw()?;
    for m in p.models.iter().filter(|m| m.status == "ok") {
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
                series
                    .label(label(m.model))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], st));
                first = false;
            }
        }
    }
    if let Some(c) = md.c {
        chart.draw_series(DashedLineSeries::new(
            vec![(c, p_lo), (c, p_hi)],
            8,
            6,
            ShapeStyle::from(&BLACK.mix(0.5)).stroke_width(1),
        ))?;
    }
    super::legend(&mut chart, SeriesLabelPosition::LowerRight, 20)?;

    let g_hi = p
        .models
        .iter()
        .flat_map(|m| m.gap.iter().copied())
        .fold(p.dugdale_range * 1.5, f64::max)
        * 1.05;
    let mut chart = ChartBuilder::on(&bottom)
        .margin(20)
        .x_label_area_size(70)
        .y_label_area_size(110)
        .build_cartesian_2d(0.0..r_max, 0.0..g_hi)?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc(ru)
        .y_desc(gu)
        .y_label_formatter(&|v| super::linear_label(*v))
        .x_label_formatter(&|v| super::linear_label(*v))
        .axis_desc_style(("sans-serif", 22))
        .label_style(("sans-serif", 18))
        .draw()?;
    for m in p.models.iter().filter(|m| m.status == "ok") {
        let (col, w) = colour(m.model);
        let st = ShapeStyle::from(&col).stroke_width(w);
        chart.draw_series(LineSeries::new(
            m.r.iter().copied().zip(m.gap.iter().copied()),
            st,
        ))?;
    }
    let dashed = ShapeStyle::from(&BLACK.mix(0.5)).stroke_width(1);
    chart.draw_series(DashedLineSeries::new(
        vec![(0.0, p.dugdale_range), (r_max, p.dugdale_range)],
        8,
        6,
        dashed,
    ))?;
    chart.draw_series(std::iter::once(Text::new(
        "Dugdale range h0: the surface forces act where the gap is below it",
        (0.02 * r_max, p.dugdale_range + 0.06 * g_hi),
        ("sans-serif", 18).into_font(),
    )))?;
    if let Some(c) = md.c {
        chart.draw_series(DashedLineSeries::new(
            vec![(c, 0.0), (c, g_hi)],
            8,
            6,
            dashed,
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            "c (MD)",
            (c, 0.92 * g_hi),
            ("sans-serif", 18).into_font(),
        )))?;
    }
    Ok(())
}
