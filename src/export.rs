//! Tables of results in the formats other programs read: the map's JSON document (the per-point
//! arrays streamed) and its NumPy files. The command line and the Python package both write
//! through here.

use crate::engine::Engine;
use crate::io::{json_num, Output};
use crate::map::{MapData, Region};
use crate::solver::Status;
use anyhow::Context;
use serde_json::json;
use std::io::Write as _;

/// The NumPy files of `--npy PREFIX`, in the order they are written.
pub const NPY_FILES: [&str; 8] = [
    "lambda.npy",
    "load_axis.npy",
    "load.npy",
    "A.npy",
    "approach.npy",
    "m_minus_1.npy",
    "region.npy",
    "region_names.json",
];

/// The map's JSON document. The per-point arrays of `full` are streamed row by row, so that
/// memory does not grow with them; timings (which differ between runs) only with `timings`.
pub fn write_map_json(
    out: &mut dyn std::io::Write,
    d: &MapData,
    engine: &Engine,
    check: Option<&crate::engine::CheckReport>,
    full: bool,
    timings: bool,
) -> anyhow::Result<()> {
    if full {
        need_exact(d, "the per-point arrays of the JSON")?;
    }
    let mut doc = map_json(d, engine, check);
    if timings {
        doc["metadata"]["timings_s"] = serde_json::to_value(&d.timings)?;
    }
    let text = serde_json::to_string_pretty(&doc)?;
    if !full {
        out.write_all(text.as_bytes())?;
        out.write_all(b"\n")?;
        return Ok(());
    }
    // Reopen the document's closing brace and append "points".
    let body = text
        .trim_end()
        .strip_suffix('}')
        .unwrap_or(&text)
        .trim_end();
    out.write_all(body.as_bytes())?;
    out.write_all(b",\n  \"points\": {")?;
    let nx = d.spec.nx;
    let fields: [(&str, &dyn Fn(usize) -> serde_json::Value); 6] = [
        ("region", &|i| json!(d.regions[i].name())),
        ("load", &|i| json_num(d.load(i))),
        ("A", &|i| json_num(d.state(i).a)),
        ("approach", &|i| json_num(d.state(i).approach)),
        ("m_minus_1", &|i| json_num(d.state(i).m_minus_1)),
        ("status", &|i| json!(d.state(i).status.name())),
    ];
    let mut line = String::new();
    for (k, (name, f)) in fields.iter().enumerate() {
        write!(out, "{}\n    \"{name}\": [", if k > 0 { "," } else { "" })?;
        for iy in 0..d.spec.ny {
            line.clear();
            line.push_str(if iy > 0 { ",\n      [" } else { "\n      [" });
            for ix in 0..nx {
                if ix > 0 {
                    line.push(',');
                }
                line.push_str(&f(iy * nx + ix).to_string());
            }
            line.push(']');
            out.write_all(line.as_bytes())?;
        }
        out.write_all(b"\n    ]")?;
    }
    out.write_all(b"\n  }\n}\n")?;
    Ok(())
}

/// A map's metadata as JSON: the spec, the engine, the check, the regions' counts and thresholds.
pub fn map_json(
    d: &MapData,
    engine: &Engine,
    check: Option<&crate::engine::CheckReport>,
) -> serde_json::Value {
    let mut doc = json!({
        "metadata": {
            "tabor_version": env!("CARGO_PKG_VERSION"),
            "backend": engine.name(),
            "adapter": engine.adapter(),
            "precision": engine.precision(),
            "tolerance": d.spec.tolerance,
            "grid": {"nx": d.spec.nx, "ny": d.spec.ny},
            "spec": d.spec,
            "cross_check": check,
            "criteria": match d.tip {
                None => json!({
                    "order": ["hertz", "rigid", "dmt", "jkr", "md"],
                    "hertz": "|A_Hertz/A - 1| <= tolerance, A_Hertz = Pbar^(1/3), Pbar >= 0",
                    "rigid": "(pi lambda / 2) max(A^2, |Dbar|) <= tolerance",
                    "dmt": "|A_DMT/A - 1| <= tolerance, A_DMT = (Pbar + 2)^(1/3)",
                    "jkr": "|A_JKR/A - 1| <= tolerance, A_JKR^3 = Pbar + 3 + sqrt(9 + 6 Pbar), Pbar >= -3/2",
                    "no_contact": "Pbar below the load-controlled pull-off",
                }),
                // A tip's own closed forms (docs/PHYSICS.md section 12), Qbar(A) the shape's
                // adhesion-free load and Fbar(A) its approach.
                Some(_) => json!({
                    "order": ["hertz", "rigid", "dmt", "jkr", "md"],
                    "hertz": "|A_Hertz/A - 1| <= tolerance, Qbar(A_Hertz) = Pbar, Pbar >= 0 (Sneddon's punch)",
                    "rigid": "(pi lambda / 2) max(Fbar(A), |Dbar|) <= tolerance",
                    "dmt": "|A_DMT/A - 1| <= tolerance, Qbar(A_DMT) = Pbar + Pbar_rigid (the rigid tip's Dugdale force at this lambda)",
                    "jkr": "|A_JKR/A - 1| <= tolerance, Qbar(A_JKR) - sqrt(6 A_JKR^3) = Pbar, on its stable branch",
                    "no_contact": "Pbar below the load-controlled pull-off",
                }),
            },
            "region_counts": d.region_counts().iter().map(|(r, n)| (r.name().to_string(), json!(n))).collect::<serde_json::Map<_, _>>(),
        },
        "axes": {
            "lambda": d.lambdas,
            "load": d.rows,
            "load_axis": d.spec.load_axis,
        },
        "thresholds": d.thresholds(),
        "large_deformation": d.large_deformation,
    });
    if let Some(tip) = d.tip {
        doc["metadata"]["tip"] = json!(tip);
    }
    doc
}

