//! Outputs, messages and settings: two outputs naming one file, a closed stderr, a saved bench
//! that cannot be drawn, `--format` per command, the backend from the environment, and figure
//! legends and titles that fit. Each case was a silent overwrite, a panic, unbounded memory or a
//! hang, a misleading help or message, or a figure cut off.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::Duration;
use tabor::io::output::{check_distinct, output_identity};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_tabor"));
    c.env("TABOR_BACKEND", "cpu").env_remove("TABOR_ADAPTER");
    c
}

/// Runs `c`, killing it after a minute: a guard against hangs, not a timing assertion.
fn finish(mut c: Command, what: &str) -> Output {
    c.stdout(Stdio::piped()).stderr(Stdio::piped());
    let child = c.spawn().unwrap();
    let pid = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(child.wait_with_output().unwrap()));
    match rx.recv_timeout(Duration::from_secs(60)) {
        Ok(o) => o,
        Err(_) => {
            let _ = Command::new("kill").args(["-9", &pid.to_string()]).status();
            panic!("tabor {what} hangs");
        }
    }
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    let mut c = bin();
    c.args(args).current_dir(dir);
    finish(c, &format!("{args:?}"))
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit 1, one `error:` line containing every needle, no panic.
fn refused(o: &Output, needles: &[&str]) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    for n in needles {
        assert!(err.contains(n), "{n:?} not in: {err}");
    }
    assert_eq!(
        err.lines().filter(|l| l.starts_with("error")).count(),
        1,
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    err
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

const SMALL_MAP: [&str; 5] = ["map", "--nx", "8", "--ny", "8"];

fn map_args<'a>(more: &[&'a str]) -> Vec<&'a str> {
    let mut v: Vec<&str> = SMALL_MAP.to_vec();
    v.extend_from_slice(more);
    v
}

// ---- 1. Two outputs that are one file ----

#[test]
fn output_identity_resolves_relative_paths_and_symlinks_without_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().canonicalize().unwrap();
    std::fs::create_dir(d.join("sub")).unwrap();
    // None of these files exists; the folder `sub` does.
    let a = output_identity(&d.join("a.png"));
    assert_eq!(a, d.join("a.png"));
    assert_eq!(output_identity(&d.join("./a.png")), a);
    assert_eq!(output_identity(&d.join("sub/../a.png")), a);
    assert_eq!(output_identity(&d.join("sub/./../sub/../a.png")), a);
    assert_ne!(output_identity(&d.join("sub/a.png")), a);
    assert_eq!(output_identity(Path::new("-")), Path::new("-"));
    #[cfg(unix)]
    {
        // A link to a file that does not exist yet, and a link to the folder.
        std::os::unix::fs::symlink(d.join("a.png"), d.join("link.png")).unwrap();
        assert_eq!(output_identity(&d.join("link.png")), a);
        std::os::unix::fs::symlink(d.join("sub"), d.join("subl")).unwrap();
        assert_eq!(
            output_identity(&d.join("subl/b.png")),
            output_identity(&d.join("sub/b.png"))
        );
    }
}

#[test]
fn check_distinct_refuses_one_file_twice_naming_both_options() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = check_distinct([("--out", d.join("x.png")), ("--json", d.join("./x.png"))])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--out") && e.contains("--json") && e.contains("x.png"),
        "{e}"
    );
    // Two stdouts collide; one is fine; /dev/null may be named any number of times.
    let e = check_distinct([("--output", "-"), ("--plot", "-")])
        .unwrap_err()
        .to_string();
    assert!(e.contains("stdout"), "{e}");
    check_distinct([("--output", "-"), ("--plot", "p.png")]).unwrap();
    check_distinct([("--output", "/dev/null"), ("--json", "/dev/null")]).unwrap();
    check_distinct([("--out", d.join("a.png")), ("--svg", d.join("a.svg"))]).unwrap();
}

