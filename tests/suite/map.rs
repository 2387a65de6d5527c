//! Maps: classification against known limits, figures, tables, determinism, GPU/CPU agreement.

use tabor::engine::Engine;
use tabor::map::{compute, LoadAxis, MapSpec, Region};

fn spec(nx: usize, ny: usize, axis: LoadAxis) -> MapSpec {
    let (lo, hi) = if axis == LoadAxis::AbovePulloff {
        (1e-6, 1e3)
    } else {
        (1e-3, 1e3)
    };
    MapSpec {
        lambda_min: 1e-3,
        lambda_max: 1e3,
        nx,
        load_axis: axis,
        load_min: lo,
        load_max: hi,
        ny,
        tolerance: 0.05,
        strength_ratios: vec![0.001, 0.01],
    }
}

#[test]
fn regions_and_thresholds_match_known_limits() {
    let d = compute(&spec(121, 61, LoadAxis::Log), &Engine::Cpu).unwrap();
    let th = d.thresholds();
    // lambda = 1e-3: Hertz is within 5% of DMT-like MD once (1 + 2/P)^(1/3) - 1 <= 0.05,
    // i.e. P >= 2 / (1.05^3 - 1) = 12.6.
    let h = th[0]["hertz_adequate_above_load"].as_f64().unwrap();
    assert!((10.0..16.0).contains(&h), "{h}");
    // lambda = 1e3: JKR is adequate at every load of the axis.
    let j = th[120]["jkr_adequate_above_load"].as_f64().unwrap();
    assert_eq!(j, 1e-3);
    // JKR within 5% at all loads only for lambda >= 1.88, DMT only for lambda <= 0.085
    // (PHYSICS.md section 6): check the bottom row.
    for ix in 0..121 {
        let l = d.lambdas[ix];
        let r = d.region_at(ix, 0);
        if l > 2.0 {
            assert_eq!(r, Region::Jkr, "lambda {l}");
        }
        if l < 0.08 && l > 0.03 {
            assert_eq!(r, Region::Dmt, "lambda {l}");
        }
        if (0.1..1.8).contains(&l) {
            assert_eq!(r, Region::Md, "lambda {l}");
        }
    }
}

#[test]
fn tensile_map_has_no_contact_only_below_pulloff() {
    let mut s = spec(64, 64, LoadAxis::Linear);
    s.load_min = -2.0;
    s.load_max = 2.0;
    let d = compute(&s, &Engine::Cpu).unwrap();
    for i in 0..d.len() {
        let below = d.state(i).load < d.pulloff[i % 64];
        assert_eq!(d.regions[i] == Region::NoContact, below, "point {i}");
    }
}

#[test]
fn figures_tables_and_determinism() {
    let dir = tempfile::tempdir().unwrap();
    let d = compute(&spec(96, 96, LoadAxis::AbovePulloff), &Engine::Cpu).unwrap();
    let (png, svg) = (dir.path().join("m.png"), dir.path().join("m.svg"));
    let print = tabor::render::Print::single_column();
    let out = |png: &std::path::Path, svg: Option<&std::path::Path>| tabor::render::Outputs {
        png: Some(png.to_path_buf()),
        svg: svg.map(|p| p.to_path_buf()),
        pdf: None,
    };
    tabor::render::map::save(&d, None, &print, &out(&png, Some(&svg))).unwrap();
    let img = image::open(&png).unwrap();
    // One column (85 mm) at 300 dpi.
    assert_eq!(img.width(), 1004);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<svg")
            && text.contains("width=\"85mm\"")
            && text.contains("Maugis parameter")
    );
    // Same input, same bytes.
    let png2 = dir.path().join("m2.png");
    tabor::render::map::save(&d, None, &print, &out(&png2, None)).unwrap();
    assert_eq!(std::fs::read(&png).unwrap(), std::fs::read(&png2).unwrap());
    // A quantity map: a viridis colorbar, and colours from the whole scale in the plot.
    tabor::render::map::save(
        &d,
        Some(tabor::render::map::Quantity::ErrJkr),
        &print,
        &out(&png2, None),
    )
    .unwrap();
    let q = image::open(&png2).unwrap().to_rgb8();
    let viridis = |t: f64| {
        let c = tabor::render::viridis(t);
        image::Rgb([c.0, c.1, c.2])
    };
    // Both ends of the scale are drawn (the colorbar samples mid-rows, so within a few levels).
    let has = |c: image::Rgb<u8>| {
        q.pixels().any(|p| {
            (0..3)
                .map(|k| (p[k] as i32 - c[k] as i32).abs())
                .sum::<i32>()
                <= 6
        })
    };
    assert!(has(viridis(0.0)) && has(viridis(1.0)), "no colour scale");
    let distinct: std::collections::HashSet<_> = q.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 200, "{} colours", distinct.len());
    assert_ne!(std::fs::read(&png).unwrap(), std::fs::read(&png2).unwrap());
}

#[test]
fn gpu_and_cpu_maps_agree() {
    let gpu = match tabor::gpu::Gpu::new(None) {
        Ok(g) => g,
        Err(e) => {
            if std::env::var("TABOR_REQUIRE_GPU").is_ok_and(|v| v == "1") {
                panic!("TABOR_REQUIRE_GPU=1 but no GPU adapter: {e}");
            }
            eprintln!("SKIPPED: no GPU adapter ({e})");
            return;
        }
    };
    for axis in [LoadAxis::Log, LoadAxis::AbovePulloff] {
        let s = spec(256, 256, axis);
        let c = compute(&s, &Engine::Cpu).unwrap();
        let g = compute(
            &s,
            &Engine::Gpu(Box::new(tabor::gpu::Gpu::new(None).unwrap())),
        )
        .unwrap();
        let same = c
            .regions
            .iter()
            .zip(&g.regions)
            .filter(|(a, b)| a == b)
            .count();
        let frac = same as f64 / c.regions.len() as f64;
        eprintln!(
            "{axis:?}: GPU and CPU regions agree on {:.4}% of points",
            100.0 * frac
        );
        assert!(frac >= 0.999, "{frac}");
    }
    drop(gpu);
}