pub(crate) fn npy_write<T: npyz::AutoSerialize + Copy>(
    out: &mut Output,
    shape: &[u64],
    data: impl Iterator<Item = T>,
) -> anyhow::Result<()> {
    use npyz::WriterBuilder;
    let shown = out.name().display().to_string();
    let mut w = npyz::WriteOptions::new()
        .default_dtype()
        .shape(shape)
        .writer(&mut *out)
        .begin_nd()
        .with_context(|| format!("cannot write {shown}"))?;
    w.extend(data)
        .with_context(|| format!("cannot write {shown}"))?;
    w.finish()
        .with_context(|| format!("cannot write {shown}"))?;
    Ok(())
}

/// The per-point arrays as NumPy files, streamed into the outputs of [`NPY_FILES`]: NaN where a
/// state could not be computed; region codes as uint8 with their names in
/// PREFIX_region_names.json.
pub fn write_npy(d: &MapData, outs: &mut [Output]) -> anyhow::Result<()> {
    need_exact(d, "the NPY files")?;
    let (nx, ny) = (d.spec.nx as u64, d.spec.ny as u64);
    let ok = |s: &crate::solver::State, x: f64| if s.status == Status::Ok { x } else { f64::NAN };
    let [lam, axis, load, a, approach, m1, region, names] = outs else {
        anyhow::bail!(
            "write_npy needs the {} outputs of NPY_FILES",
            NPY_FILES.len()
        );
    };
    npy_write(lam, &[nx], d.lambdas.iter().copied())?;
    npy_write(axis, &[ny], d.rows.iter().copied())?;
    let all = || (0..d.len()).map(|i| d.state(i));
    npy_write(load, &[ny, nx], (0..d.len()).map(|i| d.load(i)))?;
    npy_write(a, &[ny, nx], all().map(|s| ok(&s, s.a)))?;
    npy_write(approach, &[ny, nx], all().map(|s| ok(&s, s.approach)))?;
    npy_write(m1, &[ny, nx], all().map(|s| ok(&s, s.m_minus_1)))?;
    npy_write(region, &[ny, nx], d.regions.iter().map(|&r| r as u8))?;
    let map: serde_json::Map<_, _> = Region::ALL
        .iter()
        .map(|r| ((*r as u8).to_string(), json!(r.name())))
        .collect();
    let shown = names.name().display().to_string();
    names
        .write_all((serde_json::to_string_pretty(&map)? + "\n").as_bytes())
        .with_context(|| format!("cannot write {shown}"))?;
    Ok(())
}

/// The f64 exports must come from the f64 values, never from the compact records.
fn need_exact(d: &MapData, what: &str) -> anyhow::Result<()> {
    if d.exact.is_none() {
        anyhow::bail!("{what} need the map's f64 values: compute it with ComputeOptions {{ keep_exact: true, .. }}");
    }
    Ok(())
}

/// A force map's NumPy files (`tabor fit --maps PREFIX`): PREFIX_NAME.npy for each of
/// [`crate::fit::MAP_QUANTITIES`] as float64 (ny, nx), NaN where a pixel has no fitted curve, and
/// PREFIX_adequate_model.npy as int8 (0 Hertz, 1 DMT, 2 JKR, 3 Maugis-Dugdale, -1 none).
pub fn write_fit_npy(
    prefix: &str,
    results: &[crate::fit::CurveFit],
    nx: usize,
    ny: usize,
    grid: &[Option<usize>],
) -> anyhow::Result<Vec<String>> {
    let ok = |i: &Option<usize>| {
        i.map(|i| &results[i])
            .filter(|r| r.status == crate::fit::FitStatus::Ok)
    };
    let shape = [ny as u64, nx as u64];
    let mut outs = Vec::new();
    let mut names = Vec::new();
    for q in &crate::fit::MAP_QUANTITIES {
        let name = format!("{prefix}_{}.npy", q.name);
        let mut out = Output::create(&name)?;
        npy_write(
            &mut out,
            &shape,
            grid.iter()
                .map(|i| ok(i).and_then(q.value).unwrap_or(f64::NAN)),
        )?;
        outs.push(out);
        names.push(name);
    }
    let name = format!("{prefix}_adequate_model.npy");
    let mut out = Output::create(&name)?;
    npy_write(
        &mut out,
        &shape,
        grid.iter().map(|i| {
            ok(i)
                .and_then(|r| r.adequate_model)
                // The ladder's index (Hertz 0, DMT 1, JKR 2, MD 3).
                .and_then(|m| crate::fit::Model::ALL.iter().position(|x| *x == m))
                .map_or(-1i8, |i| i as i8)
        }),
    )?;
    outs.push(out);
    names.push(name);
    let name = format!("{prefix}_status.npy");
    let mut out = Output::create(&name)?;
    npy_write(
        &mut out,
        &shape,
        // The index of `PIXEL_STATUSES` (0 ok, ..., 4 no curve).
        grid.iter()
            .map(|i| crate::fit::pixel_status(i.map(|i| &results[i])) as i8),
    )?;
    outs.push(out);
    names.push(name);
    for o in outs {
        o.commit()?;
    }
    Ok(names)
}
