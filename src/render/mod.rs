//! Figures: plotters draws axes, log ticks, labels and legends with an embedded font (identical
//! output on every machine); the map raster is coloured here and placed as one bitmap. Every
//! figure is drawn once, as SVG; its PNG is that SVG rasterised by resvg with anti-aliasing and
//! the same font ([`svg_to_png`]), so the two formats show the same figure.

pub mod atlas;
pub mod map;
pub mod plots;

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

/// "1e-3"-style tick labels for log axes: 0.001 .. 1000 as plain numbers, beyond as powers.
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
        format!("1e{e}")
    }
}

/// Tick labels for linear axes: the value without binary noise (-3.4, not -3.4000000000000004),
/// in e-notation where it is very large or small.
pub fn linear_label(v: f64) -> String {
    // Within rounding of zero (a tick at -1e-17): 0, not -0.0.
    if v.abs() < 1e-12 * 1f64.max(v.abs()) || !v.is_finite() {
        return "0".into();
    }
    let trim = |s: String| -> String {
        match s.split_once('e') {
            Some((m, e)) if m.contains('.') => {
                format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            Some(_) => s,
            None if s.contains('.') => s.trim_end_matches('0').trim_end_matches('.').into(),
            None => s,
        }
    };
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        trim(format!("{v:.4e}"))
    } else {
        trim(format!("{v:.6}"))
    }
}

/// Draws a figure of `size` once, as SVG, and rasterises it to PNG if asked: the one drawing
/// path of every figure. Returns (PNG bytes, SVG text) as asked.
#[allow(clippy::type_complexity)]
pub fn draw_figure(
    size: (u32, u32),
    png: bool,
    svg: bool,
    draw: impl FnOnce(
        &plotters::prelude::DrawingArea<plotters::prelude::SVGBackend, plotters::coord::Shift>,
    ) -> Result<(), Box<dyn std::error::Error + Send + Sync>>,
) -> Result<(Option<Vec<u8>>, Option<String>), Box<dyn std::error::Error + Send + Sync>> {
    use plotters::prelude::*;
    fonts();
    let mut s = String::new();
    {
        let root = SVGBackend::with_string(&mut s, size).into_drawing_area();
        draw(&root)?;
        root.present()?;
    }
    let png = if png { Some(svg_to_png(&s)?) } else { None };
    Ok((png, svg.then_some(s)))
}

/// Rasterises an SVG drawn by plotters into an anti-aliased PNG of the same size, with the
/// same embedded font (no system fonts: the same bytes on every machine).
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, Box<dyn std::error::Error + Send + Sync>> {
    use resvg::{tiny_skia, usvg};
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
    let tree = usvg::Tree::from_str(svg, &opt)?;
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height()).ok_or("empty figure")?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    // Opaque RGB, as the figures were before (the background is white).
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    Ok(png_bytes(&rgb, size.width(), size.height())?)
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

pub fn viridis(t: f64) -> plotters::style::RGBColor {
    let c = colorous::VIRIDIS.eval_continuous(t.clamp(0.0, 1.0));
    plotters::style::RGBColor(c.r, c.g, c.b)
}

/// A vertical viridis colorbar for values lo..hi in `area`, labelled by `fmt`.
pub fn colorbar<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    lo: f64,
    hi: f64,
    fmt: &dyn Fn(f64) -> String,
) -> Result<(), Box<dyn std::error::Error + Send + Sync>>
where
    DB::ErrorType: 'static,
{
    use plotters::prelude::*;
    let mut chart = ChartBuilder::on(area)
        .margin_top(90)
        .margin_bottom(104)
        .margin_right(20)
        .y_label_area_size(100)
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
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(8)
        .label_style(("sans-serif", 20))
        .y_label_formatter(&|v| fmt(*v))
        .draw()?;
    Ok(())
}

/// The legend of a chart's labelled series, framed on a translucent white box.
pub fn legend<'a, DB: plotters::prelude::DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut plotters::prelude::ChartContext<'a, DB, CT>,
    position: plotters::prelude::SeriesLabelPosition,
    font_size: u32,
) -> Result<(), Box<dyn std::error::Error + Send + Sync>>
where
    DB::ErrorType: 'static,
{
    use plotters::prelude::*;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font(("sans-serif", font_size))
        .position(position)
        .draw()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn linear_labels_have_no_binary_noise() {
        assert_eq!(super::linear_label(-3.4000000000000004), "-3.4");
        assert_eq!(super::linear_label(2.0), "2");
        assert_eq!(super::linear_label(-1e12), "-1e12");
        assert_eq!(super::linear_label(2.5e-5), "2.5e-5");
    }
}