#[test]
fn map_refuses_outputs_that_are_one_file_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = run_in(d, &map_args(&["--out", "keep.png", "--json", "keep.png"]));
    refused(&o, &["--out keep.png", "--json keep.png"]);
    let o = run_in(
        d,
        &map_args(&["--out", "m.png", "--svg", "m.svg", "--json", "m.svg"]),
    );
    refused(&o, &["--svg m.svg", "--json m.svg"]);
    let o = run_in(
        d,
        &map_args(&["--out", "m.png", "--npy", "p", "--json", "p_lambda.npy"]),
    );
    refused(&o, &["--npy", "--json", "p_lambda.npy"]);
    std::fs::create_dir(d.join("sub")).unwrap();
    let o = run_in(
        d,
        &map_args(&[
            "--out",
            "./m.png",
            "--svg",
            "m.svg",
            "--json",
            "sub/../m.svg",
        ]),
    );
    refused(&o, &["--svg m.svg", "--json sub/../m.svg"]);
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("target.json", d.join("l.json")).unwrap();
        let o = run_in(
            d,
            &map_args(&["--out", "m.png", "--json", "l.json", "--npy", "target.json"]),
        );
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        std::fs::remove_file(d.join("l.json")).unwrap();
        std::os::unix::fs::symlink("m.png", d.join("l.json")).unwrap();
        let o = run_in(
            d,
            &map_args(&[
                "--out", "m2.png", "--json", "l.json", "--svg", "x.svg", "--pdf", "m.pdf",
            ]),
        );
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        std::fs::remove_file(d.join("l.json")).unwrap();
        std::os::unix::fs::symlink("m3.png", d.join("l.json")).unwrap();
        let o = run_in(d, &map_args(&["--out", "m3.png", "--json", "l.json"]));
        refused(&o, &["--out m3.png", "--json l.json"]);
        assert!(!d.join("m3.png").exists());
    }
    // Nothing was written by the refused runs.
    for f in files_in(d) {
        assert!(!f.starts_with("keep") && !f.starts_with("p_"), "{f}");
    }
}

#[test]
fn other_commands_refuse_outputs_that_are_one_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "scene", "--preset", "afm-si", "-o", "x.svg", "--plot", "x.svg",
        ],
        vec!["cycle", "--lambda", "1", "-o", "c.png", "--plot", "c.png"],
        vec![
            "profile", "--lambda", "1", "--load", "1", "-o", "p.svg", "--plot", "./p.svg",
        ],
        vec![
            "fit",
            "-i",
            "none.csv",
            "--radius",
            "2e-8",
            "--spring-n-m",
            "40",
            "-o",
            "f.svg",
            "--plot",
            "f.svg",
        ],
        vec![
            "fit",
            "-i",
            "none.csv",
            "--radius",
            "2e-8",
            "--spring-n-m",
            "40",
            "-o",
            "mp_e_star.npy",
            "--maps",
            "mp",
        ],
        vec![
            "fit",
            "-i",
            "none.csv",
            "--radius",
            "2e-8",
            "--spring-n-m",
            "40",
            "--plot",
            "a.png",
            "--on-map",
            "a.png",
        ],
    ];
    for args in &cases {
        let o = run_in(d, args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("are the same file"), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    assert!(files_in(d).is_empty(), "{:?}", files_in(d));
    // plot: the formats differ, but the link makes them one file.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("q.png", d.join("q.svg")).unwrap();
        let o = run_in(
            d,
            &[
                "plot", "curves", "--lambda", "1", "--out", "q.png", "--svg", "q.svg",
            ],
        );
        refused(&o, &["--out q.png", "--svg q.svg", "are the same file"]);
        assert!(!d.join("q.png").exists());
    }
}

// ---- 2. A closed stderr ----

#[test]
fn a_closed_stderr_pipe_is_no_panic_and_the_outputs_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.png");
    let mut c = bin();
    c.args(map_args(&["--out", out.to_str().unwrap()]))
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let mut child = c.spawn().unwrap();
    // The reader goes away before tabor writes its first message (`2>&1 | head -0`).
    drop(child.stderr.take());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0));
    assert_eq!(&std::fs::read(&out).unwrap()[1..4], b"PNG");
}

