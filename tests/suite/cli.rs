//! The command line end to end: real outputs, and bad input giving a clear error, a non-zero
//! exit and no output file.

use std::process::Command;

fn tabor(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .env("TABOR_BACKEND", "cpu")
        .output()
        .unwrap()
}

#[test]
fn solve_file_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.csv");
    std::fs::write(&input, "id,lambda,load\na,1,0.5\nb,0.1,-1.9\nc,10,-1.6\n").unwrap();
    let out = dir.path().join("out.csv");
    let o = tabor(&[
        "solve",
        "--input",
        input.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "lambda,load,A,approach,m_minus_1,status,method");
    assert_eq!(lines.len(), 4);
    // Row order kept; A at lambda = 1, load 0.5 (f64 solver, 17 digits).
    let a: f64 = lines[1].split(',').nth(2).unwrap().parse().unwrap();
    assert!((a - 1.7289400402050878).abs() < 1e-14);
    assert!(lines[2].ends_with(",ok,md"));
    assert!(lines[3].ends_with(",,,,no_contact,md"), "{}", lines[3]);
}

#[test]
fn bad_input_fails_cleanly_without_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.csv");
    for (content, needle) in [
        ("lambda,load\n1,0.5\n2,x\n", "line 3"),
        ("lambda,force\n1,0.5\n", "no column `load`"),
        ("lambda,load\n0,0.5\n", "must be > 0"),
        ("lambda,load\n1,nan\n", "finite"),
        ("", "empty"),
    ] {
        let input = dir.path().join("in.csv");
        std::fs::write(&input, content).unwrap();
        let o = tabor(&[
            "solve",
            "-i",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{content:?}");
        assert!(err.contains(needle), "{content:?}: {err}");
        assert!(
            !out.exists(),
            "a partial output file was left for {content:?}"
        );
    }
    let o = tabor(&["pulloff", "--lambda", "-1"]);
    assert!(!o.status.success());
    let png = dir.path().join("m.png");
    let o = tabor(&["map", "--tolerance", "2", "--out", png.to_str().unwrap()]);
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("--tolerance"));
    assert!(!png.exists());
}

