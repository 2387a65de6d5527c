//! Every figure kind drawn through the one path (SVG, then PNG and PDF from it): the PNG is
//! anti-aliased and sized for print, the SVG parses and carries true symbols, the PDF opens and
//! has the printed size, and the same input gives the same bytes.

use tabor::render::{self, Formats, Kind, Print, Rendered};

const ALL: Formats = Formats {
    png: true,
    svg: true,
    pdf: true,
};

fn map_spec(axis: tabor::map::LoadAxis) -> tabor::map::MapSpec {
    let (load_min, load_max) = match axis {
        tabor::map::LoadAxis::Linear => (-2.0, 4.0),
        _ => (1e-5, 1e3),
    };
    tabor::map::MapSpec {
        lambda_min: 1e-3,
        lambda_max: 1e3,
        nx: 96,
        load_axis: axis,
        load_min,
        load_max,
        ny: 96,
        tolerance: 0.05,
        strength_ratios: vec![0.001, 0.01],
    }
}

/// Each figure kind, drawn at `print`.
fn figures(print: &Print) -> Vec<(&'static str, Rendered)> {
    use tabor::map::{compute, LoadAxis};
    use tabor::render::plots;
    let engine = tabor::engine::Engine::Cpu;
    let log_map = compute(&map_spec(LoadAxis::Log), &engine).unwrap();
    let tensile = compute(&map_spec(LoadAxis::AbovePulloff), &engine).unwrap();
    let pulloff = tabor::figure_data::pulloff_data().unwrap();
    let curves = tabor::figure_data::curves_data(&[0.1, 1.0, 10.0]).unwrap();
    let scene = tabor::scene::solve_scene(&tabor::scene::preset("afm-si").unwrap()).unwrap();
    let scene_fig = tabor::figure_data::scene_data(&scene).unwrap();
    let cycle = tabor::cycle::cycle(1.0, tabor::cycle::Drive::Spring(0.5), 2.0).unwrap();
    let bench = vec![
        variant("cpu_f64", 2e6, 1e-15, 0),
        variant("gpu_f32", 5e7, 3e-6, 0),
        variant("closed_jkr", 1e8, 0.3, 12),
    ];
    let err: Vec<f64> = (0..40 * 30)
        .map(|i| {
            if i % 97 == 0 {
                f64::NAN
            } else {
                10f64.powf(-16.0 + (i % 40) as f64 * 0.4)
            }
        })
        .collect();
    let atlas = render::atlas::ErrorMap {
        title: "f32 kernel".into(),
        lambdas: (1e-4, 1e4),
        gaps: (1e-6, 1e3),
        nx: 40,
        ny: 30,
        err: &err,
    };
    let draw = |kind: Kind, g: render::DrawSvg| render::draw_figure(kind, print, ALL, g).unwrap();
    vec![
        (
            "map",
            render::map::render(&log_map, None, print, ALL).unwrap(),
        ),
        (
            "quantity map",
            render::map::render(&log_map, Some(render::map::Quantity::ErrJkr), print, ALL).unwrap(),
        ),
        (
            "tensile map",
            render::map::render(&tensile, None, print, ALL).unwrap(),
        ),
        (
            "pull-off",
            draw(Kind::Pulloff, &|r| plots::pulloff(r, &pulloff)),
        ),
        ("curves", draw(Kind::Curves, &|r| plots::curves(r, &curves))),
        (
            "scene",
            draw(Kind::Scene, &|r| plots::scene(r, &scene, &scene_fig)),
        ),
        ("cycle", draw(Kind::Cycle, &|r| plots::cycle(r, &cycle))),
        (
            "bench",
            draw(Kind::Bench, &|r| {
                plots::bench_chart(r, &bench, &[0, 1, 2], "bench")
            }),
        ),
        ("atlas", render::atlas::render(&atlas, print, ALL).unwrap()),
    ]
}

fn variant(name: &str, speed: f64, err: f64, failures: usize) -> tabor::bench::VariantResult {
    tabor::bench::VariantResult {
        name: name.into(),
        description: String::new(),
        points: 1000,
        seconds: 1000.0 / speed,
        points_per_second: speed,
        max_rel_err: err,
        median_rel_err: err / 10.0,
        p99_rel_err: err / 2.0,
        max_rel_err_away: err,
        failures,
        evals_per_state: None,
    }
}