#[cfg(unix)]
#[test]
fn stderr_closed_at_start_writes_the_output_and_only_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.json");
    let exe = env!("CARGO_BIN_EXE_tabor");
    let mut c = Command::new("sh");
    c.arg("-c")
        .arg(format!(
            "exec \"{exe}\" solve --lambda 1 --load 0.5 --format json -o \"{}\" 2>&-",
            out.display()
        ))
        .env("TABOR_BACKEND", "cpu");
    let o = finish(c, "solve with stderr closed");
    assert_eq!(o.status.code(), Some(0));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    // The known answer of the crate's documentation example.
    let a = v["results"][0]["A"].as_f64().unwrap();
    assert!((a - 1.7289400402050878).abs() < 1e-12, "{a}");
}

// ---- 3. bench --replot of a saved file that cannot be drawn ----

fn bench_json(speeds: &[&str]) -> String {
    let results: Vec<String> = speeds
        .iter()
        .enumerate()
        .map(|(i, s)| {
            format!(
                r#"{{"name":"cpu{i}","description":"d","points":1,"seconds":1,"points_per_second":{s},"max_rel_err":1e-10,"median_rel_err":1e-12,"p99_rel_err":1e-11,"max_rel_err_away":1e-10,"failures":0}}"#
            )
        })
        .collect();
    format!(
        r#"{{"metadata":{{"machine":"test"}},"results":[{}]}}"#,
        results.join(",")
    )
}

#[test]
fn bench_replot_refuses_what_it_cannot_draw_and_draws_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, speeds, needle) in [
        ("empty.json", vec![], "\"results\" is empty"),
        ("zero.json", vec!["1e6", "0"], "points_per_second = 0"),
        ("huge.json", vec!["1e308"], "points_per_second = 1e308"),
    ] {
        std::fs::write(d.join(name), bench_json(&speeds)).unwrap();
        let o = run_in(d, &["bench", "--replot", name, "--out-dir", "out"]);
        refused(&o, &["--replot", name, needle]);
    }
    assert!(!d.join("out").exists());
    std::fs::write(d.join("ok.json"), bench_json(&["1e6", "3e8"])).unwrap();
    let o = run_in(d, &["bench", "--replot", "ok.json", "--out-dir", "out"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        &std::fs::read(d.join("out/bench.png")).unwrap()[1..4],
        b"PNG"
    );
    let svg = std::fs::read_to_string(d.join("out/bench.svg")).unwrap();
    assert!(svg.contains("cpu1"), "the markers' labels are drawn");
}

// ---- 4. --format lists what each command writes ----

#[test]
fn format_help_lists_only_the_formats_each_command_accepts() {
    let dir = tempfile::tempdir().unwrap();
    for (cmd, listed, refused_one) in [
        ("solve", "text, csv, json", None),
        ("pulloff", "text, csv, json", None),
        ("curve", "csv, json", Some("text")),
        ("fit", "csv, json", Some("text")),
        ("cycle", "csv, json", Some("text")),
        ("profile", "csv, json", Some("text")),
        ("rough", "csv, json", Some("text")),
        ("rough-pulloff", "csv, json", Some("text")),
        ("scene", "text, json", Some("csv")),
        ("infer", "text, json", Some("csv")),
    ] {
        let o = run_in(dir.path(), &[cmd, "--help"]);
        assert_eq!(o.status.code(), Some(0));
        let help = String::from_utf8_lossy(&o.stdout).into_owned();
        let at = help
            .find("--format")
            .unwrap_or_else(|| panic!("{cmd}: {help}"));
        let line = &help[at..];
        let pv = &line[line.find("possible values: ").expect(cmd) + 17..];
        let pv = &pv[..pv.find(']').unwrap()];
        assert_eq!(pv, listed, "{cmd}");
        if let Some(f) = refused_one {
            let o = run_in(dir.path(), &[cmd, "--format", f]);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(1), "{cmd}: {err}");
            assert!(
                err.contains(&format!("invalid value '{f}' for '--format")),
                "{err}"
            );
            assert!(
                err.contains(&format!("[possible values: {listed}]")),
                "{err}"
            );
        }
    }
}

// ---- 5. The backend from the environment ----