#[test]
fn pulloff_and_curve_outputs() {
    let o = tabor(&["pulloff", "--lambda", "0.1,1,10", "--format", "csv"]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.starts_with("lambda,load_control_load,load_control_A,"));
    let row: Vec<f64> = text
        .lines()
        .nth(2)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!((row[1] - -1.600734911).abs() < 1e-9 && (row[4] - -0.8917414828).abs() < 1e-9);
    let o = tabor(&[
        "curve", "--lambda", "1", "--points", "50", "--format", "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["points"].as_array().unwrap().len(), 50);
    let o = tabor(&[
        "solve", "--lambda", "1", "--load", "0.5", "--format", "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["results"][0]["status"], "ok");
}

#[test]
fn map_writes_json_and_npy() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let o = tabor(&[
        "map",
        "--nx",
        "40",
        "--ny",
        "30",
        "--out",
        &p("m.png"),
        "--json",
        &p("m.json"),
        "--json-full",
        "--npy",
        &p("m"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p("m.json")).unwrap()).unwrap();
    assert_eq!(v["metadata"]["backend"], "cpu");
    assert_eq!(v["metadata"]["tolerance"], 0.05);
    assert_eq!(v["axes"]["lambda"].as_array().unwrap().len(), 40);
    assert_eq!(v["thresholds"].as_array().unwrap().len(), 40);
    let region = v["points"]["region"].as_array().unwrap();
    assert_eq!(region.len(), 30);
    assert_eq!(region[0].as_array().unwrap().len(), 40);
    let bytes = std::fs::read(p("m_A.npy")).unwrap();
    let npy = npyz::NpyFile::new(&bytes[..]).unwrap();
    assert_eq!(npy.shape(), &[30, 40]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("solve") && err.contains("render"), "{err}");
}

#[test]
fn scene_infer_cycle_bench_and_atlas() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    // A scene in SI units, with the required JSON keys.
    let o = tabor(&["scene", "--preset", "afm-si", "--format", "json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for k in [
        "lambda",
        "tabor_parameter",
        "pulloff_force_load_control_N",
        "pulloff_force_displacement_control_N",
        "zero_load_contact_radius_m",
        "recommended_model",
    ] {
        assert!(!v[k].is_null(), "{k}");
    }
    for k in ["load_n", "contact_radius_m", "approach_m", "model"] {
        assert!(!v["loads"][0][k].is_null(), "loads[0].{k}");
    }
    // Impossible inputs name the field.
    std::fs::write(
        p("bad.json"),
        r#"{"e_star_pa": -1, "radius_m": 1e-6, "work_of_adhesion_j_m2": 0.1, "z0_m": 3e-10}"#,
    )
    .unwrap();
    let o = tabor(&["scene", &p("bad.json")]);
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("e_star_pa"));
    // Inference from a pull-off force.
    let o = tabor(&[
        "infer",
        "--pulloff",
        "-12.2e-9",
        "--radius",
        "20e-9",
        "--e-star",
        "91e9",
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // The MD w and lambda reproduce the measured force: -Pbar_c(lambda) pi w R = 12.2 nN.
    let (w, l) = (
        v["w_md_j_m2"].as_f64().unwrap(),
        v["lambda_md"].as_f64().unwrap(),
    );
    let pc = tabor::solver::LambdaContext::new(l)
        .unwrap()
        .load_pulloff
        .load;
    let f = -pc * std::f64::consts::PI * w * 20e-9;
    assert!((f / 12.2e-9 - 1.0).abs() < 1e-8, "{f}");
    // A cycle: CSV with both phases and a jump.
    let o = tabor(&["cycle", "--lambda", "3", "-o", &p("c.csv")]);
    assert!(o.status.success());
    let text = std::fs::read_to_string(p("c.csv")).unwrap();
    assert!(text.starts_with("phase,branch,approach,load,A,C,control,jump"));
    assert!(text.contains("\nretract,") && text.contains(",1\n"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("energy lost per cycle"));
    // The benchmark and the atlas, small.
    let o = tabor(&["bench", "--quick", "--no-gpu", "--out-dir", &p("b")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p("b/bench.json")).unwrap()).unwrap();
    let names: Vec<&str> = v["results"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert!(
        names.contains(&"cpu-f64") && names.contains(&"cpu-f32-naive") && names.contains(&"cos")
    );
    assert!(std::path::Path::new(&p("b/bench.png")).exists());
    let o = tabor(&[
        "atlas",
        "--no-gpu",
        "--nx",
        "24",
        "--ny",
        "16",
        "--out-dir",
        &p("a"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::path::Path::new(&p("a/naive_f32.png")).exists());
}

#[test]
fn figures_for_print_in_png_svg_and_pdf() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    // The format follows the name; --svg and --pdf add the same figure in those formats.
    let o = tabor(&[
        "plot",
        "pulloff",
        "--out",
        &p("a.pdf"),
        "--svg",
        &p("a.svg"),
        "--width-mm",
        "85",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read(p("a.pdf")).unwrap().starts_with(b"%PDF-"));
    assert!(std::fs::read_to_string(p("a.svg"))
        .unwrap()
        .contains("width=\"85mm\""));
    // 85 mm at 300 dpi is 1004 pixels; two columns at 150 dpi, 1033.
    let o = tabor(&[
        "plot",
        "curves",
        "--out",
        &p("c.png"),
        "--width-mm",
        "85",
        "--dpi",
        "300",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(image::open(p("c.png")).unwrap().width(), 1004);
    let o = tabor(&[
        "plot",
        "curves",
        "--out",
        &p("d.png"),
        "--double-column",
        "--dpi",
        "150",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(image::open(p("d.png")).unwrap().width(), 1033);
    // Bad sizes and formats: one line, no file.
    for (args, needle) in [
        (
            vec!["plot", "curves", "--out", "e.png", "--width-mm", "5"],
            "--width-mm 5",
        ),
        (
            vec!["plot", "curves", "--out", "e.png", "--dpi", "1e9"],
            "--dpi 1e9",
        ),
        (
            vec!["plot", "curves", "--out", "e.jpg"],
            ".png, .svg or .pdf",
        ),
        (
            vec!["plot", "curves", "--out", "e.png", "--pdf", "e.svg"],
            ".pdf",
        ),
    ] {
        let mut a: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        for s in a.iter_mut().filter(|s| s.starts_with("e.")) {
            *s = p(s);
        }
        let a: Vec<&str> = a.iter().map(|s| s.as_str()).collect();
        let o = tabor(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
        assert!(!dir.path().join(a[3].rsplit('/').next().unwrap()).exists());
    }
}