/// Most distinct colours along any one row or column of the image's middle half: a curve or
/// boundary drawn with anti-aliasing leaves a run of blended shades where the line crosses it;
/// drawn without, only the few colours of the palette.
fn colours_along_a_line(png: &[u8]) -> usize {
    let img = image::load_from_memory(png).unwrap().to_rgb8();
    let (w, h) = img.dimensions();
    let mut best = 0;
    for k in 0..16 {
        let y = h / 4 + k * h / 32;
        let row: std::collections::HashSet<_> = (0..w).map(|x| img.get_pixel(x, y).0).collect();
        let x = w / 4 + k * w / 32;
        let col: std::collections::HashSet<_> = (0..h).map(|y| img.get_pixel(x, y).0).collect();
        best = best.max(row.len()).max(col.len());
    }
    best
}

/// The same SVG rasterised without anti-aliasing (shapes, text and images), for comparison.
fn crisp_png(svg: &str, width: u32) -> Vec<u8> {
    use resvg::{tiny_skia, usvg};
    let mut db = usvg::fontdb::Database::new();
    db.load_font_data(include_bytes!("../../assets/fonts/DejaVuSans.ttf").to_vec());
    db.set_sans_serif_family("DejaVu Sans");
    let opt = usvg::Options {
        fontdb: std::sync::Arc::new(db),
        shape_rendering: usvg::ShapeRendering::CrispEdges,
        text_rendering: usvg::TextRendering::OptimizeSpeed,
        image_rendering: usvg::ImageRendering::OptimizeSpeed,
        ..Default::default()
    };
    let tree = usvg::Tree::from_str(svg, &opt).unwrap();
    let scale = width as f32 / tree.size().width();
    let h = (tree.size().height() * scale).round() as u32;
    let mut pm = tiny_skia::Pixmap::new(width, h).unwrap();
    pm.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pm.as_mut(),
    );
    let rgb: Vec<u8> = pm
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    tabor::render::png_bytes(&rgb, width, h).unwrap()
}

/// Page size in points from `pdfinfo`, or None where poppler-utils is not installed (a loud
/// skip on a developer machine; CI installs it and requires it).
fn pdfinfo_size(pdf: &[u8]) -> Option<(f64, f64)> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("f.pdf");
    std::fs::write(&path, pdf).unwrap();
    let out = match std::process::Command::new("pdfinfo").arg(&path).output() {
        Ok(o) => o,
        Err(_) => {
            assert!(
                std::env::var_os("CI").is_none(),
                "pdfinfo (poppler-utils) is required in CI to check the PDFs"
            );
            eprintln!("SKIPPED the pdfinfo check: pdfinfo (poppler-utils) is not installed");
            return None;
        }
    };
    assert!(
        out.status.success(),
        "pdfinfo rejects the PDF: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let line = text.lines().find(|l| l.starts_with("Page size:")).unwrap();
    let nums: Vec<f64> = line
        .split_whitespace()
        .filter_map(|t| t.parse().ok())
        .collect();
    Some((nums[0], nums[1]))
}

#[test]
fn every_figure_in_png_svg_and_pdf_for_one_column() {
    let print = Print::new(85.0, 300.0).unwrap();
    for (name, f) in figures(&print) {
        let png = f.png.as_ref().unwrap();
        let img = image::load_from_memory(png).unwrap();
        // 85 mm at 300 dpi.
        assert_eq!(img.width(), 1004, "{name}");
        let n = colours_along_a_line(png);
        let crisp = colours_along_a_line(&crisp_png(f.svg.as_ref().unwrap(), 1004));
        eprintln!("{name}: {n} distinct colours along a line ({crisp} without anti-aliasing)");
        assert!(
            n > 36 && n >= crisp + 20,
            "{name}: {n} distinct colours along a line ({crisp} without anti-aliasing)"
        );
        // The SVG parses, has the printed size, and its label markup became SVG text features.
        let svg = f.svg.as_ref().unwrap();
        let tree = resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default())
            .unwrap_or_else(|e| panic!("{name}: the SVG does not parse: {e}"));
        // usvg sizes at 96 px per inch: 85 mm is 321.26 px.
        assert!(
            (tree.size().width() - 85.0 / 25.4 * 96.0).abs() < 0.01,
            "{name}"
        );
        assert!(svg.contains("width=\"85mm\""), "{name}");
        for raw in ["\\bar{", "_{", "^{"] {
            assert!(!svg.contains(raw), "{name}: markup {raw} left in the SVG");
        }
        // The PDF: a PDF, and 85 mm wide (241 pt) where pdfinfo can open it.
        let pdf = f.pdf.as_ref().unwrap();
        assert!(pdf.starts_with(b"%PDF-"), "{name}");
        if let Some((w, h)) = pdfinfo_size(pdf) {
            assert!((w - 85.0 / 25.4 * 72.0).abs() < 0.05, "{name}: {w} pt wide");
            let ratio = img.height() as f64 / img.width() as f64;
            assert!(
                (h / w - ratio).abs() < 0.01,
                "{name}: PDF {w} x {h}, PNG ratio {ratio}"
            );
        }
    }
}

