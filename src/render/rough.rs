//! The rough-surface cycle: load per summit against the separation (approach and retract, the
//! pull-off marked), and the fractions of summits in contact and on the non-contact branch.

use super::plots::{builder, two_panels, BLUE_, GRAY_, ORANGE_};
use super::{legend, sample, sample_dashed, NOTE, TICK};
use crate::rough::{Mean, RoughCycle};
use plotters::coord::combinators::LogCoord;
use plotters::coord::Shift;
use plotters::prelude::*;

type Err = Box<dyn std::error::Error + Send + Sync>;

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}

/// A rough surface's cycle: the load per summit on the approach and the retract, and the
/// fractions of summits in contact and with a cohesive zone only; `wet` is added to the title
/// (the meniscus, where the summits carry one).
pub fn cycle<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    c: &RoughCycle,
    wet: &str,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (left, right) = two_panels(root);
    let all = || c.approach.iter().chain(&c.retract);
    let (xmin, xmax) = range(all().map(|m| m.separation));
    let (ymin, ymax) = range(all().map(|m| m.load).chain([0.0]));
    let pad = 0.06 * (ymax - ymin).max(1e-12);
    let title = format!(
        "Rough surface, λ = {}, σ = {}{wet}",
        crate::physics::domain::short(c.lambda),
        crate::physics::domain::short(c.sigma)
    );
    let mut chart =
        builder(&left, &title).build_cartesian_2d(xmin..xmax, ymin - pad..ymax + pad)?;
    super::house_mesh(
        chart.configure_mesh(),
        "separation  d (approach units)",
        "load per summit  \\bar{P}",
    )
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    let pts =
        |v: &[Mean]| -> Vec<(f64, f64)> { v.iter().map(|m| (m.separation, m.load)).collect() };
    // Retract first and wide, approach on top and thin: where they coincide both stay visible.
    let retract = ShapeStyle::from(&ORANGE_).stroke_width(12);
    chart
        .draw_series(LineSeries::new(pts(&c.retract), retract))?
        .label("retract")
        .legend(sample(retract));
    let approach = ShapeStyle::from(&BLUE_).stroke_width(4);
    chart
        .draw_series(LineSeries::new(pts(&c.approach), approach))?
        .label("approach")
        .legend(sample(approach));
    // What each branch carries, in the leg's colour and the line styles of the fractions'
    // panel: the summits in contact (solid) and those with a cohesive zone only (dashed, always
    // tensile). Drawn only where that branch holds summits, and only where some summits have a
    // cohesive zone only (else the summits in contact carry the whole load).
    let split = all().any(|m| m.noncontact_fraction > 0.0);
    for (v, col) in [(&c.retract, ORANGE_), (&c.approach, BLUE_)]
        .into_iter()
        .filter(|_| split)
    {
        let thin = ShapeStyle::from(&col.mix(0.75)).stroke_width(3);
        let on = |f: fn(&Mean) -> f64, w: fn(&Mean) -> f64| -> Vec<(f64, f64)> {
            v.iter()
                .filter(|m| w(m) > 0.0)
                .map(|m| (m.separation, f(m)))
                .collect()
        };
        chart.draw_series(LineSeries::new(
            on(|m| m.contact_load, |m| m.contact_fraction),
            thin,
        ))?;
        chart.draw_series(DashedLineSeries::new(
            on(|m| m.noncontact_load, |m| m.noncontact_fraction),
            12,
            8,
            thin,
        ))?;
    }
    if split {
        let key = ShapeStyle::from(&GRAY_).stroke_width(3);
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
            .label("by the summits in contact")
            .legend(sample(key));
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
            .label("by cohesive zones only")
            .legend(sample_dashed(key));
    }
    chart.draw_series(std::iter::once(Circle::new(
        (c.pulloff_separation, c.pulloff_load),
        14,
        ShapeStyle::from(&BLACK).stroke_width(4),
    )))?;
    chart.draw_series(std::iter::once(Text::new(
        format!(
            "pull-off {}",
            super::minus(&format!("{:.4}", c.pulloff_load))
        ),
        (c.pulloff_separation, c.pulloff_load),
        ("sans-serif", NOTE).into_font().color(&BLACK),
    )))?;
    legend(&mut chart, SeriesLabelPosition::LowerRight, NOTE)?;

    fractions(&right, c, (xmin, xmax))
}