/// The map keeps compact records (13 bytes a point) and f64 values only where asked: both give
/// the same regions and thresholds, the f64 values are the states solved one by one, and the
/// records are those values in single precision.
#[test]
fn compact_records_and_kept_values_agree_with_direct_solves() {
    use tabor::map::{compute_with, ComputeOptions};
    use tabor::solver::{LambdaContext, Status};
    for axis in [LoadAxis::Log, LoadAxis::AbovePulloff, LoadAxis::Linear] {
        let mut s = spec(40, 30, axis);
        if axis == LoadAxis::Linear {
            (s.load_min, s.load_max) = (-2.0, 4.0);
        }
        let opts = |keep_exact| ComputeOptions {
            keep_exact,
            check: 0,
            records: true,
        };
        let full = compute_with(&s, &Engine::Cpu, opts(true)).unwrap();
        let lean = compute_with(&s, &Engine::Cpu, opts(false)).unwrap();
        assert!(lean.exact.is_none() && full.exact.is_some());
        assert_eq!(full.regions, lean.regions);
        assert_eq!(full.thresholds(), lean.thresholds());
        for i in (0..full.len()).step_by(7) {
            let (ix, iy) = (i % 40, i / 40);
            let ctx = LambdaContext::new(full.lambdas[ix]).unwrap();
            let direct = match axis {
                LoadAxis::AbovePulloff => {
                    ctx.solve_load_gap(full.rows[iy], ctx.load_pulloff.load + full.rows[iy])
                }
                _ => ctx.solve_load(full.rows[iy]),
            };
            let (f, l) = (full.state(i), lean.state(i));
            assert_eq!(
                (f.status, l.status),
                (direct.status, direct.status),
                "{axis:?} point {i}"
            );
            assert_eq!(f.load, direct.load, "{axis:?} point {i}");
            if direct.status == Status::Ok {
                assert!((f.a / direct.a - 1.0).abs() < 1e-13, "{axis:?} point {i}");
                assert_eq!(l.a, direct.a as f32 as f64);
                assert_eq!(l.m_minus_1, direct.m_minus_1 as f32 as f64);
            }
        }
        // Exports refuse a map without its f64 values rather than write single precision.
        let mut sink = Vec::new();
        let e = tabor::export::write_map_json(&mut sink, &lean, &Engine::Cpu, None, true, false);
        assert!(e.unwrap_err().to_string().contains("f64 values"));
    }
}

/// A map of regions alone keeps the records of the contour grid only (every third row and
/// column here), and is otherwise the map that keeps them all: the same regions, thresholds and
/// checks, and at the contour grid's points the same records.
#[test]
fn a_map_of_regions_alone_keeps_the_contour_grid() {
    use tabor::map::{compute_with, trace_stride, ComputeOptions};
    let s = MapSpec {
        load_axis: LoadAxis::Linear,
        load_min: -2.0,
        load_max: 10.0,
        ..spec(1700, 40, LoadAxis::Linear)
    };
    let opts = |records| ComputeOptions {
        keep_exact: false,
        check: 0,
        records,
    };
    let all = compute_with(&s, &Engine::Cpu, opts(true)).unwrap();
    let alone = compute_with(&s, &Engine::Cpu, opts(false)).unwrap();
    let k = trace_stride(s.nx, s.ny);
    assert_eq!(k, 3);
    assert_eq!((all.points.stride, alone.points.stride), (1, k));
    assert_eq!(alone.points.a.len(), 567 * 14);
    assert_eq!(all.points.a.len(), 1700 * 40);
    assert!(all.regions == alone.regions);
    assert_eq!(all.thresholds(), alone.thresholds());
    for iy in (0..s.ny).step_by(k) {
        for ix in (0..s.nx).step_by(k) {
            let i = iy * s.nx + ix;
            let (a, b) = (all.drawn(i), alone.drawn(i));
            assert_eq!(
                (a.a.to_bits(), a.approach.to_bits(), a.status),
                (b.a.to_bits(), b.approach.to_bits(), b.status),
                "point {ix}, {iy}"
            );
        }
    }
    // Every region of the linear axis is there, no contact below the pull-offs included.
    for r in [Region::NoContact, Region::Dmt, Region::Jkr, Region::Md] {
        assert!(alone.regions.contains(&r), "{r:?}");
    }
}

/// Without every point's values a map may exceed 4096 x 4096 points (up to 16384 a side);
/// with them it may not.
#[test]
fn only_a_map_of_values_is_held_to_4096_squared() {
    use tabor::map::ComputeOptions;
    let s = spec(5000, 5000, LoadAxis::Log);
    let regions = ComputeOptions {
        keep_exact: false,
        check: 0,
        records: false,
    };
    assert!(s.validate_with(&regions).is_ok());
    let e = s.validate().unwrap_err().to_string();
    assert!(e.contains("25000000 points, more than the 16777216"), "{e}");
    let values = ComputeOptions {
        records: true,
        ..regions
    };
    assert!(s.validate_with(&values).is_err());
}
