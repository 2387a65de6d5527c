//! The failure atlas: one error map per method over lambda and the distance above pull-off.

use super::{colorbar, log_label, viridis};
use plotters::prelude::*;
use std::path::Path;

type Err = Box<dyn std::error::Error + Send + Sync>;
pub const W: u32 = 1400;
pub const H: u32 = 1050;

/// An error map: `err` is row-major (ny rows of nx, row 0 the smallest gap), NaN marks a failure.
pub struct ErrorMap<'a> {
    pub title: String,
    pub lambdas: (f64, f64),
    pub gaps: (f64, f64),
    pub nx: usize,
    pub ny: usize,
    pub err: &'a [f64],
}

/// Draws the map as SVG and writes it rasterised with anti-aliasing, as every figure.
pub fn write(m: &ErrorMap, png: &Path) -> Result<(), Err> {
    let (bytes, _) = super::draw_figure((W, H), true, false, |root| draw(root, m))?;
    crate::io::write_atomic(png, &bytes.unwrap_or_default())?;
    Ok(())
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
    let (upper, _) = root.split_vertically(H - 40);
    let (plot_area, bar) = upper.split_horizontally(W - 170);
    let plot = root.clone();
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(&m.title, ("sans-serif", 28))
        .margin(24)
        .x_label_area_size(90)
        .y_label_area_size(110)
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
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("Maugis parameter  λ")
        .y_desc("load above pull-off  (P − Pc) / (π w R)")
        .axis_desc_style(("sans-serif", 26))
        .label_style(("sans-serif", 20))
        .x_label_formatter(&|v| log_label(*v))
        .y_label_formatter(&|v| log_label(*v))
        .draw()?;
    plot.draw(&Rectangle::new(
        [(30, H as i32 - 34), (54, H as i32 - 14)],
        RGBColor(255, 0, 255).filled(),
    ))?;
    plot.draw(&Text::new("failed: no answer, NaN, or off by more than 50%.  Colour: relative error of A against the exact f64 solver.", (62, H as i32 - 34), ("sans-serif", 19).into_font()))?;
    colorbar(&bar, -16.0, 0.0, &|v| format!("1e{v:.0}"))?;
    Ok(())
}