#[test]
fn backend_from_the_environment_is_named_as_such_and_empty_is_unset() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut c = bin();
    c.env("TABOR_BACKEND", "garbage")
        .args(map_args(&["--out", "g.png"]))
        .current_dir(d);
    let o = finish(c, "TABOR_BACKEND=garbage");
    let err = refused(&o, &["TABOR_BACKEND", "garbage", "auto, gpu or cpu"]);
    assert!(!err.contains("--backend <"), "{err}");
    assert!(!d.join("g.png").exists());
    // An empty one is unset: solve's default (cpu) applies.
    std::fs::write(d.join("pts.csv"), "lambda,load\n1,0.5\n").unwrap();
    let mut c = bin();
    c.env("TABOR_BACKEND", "")
        .args(["solve", "--input", "pts.csv", "--format", "csv"])
        .current_dir(d);
    let o = finish(c, "TABOR_BACKEND=");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("CPU"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("TABOR_BACKEND"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("--backend"), "{}", stderr(&o));
    // The flag wins over the environment.
    let mut c = bin();
    c.env("TABOR_BACKEND", "garbage")
        .args(map_args(&["--out", "f.png", "--backend", "cpu"]))
        .current_dir(d);
    let o = finish(c, "--backend cpu over TABOR_BACKEND=garbage");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn an_adapter_with_the_cpu_backend_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let o = run_in(
        dir.path(),
        &map_args(&[
            "--out",
            "a.png",
            "--adapter",
            "nonsense",
            "--backend",
            "cpu",
        ]),
    );
    refused(&o, &["--adapter \"nonsense\"", "--backend cpu"]);
    assert!(!dir.path().join("a.png").exists());
    // TABOR_ADAPTER is a global setting: the CPU backend does not use it, and runs.
    let mut c = bin();
    c.env("TABOR_ADAPTER", "nonsense")
        .args(map_args(&["--out", "b.png"]))
        .current_dir(dir.path());
    let o = finish(c, "TABOR_ADAPTER with cpu");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

// ---- 6. Legends and titles that fit ----

#[test]
fn many_curves_get_one_legend_entry_and_short_labels() {
    let dir = tempfile::tempdir().unwrap();
    let lambdas: Vec<String> = (0..201)
        .map(|i| format!("{}", 0.1 * i as f64 + 0.1))
        .collect();
    assert!(
        lambdas.iter().any(|l| l.len() > 15),
        "17-digit values are in the list"
    );
    let all = lambdas.join(",");
    let o = run_in(
        dir.path(),
        &["plot", "curves", "--lambda", &all, "--out", "c.svg"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(dir.path().join("c.svg")).unwrap();
    assert_eq!(svg.matches("MD, ").count(), 1, "one MD entry in the legend");
    assert!(svg.contains("201 curves"), "the legend says how many");
    assert!(!svg.contains("0000000"), "no 17-digit labels");
    // A few curves: one entry each, lambda in short form.
    assert_eq!(tabor::render::plots::curve_label(0.1 + 0.2), "MD, λ = 0.3");
    let o = run_in(
        dir.path(),
        &[
            "plot",
            "curves",
            "--lambda",
            "0.30000000000000004,1,10",
            "--out",
            "d.svg",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(dir.path().join("d.svg")).unwrap();
    assert_eq!(svg.matches("MD, ").count(), 3);
    assert!(svg.contains("λ = 0.3"), "short label");
    assert!(!svg.contains("0.30000000000000004"), "no 17-digit label");
}

#[test]
fn a_title_too_long_for_its_panel_is_set_smaller() {
    use plotters::prelude::*;
    let mut buf = String::new();
    let root = SVGBackend::with_string(&mut buf, (600, 400)).into_drawing_area();
    let short = "A map";
    // A title about 1.5 times the panel's width at size 40.
    let words = "a title longer than the panel it is written over, cut at both ends of the figure";
    let cut = (1..=words.len())
        .filter(|&i| words.is_char_boundary(i))
        .find(|&i| tabor::render::text_width(&root, &words[..i], 40.0) > 900)
        .unwrap();
    let long = &words[..cut];
    let s = tabor::render::fitting_size(&root, short, 40.0);
    assert_eq!(s, 40.0);
    let l = tabor::render::fitting_size(&root, long, 40.0);
    assert!(l < 40.0, "{l}");
    let w = tabor::render::text_width(&root, long, l);
    assert!(w <= 600, "{w} pixels at size {l}");
}
