//! The failure atlas: one error map per method over lambda and the distance above pull-off.

use super::map::{MARGIN, X_AREA, Y_AREA};
use super::{colorbar, log_label, viridis, Kind, Outputs, Print, NOTE, TICK, TITLE};
use plotters::prelude::*;

type Err = Box<dyn std::error::Error + Send + Sync>;

/// An error map: `err` is row-major (ny rows of nx, row 0 the smallest gap), NaN marks a failure.
pub struct ErrorMap<'a> {
    /// The figure's title (the method).
    pub title: String,
    /// The first and last lambda of the columns (log-spaced).
    pub lambdas: (f64, f64),
    /// The first and last distance above the pull-off of the rows (normalised load, log-spaced).
    pub gaps: (f64, f64),
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// The relative error of the contact radius at each point.
    pub err: &'a [f64],
}

/// Draws the map in the formats asked for.
pub fn render(m: &ErrorMap, print: &Print, want: super::Formats) -> Result<super::Rendered, Err> {
    super::draw_figure(Kind::Atlas, print, want, &|root| draw(root, m))
}

/// Draws the map and writes it to the files in `out`, as every figure.
pub fn save(m: &ErrorMap, print: &Print, out: &Outputs) -> anyhow::Result<()> {
    super::save(Kind::Atlas, print, out, &|root| draw(root, m))
}

/// log10 of the error is coloured from -16 (dark) to 0 (yellow); failures are magenta.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    m: &ErrorMap,
) -> Result<(), Err>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (w, h) = root.dim_in_pixel();
    let note = "magenta: failed (no answer, NaN, or off by more than 50%); colour: relative error of A against the exact f64 solver";
    let lines = super::wrap(root, note, NOTE, w as i32 - 160);
    let lh = super::line_height(NOTE);
    let (upper, lower) = root.split_vertically(h - (lines.len() as i32 * lh + 32) as u32);
    let (plot_area, bar) = upper.split_horizontally(w - (TICK * 4.2) as u32);
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(&m.title, ("sans-serif", TITLE))
        .margin(MARGIN)
        .margin_top(MARGIN + (TICK * 0.5) as i32)
        .margin_right(MARGIN + (TICK * 0.9) as i32)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(
            (m.lambdas.0..m.lambdas.1).log_scale(),
            (m.gaps.0..m.gaps.1).log_scale(),
        )?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (w, h) = ((px.end - px.start) as u32, (py.end - py.start) as u32);
    let mut buf = vec![0u8; (w * h * 3) as usize];
    for r in 0..h {
        let iy = ((1.0 - (r as f64 + 0.5) / h as f64) * (m.ny - 1) as f64).round() as usize;
        for c in 0..w {
            let ix = (((c as f64 + 0.5) / w as f64) * (m.nx - 1) as f64).round() as usize;
            let e = m.err[iy * m.nx + ix];
            let col = if e.is_nan() {
                RGBColor(255, 0, 255)
            } else {
                viridis((e.max(1e-16).log10() + 16.0) / 16.0)
            };
            let k = ((r * w + c) * 3) as usize;
            buf[k..k + 3].copy_from_slice(&[col.0, col.1, col.2]);
        }
    }
    if let Some(el) = BitMapElement::with_owned_buffer((m.lambdas.0, m.gaps.1), (w, h), buf) {
        chart.draw_series(std::iter::once(el))?;
    }
    super::house_axes(
        chart.configure_mesh(),
        "Maugis parameter  λ",
        "load above pull-off  \\bar{P} − \\bar{P}_{c}",
    )
    .x_label_formatter(&|v| log_label(*v))
    .y_label_formatter(&|v| log_label(*v))
    .draw()?;
    lower.draw(&Rectangle::new(
        [(32, 8), (32 + lh, lh)],
        RGBColor(255, 0, 255).filled(),
    ))?;
    for (k, l) in lines.into_iter().enumerate() {
        lower.draw(&Text::new(
            l,
            (48 + lh, 4 + k as i32 * lh),
            ("sans-serif", NOTE).into_font(),
        ))?;
    }
    let ticks: Vec<(f64, String)> = super::round_ticks(-16.0, 0.0)
        .into_iter()
        .map(|v| (v, format!("10^{{{}}}", super::minus(&format!("{v:.0}")))))
        .collect();
    colorbar(&bar, -16.0, 0.0, &ticks)?;
    Ok(())
}
