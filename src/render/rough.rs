//! The rough-surface cycle: load per summit against the separation (approach and retract, the
//! pull-off marked), and the fractions of summits in contact and on the non-contact branch.

use super::plots::{builder, two_panels, BLUE_, GRAY_, ORANGE_};
use super::{legend, sample, sample_dashed, AXIS, NOTE, TICK};
use crate::rough::{Mean, RoughCycle};
use plotters::coord::Shift;
use plotters::prelude::*;

type Err = Box<dyn std::error::Error + Send + Sync>;

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}

pub fn cycle<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, c: &RoughCycle) -> Result<(), Err>
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
        "Rough surface, λ = {}, σ = {}",
        crate::physics::domain::short(c.lambda),
        crate::physics::domain::short(c.sigma)
    );
    let mut chart =
        builder(&left, &title).build_cartesian_2d(xmin..xmax, ymin - pad..ymax + pad)?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_desc("separation  d (approach units)")
        .y_desc("load per summit  \\bar{P}")
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK))
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

    let mut frac = builder(&right, "").build_cartesian_2d(xmin..xmax, 0.0..1.0)?;
    frac.configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_desc("separation  d")
        .y_desc("fraction of summits")
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK))
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
    chart
        .configure_mesh()
        .max_light_lines(1)
        .light_line_style(RGBColor(245, 245, 245))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_desc("adhesion parameter  θ = E*σ^{3/2}/(R^{1/2}w)")
        .y_desc("pull-off / smooth summit's")
        .axis_desc_style(("sans-serif", AXIS))
        .label_style(("sans-serif", TICK))
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