/// The cycle's right panel: the fractions of summits in contact (solid) and with a cohesive
/// zone only (dashed), coloured by leg as in the load panel.
fn fractions<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    c: &RoughCycle,
    (xmin, xmax): (f64, f64),
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    let mut frac = builder(area, "").build_cartesian_2d(xmin..xmax, 0.0..1.0)?;
    super::house_mesh(
        frac.configure_mesh(),
        "separation  d",
        "fraction of summits",
    )
    .x_label_formatter(&|v| super::linear_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    // Colours as in the load panel; the legend names the line styles only.
    for (v, col) in [(&c.retract, ORANGE_), (&c.approach, BLUE_)] {
        let solid = ShapeStyle::from(&col).stroke_width(6);
        frac.draw_series(LineSeries::new(
            v.iter().map(|m| (m.separation, m.contact_fraction)),
            solid,
        ))?;
        let dashed = ShapeStyle::from(&col.mix(0.8)).stroke_width(4);
        frac.draw_series(DashedLineSeries::new(
            v.iter().map(|m| (m.separation, m.noncontact_fraction)),
            16,
            10,
            dashed,
        ))?;
    }
    let key = ShapeStyle::from(&GRAY_).stroke_width(5);
    frac.draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
        .label("in contact")
        .legend(sample(key));
    frac.draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
        .label("cohesive zone only")
        .legend(sample_dashed(key));
    legend(&mut frac, SeriesLabelPosition::MiddleRight, NOTE)?;
    Ok(())
}

/// Fuller and Tabor's figure: the pull-off per summit relative to the smooth summit's against
/// the adhesion parameter (log axis), one line per lambda.
pub fn pulloff_curves<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curves: &[crate::rough::PulloffCurve],
    press: f64,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (xmin, xmax) = range(
        curves
            .iter()
            .flat_map(|c| c.fuller_tabor_parameter.iter().copied()),
    );
    let title = format!(
        "Rough pull-off, pressed to d = {}σ",
        super::minus(&crate::physics::domain::short(press))
    );
    let mut chart =
        builder(root, &title).build_cartesian_2d((xmin..xmax).log_scale(), 0.0..1.05)?;
    super::house_mesh(
        chart.configure_mesh(),
        "adhesion parameter  θ = E*σ^{3/2}/(R^{1/2}w)",
        "pull-off / smooth summit's",
    )
    .x_label_formatter(&|v| super::log_label(*v))
    .y_label_formatter(&|v| super::linear_label(*v))
    .draw()?;
    let colours = [BLUE_, ORANGE_, super::plots::GREEN_, GRAY_, BLACK];
    for (k, c) in curves.iter().enumerate() {
        let style = ShapeStyle::from(&colours[k % colours.len()]).stroke_width(6);
        let pts: Vec<(f64, f64)> = c
            .fuller_tabor_parameter
            .iter()
            .zip(&c.relative_pulloff)
            .map(|(x, y)| (*x, *y))
            .collect();
        chart
            .draw_series(LineSeries::new(pts, style))?
            .label(format!("λ = {}", crate::physics::domain::short(c.lambda)))
            .legend(sample(style));
    }
    legend(&mut chart, SeriesLabelPosition::LowerLeft, NOTE)?;
    Ok(())
}

/// The rough map's legend: the regions present, then the contour levels.
fn map_legend(m: &crate::rough::map::RoughMap) -> Vec<super::Entry> {
    use super::map::region_color;
    use super::Entry;
    use crate::map::Region;
    let present: Vec<Region> = m.region_counts().iter().map(|r| r.0).collect();
    let mut legend: Vec<Entry> = present
        .iter()
        .map(|&r| Entry {
            label: r
                .label()
                .replace("Bradley (rigid)", "Bradley (rigid summits)"),
            style: region_color(r).stroke_width(28),
            dashed: false,
        })
        .collect();
    legend.push(Entry {
        label: "P_{c}/P_{c,smooth} = 0.5, 0.1, 0.01".into(),
        style: BLACK.stroke_width(5),
        dashed: false,
    });
    legend
}