/// The text contents of an SVG's text elements.
fn texts(svg: &str) -> Vec<String> {
    svg.split("</text>")
        .filter_map(|t| t.rsplit_once("<text").map(|(_, t)| t.to_string()))
        .filter_map(|t| t.split_once('>').map(|(_, c)| c.trim().to_string()))
        .collect()
}

#[test]
fn symbols_are_typeset() {
    let print = Print::single_column();
    let figs = figures(&print);
    let svg = |name: &str| {
        figs.iter()
            .find(|f| f.0 == name)
            .unwrap()
            .1
            .svg
            .clone()
            .unwrap()
    };
    // The normalised load: P with an overline, P_c with a subscript; minus signs are U+2212.
    let map = svg("tensile map");
    assert!(map.contains("<tspan text-decoration=\"overline\">P</tspan>"));
    assert!(map.contains("<tspan baseline-shift=\"-22%\" font-size=\"72%\">c</tspan>"));
    // Log ticks below 0.01 as powers of ten with a superscript exponent.
    assert!(map.contains("10<tspan baseline-shift=\"38%\" font-size=\"72%\">\u{2212}3</tspan>"));
    let pulloff = svg("pull-off");
    assert!(pulloff.contains("\n\u{2212}2\n") && !pulloff.contains("\n-2\n"));
    assert!(pulloff.contains("Carpick") && !pulloff.contains("Johnson-Greenwood fit"));
    // The 1e-4 end of the pull-off figure's lambda axis is labelled.
    assert!(pulloff.contains(">\u{2212}4</tspan>"));
    // The scene in engineering units: nN and nm, no e-notation ticks.
    let scene = svg("scene");
    assert!(scene.contains("load  P (nN)") && scene.contains("contact radius  a (nm)"));
    for t in texts(&scene) {
        let b = t.as_bytes();
        let e_notation = b.windows(3).any(|w| {
            w[0].is_ascii_digit() && w[1] == b'e' && (w[2] == b'-' || w[2].is_ascii_digit())
        });
        assert!(!e_notation, "e-notation in the scene figure: {t}");
    }
}

#[test]
fn sizes_for_two_columns_and_the_same_bytes_each_time() {
    let double = Print::double_column();
    assert_eq!(double.png_width(), 2067);
    let d = tabor::map::compute(
        &map_spec(tabor::map::LoadAxis::Log),
        &tabor::engine::Engine::Cpu,
    )
    .unwrap();
    let a = render::map::render(&d, None, &double, ALL).unwrap();
    let b = render::map::render(&d, None, &double, ALL).unwrap();
    assert_eq!(a.png, b.png);
    assert_eq!(a.svg, b.svg);
    assert_eq!(a.pdf, b.pdf);
    let img = image::load_from_memory(a.png.as_ref().unwrap()).unwrap();
    assert_eq!(img.width(), 2067);
    // Bad sizes are refused with the value and what to give.
    let e = Print::new(5.0, 300.0).unwrap_err().to_string();
    assert!(e.contains("width_mm 5") && e.contains("85"), "{e}");
    assert!(Print::new(85.0, 0.0)
        .unwrap_err()
        .to_string()
        .contains("dpi 0"));
    assert!(Print::new(600.0, 2400.0)
        .unwrap_err()
        .to_string()
        .contains("pixels wide"));
}

#[test]
fn a_cycle_figure_holds_its_jump_landings() {
    // Under a soft spring the retract jump lands far out of contact: the figure's approach
    // axis must reach it, so the arrow's head is inside the axes. The tick labels of the SVG
    // show the axis range.
    let c = tabor::cycle::cycle(1.0, tabor::cycle::Drive::Spring(0.5), 2.0).unwrap();
    let lowest = c
        .jumps
        .iter()
        .filter_map(|j| j.to.as_ref().map(|t| t.approach))
        .fold(f64::INFINITY, f64::min);
    assert!(lowest < -1.5, "the test case needs a far landing: {lowest}");
    let f = render::draw_figure(Kind::Cycle, &Print::single_column(), ALL, &|r| {
        render::plots::cycle(r, &c)
    })
    .unwrap();
    let svg = f.svg.unwrap();
    // Tick values of the approach axis (the first chart's x labels) include one below it.
    let ticks: Vec<f64> = texts(&svg)
        .iter()
        .map(|t| t.replace('\u{2212}', "-"))
        .filter_map(|t| t.parse::<f64>().ok())
        .collect();
    assert!(
        ticks.iter().any(|&t| t <= lowest + 0.5),
        "no tick near the landing {lowest}: {ticks:?}"
    );
}