/// Contours of the pull-off relative to the smooth summit's (log10, in chart coordinates), each
/// level labelled on its longest path.
fn contours<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>,
    m: &crate::rough::map::RoughMap,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    use super::map::contour_paths;
    let sp = &m.spec;
    let field: Vec<f64> = m
        .relative_pulloff
        .iter()
        .map(|&r| if r > 0.0 { r.log10() } else { -30.0 })
        .collect();
    let at = |f: f64, lo: f64, hi: f64, n: usize| {
        10f64.powf(lo.log10() + f / (n - 1) as f64 * (hi.log10() - lo.log10()))
    };
    for (k, level) in crate::rough::map::CONTOURS.into_iter().enumerate() {
        let paths = contour_paths(&field, sp.nx, sp.ny, level.log10());
        for path in &paths {
            let pts: Vec<(f64, f64)> = path
                .iter()
                .map(|&(x, y)| {
                    (
                        at(x, sp.lambda_min, sp.lambda_max, sp.nx),
                        at(y, sp.sigma_min, sp.sigma_max, sp.ny),
                    )
                })
                .collect();
            chart.draw_series(LineSeries::new(pts.clone(), BLACK.stroke_width(5)))?;
        }
        // The level's label on its longest path, the three staggered across the map (at 35%,
        // 60% and 85% of the lambda axis) so that they never overlap.
        let want_x = (0.35 + 0.25 * k as f64) * (sp.nx - 1) as f64;
        if let Some(path) = paths.iter().max_by_key(|p| p.len()) {
            let &(x, y) = path
                .iter()
                .min_by(|a, b| (a.0 - want_x).abs().total_cmp(&(b.0 - want_x).abs()))
                .unwrap_or(&path[path.len() / 2]);
            let p = (
                at(x, sp.lambda_min, sp.lambda_max, sp.nx),
                at(y, sp.sigma_min, sp.sigma_max, sp.ny),
            );
            let text = crate::physics::domain::short(level);
            let style = ("sans-serif", NOTE).into_font().color(&BLACK);
            let (cx, cy) = chart.backend_coord(&p);
            let tw = super::text_width(chart.plotting_area(), &text, NOTE);
            let th = super::line_height(NOTE);
            let area = chart.plotting_area().strip_coord_spec();
            let base = area.get_base_pixel();
            let (x0, y0) = (cx - base.0 - tw / 2 - 6, cy - base.1 - th / 2 - 4);
            area.draw(&Rectangle::new(
                [(x0, y0), (x0 + tw + 12, y0 + th + 8)],
                WHITE.mix(0.85).filled(),
            ))?;
            area.draw(&Text::new(text, (x0 + 6, y0 + 4), style))?;
        }
    }
    Ok(())
}

/// The rough adhesion map: regions (the simplest adequate summit model) coloured, the contours
/// of the pull-off relative to the smooth summit's on top.
pub fn map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    m: &crate::rough::map::RoughMap,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    use super::map::{region_color, MARGIN, X_AREA, Y_AREA};
    use super::TITLE;
    root.fill(&WHITE)?;
    let (w, h) = root.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    let sp = &m.spec;
    let pad = 32;
    let tol = format!("{}%", sp.tolerance * 100.0);
    let legend = map_legend(m);
    let caption = super::wrap(
        root,
        &format!(
            "Greenwood-Williamson summits, heights N(0, σ²), pressed to −{}σ and retracted. Colour: the simplest summit model whose rough pull-off is within {tol} of the smooth summit's pull-off and whose retract curve is within {tol} of its largest load, against exact Maugis-Dugdale summits. Lines: the rough pull-off per summit relative to the smooth summit's.",
            crate::physics::domain::short(sp.press_sigmas)
        ),
        NOTE,
        w - 2 * pad,
    );
    let bottom = super::legend_rows_height(root, &legend, NOTE, w - 2 * pad)
        + caption.len() as i32 * super::line_height(NOTE)
        + 28;
    let (upper, lower) = root.split_vertically(h - bottom);
    let mut chart = ChartBuilder::on(&upper)
        .caption(
            format!("Rough adhesion map (tolerance {tol})"),
            ("sans-serif", TITLE),
        )
        .margin(MARGIN)
        .margin_top(MARGIN + (TICK * 0.5) as i32)
        .margin_right(MARGIN + (TICK * 0.9) as i32)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(
            (sp.lambda_min..sp.lambda_max).log_scale(),
            (sp.sigma_min..sp.sigma_max).log_scale(),
        )?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (bw, bh) = ((px.end - px.start) as u32, (py.end - py.start) as u32);
    let buf = super::map::pixels((sp.nx, sp.ny), (bw, bh), |i| region_color(m.regions[i]));
    if let Some(el) = BitMapElement::with_owned_buffer((sp.lambda_min, sp.sigma_max), (bw, bh), buf)
    {
        chart.draw_series(std::iter::once(el))?;
    }
    super::house_axes(
        chart.configure_mesh(),
        "Maugis parameter of a summit  λ",
        "roughness  σ/(π²w²R/K²)^{1/3}",
    )
    .x_label_formatter(&|v| super::log_label(*v))
    .y_label_formatter(&|v| super::log_label(*v))
    .draw()?;
    contours(&mut chart, m)?;
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
