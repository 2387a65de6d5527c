//! Hostile and careless input to every command: each case was a wrong answer marked ok, a hang,
//! a clobbered or half-written file, unbounded memory or a panic, and is now one clear line and a
//! non-zero exit, or the right answer.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::Duration;

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_tabor"));
    c.env("TABOR_BACKEND", "cpu");
    c
}

/// Runs tabor, killing it after a minute: a guard against hangs (which these cases were), not a
/// timing assertion.
fn run_in(dir: Option<&Path>, args: &[&str]) -> Output {
    let mut c = bin();
    c.args(args).stdout(Stdio::piped()).stderr(Stdio::piped());
    if let Some(d) = dir {
        c.current_dir(d);
    }
    let child = c.spawn().unwrap();
    let pid = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(child.wait_with_output().unwrap()));
    match rx.recv_timeout(Duration::from_secs(60)) {
        Ok(o) => o,
        Err(_) => {
            let _ = Command::new("kill").args(["-9", &pid.to_string()]).status();
            panic!("tabor {args:?} hangs");
        }
    }
}

fn run(args: &[&str]) -> Output {
    run_in(None, args)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A refusal: exit 1, one error line naming `needle`, no panic, nothing on stdout.
fn refused(args: &[&str], needle: &str) {
    let o = run(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert_eq!(
        err.lines().filter(|l| l.starts_with("error")).count(),
        1,
        "{args:?}: {err}"
    );
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    let out = stdout(&o);
    assert!(
        !out.contains("NaN") && !out.contains("inf"),
        "{args:?}: {out}"
    );
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn lambda_outside_the_domain_is_refused_everywhere() {
    // Beyond the exact solver's 1e-26..1e26 only `solve` answers (by the closed-form limits,
    // up to 1e-300 and 1e150); every other command refuses, and `solve` beyond the limits.
    for l in ["1e-28", "1e-40", "1e30", "1e160", "1e300", "-1"] {
        refused(&["pulloff", "--lambda", l], "1e-26..1e26");
        refused(&["curve", "--lambda", l], "1e-26..1e26");
        refused(&["cycle", "--lambda", l], "1e-26..1e26");
        refused(&["profile", "--lambda", l, "--load", "0"], "1e-26..1e26");
        refused(&["solve", "--lambda", l, "--radius-a", "1"], "1e-26..1e26");
    }
    for l in ["1e-301", "1e160", "1e300", "-1"] {
        refused(&["solve", "--lambda", l, "--load", "1"], "1e26..1e150");
    }
    refused(
        &["map", "--lambda-min", "1e200", "--lambda-max", "1e201"],
        "--lambda-min",
    );
    // The limits themselves are inside: the solver certifies them.
    for l in ["1e-26", "1e26"] {
        let o = run(&["solve", "--lambda", l, "--load", "1", "--format", "csv"]);
        assert!(
            o.status.success() && stdout(&o).trim_end().ends_with(",ok,md"),
            "{}",
            stdout(&o)
        );
    }
}

#[test]
fn out_of_domain_rows_of_a_file_are_marked_not_filled() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.csv");
    std::fs::write(&input, "lambda,load\n1e-301,1\n1e200,1\n1,1e13\n1,0.5\n").unwrap();
    let o = run(&["solve", "-i", input.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let rows: Vec<&str> = text.lines().skip(1).collect();
    for r in &rows[..3] {
        assert!(r.contains(",,,,invalid_input,"), "{r}");
    }
    assert!(rows[0].ends_with(",invalid_input,") && rows[2].ends_with(",invalid_input,md"));
    assert!(rows[3].ends_with(",ok,md"));
}

#[test]
fn values_outside_the_domain_are_refused() {
    refused(&["solve", "--lambda", "1", "--load", "1e13"], "-1e12..1e12");
    refused(
        &["solve", "--lambda", "1", "--approach", "1e300"],
        "approach",
    );
    refused(
        &[
            "curve", "--lambda", "1", "--a-max", "1e300", "--points", "3",
        ],
        "--a-max",
    );
    refused(
        &["cycle", "--lambda", "1", "--max-load", "1e20"],
        "the largest load of the approach",
    );
    refused(
        &[
            "infer",
            "--pulloff=-1e300",
            "--radius",
            "1e-8",
            "--e-star",
            "1e11",
        ],
        "pulloff_force_n = -1e300",
    );
}

fn scene_file(dir: &Path, json: &str) -> String {
    let p = dir.join("scene.json");
    std::fs::write(&p, json).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn scene_inputs_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let base = |extra: &str, w: &str| {
        format!(
            r#"{{"e_star_pa": 1e9, "radius_m": 1e-6, "work_of_adhesion_j_m2": {w}, "z0_m": 3e-10{extra}}}"#
        )
    };
    // A tiny w gives a lambda far outside the domain: refused, never "NaN N".
    refused(
        &["scene", &scene_file(dir.path(), &base("", "1e-200"))],
        "Maugis parameter",
    );
    // E* = 1e300: the message gives lambda in short form.
    let f = scene_file(dir.path(), &base("", "0.05").replace("1e9", "1e300"));
    refused(&["scene", &f], "lambda of these inputs = ");
    refused(
        &[
            "scene",
            &scene_file(dir.path(), &base(r#", "shear_strength_pa": -1"#, "0.05")),
        ],
        "shear_strength_pa",
    );
    refused(
        &[
            "scene",
            &scene_file(
                dir.path(),
                &base(r#", "load_range_n": [0, 1e-6, 100000000]"#, "0.05"),
            ),
        ],
        "number of loads",
    );
    // A typo in a body's key is an error naming it, not silently a flat.
    let typo = r#"{"body1": {"youngs_modulus_pa": 1e9, "poisson_ratio": 0.3, "radius_m": 1e-6},
                  "body2": {"youngs_modulus_pa": 1e9, "poisson_ratio": 0.3, "radius": 1e-6},
                  "work_of_adhesion_j_m2": 0.05, "z0_m": 3e-10}"#;
    refused(
        &["scene", &scene_file(dir.path(), typo)],
        "unknown field `radius`",
    );
    refused(
        &["scene", "--preset", "afm-si", "--format", "csv"],
        "invalid value 'csv' for '--format",
    );
}

#[test]
fn ill_posed_pair_fits_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, body: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, format!("load_n,contact_radius_m\n{body}")).unwrap();
        p.to_str().unwrap().to_string()
    };
    let identical = write("same.csv", "1e-6,1e-6\n1e-6,1e-6\n1e-6,1e-6\n");
    refused(
        &["infer", "--pairs", &identical, "--radius", "1e-3"],
        "two different loads",
    );
    let constant = write("const.csv", "1e-6,2e-6\n2e-6,2e-6\n3e-6,2e-6\n");
    refused(
        &["infer", "--pairs", &constant, "--radius", "1e-3"],
        "grows with the load",
    );
    let tensile = write("below.csv", "-1,1e-6\n-0.9,2e-6\n-0.8,3e-6\n");
    refused(&["infer", "--pairs", &tensile, "--radius", "1e-3"], "");
    let inf = write("inf.csv", "1e-6,1e-6\n2e-6,inf\n");
    refused(&["infer", "--pairs", &inf, "--radius", "1e-3"], "line 3");
    // `-` is stdin.
    let mut child = bin()
        .args(["infer", "--pairs", "-", "--radius", "1e-3"])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"load_n,contact_radius_m\n1e-6,1e-6\n1e-6,1e-6\n")
        .unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(stderr(&o).contains("two different loads"), "{}", stderr(&o));
}

#[test]
fn a_large_final_load_keeps_the_cycle_loop() {
    let o = run(&["cycle", "--lambda", "1", "--max-load", "1e10"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let w: f64 = err
        .split("energy lost per cycle: ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!((w - 0.4963).abs() < 2e-3, "{err}");
}

#[test]
fn former_hangs_draw_or_refuse() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("q.png");
    let png = png.to_str().unwrap();
    // Every point below the pull-off: an empty colour scale, drawn.
    let o = run(&[
        "map",
        "--nx",
        "2",
        "--ny",
        "2",
        "--quantity",
        "a",
        "--load-axis",
        "linear",
        "--load-min",
        "-5",
        "--load-max",
        "-3",
        "--out",
        png,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    refused(
        &[
            "map",
            "--nx",
            "2",
            "--ny",
            "2",
            "--lambda-min",
            "1e-160",
            "--lambda-max",
            "1e150",
        ],
        "--lambda-min",
    );
    refused(
        &[
            "map",
            "--nx",
            "2",
            "--ny",
            "2",
            "--load-min",
            "1e-200",
            "--load-max",
            "1e200",
        ],
        "1e-15..1e12",
    );
    refused(
        &[
            "map",
            "--nx",
            "4",
            "--ny",
            "4",
            "--load-axis",
            "linear",
            "--load-min=-1e308",
            "--load-max",
            "1e308",
        ],
        "-1e12..1e12",
    );
    // The widest axes the domain allows are drawn.
    for args in [
        vec![
            "--lambda-min",
            "1e-8",
            "--lambda-max",
            "1e8",
            "--load-min",
            "1e-15",
            "--load-max",
            "1e12",
        ],
        vec![
            "--load-axis",
            "linear",
            "--load-min=-1e12",
            "--load-max",
            "1e12",
        ],
        vec![
            "--load-axis",
            "above-pulloff",
            "--load-min",
            "1e-15",
            "--load-max",
            "1e12",
        ],
    ] {
        let mut a = vec!["map", "--nx", "16", "--ny", "16", "--out", png];
        a.extend(args);
        let o = run(&a);
        assert!(o.status.success(), "{a:?}: {}", stderr(&o));
    }
}

#[cfg(unix)]
#[test]
fn outputs_follow_links_and_write_into_devices() {
    let dir = tempfile::tempdir().unwrap();
    let real = dir.path().join("real.csv");
    std::fs::write(&real, "old").unwrap();
    let link = dir.path().join("link.csv");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let o = run(&[
        "pulloff",
        "--lambda",
        "1",
        "--format",
        "csv",
        "-o",
        link.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(&real)
        .unwrap()
        .starts_with("lambda,"));
    let o = run(&["pulloff", "--lambda", "1", "-o", "/dev/null"]);
    assert!(o.status.success(), "{}", stderr(&o));
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
    assert_eq!(files_in(dir.path()), ["link.csv", "real.csv"]);
}

#[cfg(unix)]
#[test]
fn interrupted_writes_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    for signal in ["INT", "TERM"] {
        let out = dir.path().join("out.csv");
        let mut child = bin()
            .args(["solve", "-i", "-", "-o", out.to_str().unwrap()])
            .stdin(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut stdin = child.stdin.take().unwrap();
        stdin.write_all(b"lambda,load\n").unwrap();
        // Rows until the output's temporary file exists (the first chunk was written).
        let row = "0.5,1.0\n".repeat(1 << 16);
        while files_in(dir.path()).is_empty() {
            stdin.write_all(row.as_bytes()).unwrap();
        }
        let kill = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(kill.success());
        let o = child.wait_with_output().unwrap();
        drop(stdin);
        assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
        assert!(
            files_in(dir.path()).is_empty(),
            "left behind: {:?}",
            files_in(dir.path())
        );
    }
}

#[test]
fn map_outputs_are_checked_before_the_work_and_written_together() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    // A JSON path that cannot be written: refused before anything is computed or written.
    let o = run(&[
        "map",
        "--nx",
        "8",
        "--ny",
        "8",
        "--out",
        &p("m.png"),
        "--svg",
        &p("m.svg"),
        "--json",
        &p("no/such/dir/m.json"),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--json"), "{}", stderr(&o));
    assert!(
        !stderr(&o).contains("backend"),
        "computed before failing: {}",
        stderr(&o)
    );
    assert!(
        files_in(dir.path()).is_empty(),
        "{:?}",
        files_in(dir.path())
    );
    // Formats follow the names.
    refused(
        &["map", "--nx", "8", "--ny", "8", "--out", &p("x.txt")],
        ".png, .svg or .pdf",
    );
    refused(
        &[
            "plot",
            "pulloff",
            "--out",
            &p("x.png"),
            "--svg",
            &p("x.png"),
        ],
        ".svg",
    );
    assert!(files_in(dir.path()).is_empty());
    // The same command gives the same bytes (timings only with --timings).
    let json = |name: &str, extra: &[&str]| {
        let png = p("m.png");
        let mut a = vec!["map", "--nx", "16", "--ny", "16", "--out", &png];
        let j = p(name);
        a.extend(["--json", j.as_str()]);
        a.extend(extra);
        let o = run(&a);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(&j).unwrap()
    };
    assert_eq!(json("a.json", &[]), json("b.json", &[]));
    let t = String::from_utf8(json("c.json", &["--timings"])).unwrap();
    assert!(t.contains("timings_s"));
    // --json-full streams the per-point arrays: valid JSON with ny rows of nx.
    let full = json("d.json", &["--json-full"]);
    let v: serde_json::Value = serde_json::from_slice(&full).unwrap();
    let a = v["points"]["A"].as_array().unwrap();
    assert_eq!((a.len(), a[0].as_array().unwrap().len()), (16, 16));
    assert_eq!(v["points"]["region"][15][15], "hertz");
}

#[test]
fn closed_pipes_end_quietly_and_full_disks_are_errors() {
    for args in [
        vec!["info"],
        vec![
            "infer",
            "--pulloff",
            "1e-8",
            "--radius",
            "1e-8",
            "--e-star",
            "1e11",
        ],
        vec!["pulloff", "--lambda", "0.1,1,10"],
    ] {
        // stdout closed before tabor writes.
        let mut child = bin()
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let o = child.wait_with_output().unwrap();
        assert!(!stderr(&o).contains("panicked"), "{args:?}: {}", stderr(&o));
        assert_ne!(o.status.code(), Some(101), "{args:?}");
        #[cfg(target_os = "linux")]
        {
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let o = bin()
                .args(&args)
                .stdout(full)
                .stderr(Stdio::piped())
                .output()
                .unwrap();
            assert_eq!(o.status.code(), Some(1), "{args:?}");
            assert!(
                stderr(&o).contains("No space left"),
                "{args:?}: {}",
                stderr(&o)
            );
        }
    }
}

/// `tabor solve ... >&-`: stdout closed before tabor starts. The results would vanish, so it
/// must not exit 0; `/dev/null` given by the caller, write-only or read-write, is the user's
/// choice and succeeds.
#[cfg(target_os = "linux")]
#[test]
fn a_closed_stdout_is_an_error_and_dev_null_is_not() {
    let exe = env!("CARGO_BIN_EXE_tabor");
    // `1<> /dev/null` is how a program's caller often discards it (Python's subprocess.DEVNULL).
    for (redirect, code) in [
        (">&-", Some(1)),
        ("> /dev/null", Some(0)),
        ("1<> /dev/null", Some(0)),
    ] {
        let o = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "exec \"$0\" solve --lambda 1 --load 0.5 --format csv {redirect}"
            ))
            .arg(exe)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), code, "{redirect}: {}", stderr(&o));
        if code == Some(1) {
            let e = stderr(&o);
            assert!(
                e.contains("stdout is closed") && e.trim().lines().count() == 1,
                "{e}"
            );
        }
    }
}

#[test]
fn sizes_beyond_the_memory_bound_are_refused_up_front() {
    refused(
        &["map", "--nx", "16384", "--ny", "16384", "--quantity", "a"],
        "4096 x 4096",
    );
    refused(
        &["curve", "--lambda", "1", "--points", "100000000"],
        "--points",
    );
    let o = run(&["solve", "-i", "/dev/zero"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("not a CSV table"), "{}", stderr(&o));
}

/// `rough-map --json-full` streams its per-point arrays: a 1024 x 1024 map's held as JSON values
/// and one string took over 600 MB; streamed, the map's own arrays (about 60 MB) are the bulk.
#[cfg(target_os = "linux")]
#[test]
fn a_full_rough_map_json_streams_in_bounded_memory() {
    if Command::new("prlimit").arg("--version").output().is_err() {
        eprintln!("SKIPPED: no prlimit");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("rough.json");
    let o = Command::new("prlimit")
        .arg(format!("--as={}", 400 << 20))
        .arg(env!("CARGO_BIN_EXE_tabor"))
        .args([
            "rough-map",
            "--nx",
            "1024",
            "--ny",
            "1024",
            "--check",
            "0",
            "--backend",
            "cpu",
        ])
        .args(["--json-full", "--json", json.to_str().unwrap()])
        .args(["--out", dir.path().join("rough.png").to_str().unwrap()])
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    for key in ["pulloff", "relative_pulloff", "region", "jkr_error"] {
        assert_eq!(j[key].as_array().map(|a| a.len()), Some(1 << 20), "{key}");
    }
}

/// A solve whose input and output are several times the memory it may use: it streams.
#[cfg(target_os = "linux")]
#[test]
fn large_solves_run_in_bounded_memory() {
    if Command::new("prlimit").arg("--version").output().is_err() {
        eprintln!("SKIPPED: no prlimit");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.csv");
    let rows = 3_000_000;
    // 3e6 rows: 33 MB in, 330 MB out; held in memory at once they took over 600 MB.
    let mut child = Command::new("prlimit")
        .arg(format!("--as={}", 300 << 20))
        .arg(env!("CARGO_BIN_EXE_tabor"))
        .args([
            "solve",
            "-i",
            "-",
            "-o",
            out.to_str().unwrap(),
            "--backend",
            "cpu",
        ])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        stdin.write_all(b"lambda,load\n").unwrap();
        let block: String = (0..1000).map(|i| format!("0.5,{i}.25\n")).collect();
        for _ in 0..rows / 1000 {
            stdin.write_all(block.as_bytes()).unwrap();
        }
    });
    writer.join().unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    // No progress bar chatter where stderr is not a terminal.
    assert!(!stderr(&o).contains('\r'));
    let f = std::io::BufReader::new(std::fs::File::open(&out).unwrap());
    use std::io::BufRead;
    let (mut n, mut last) = (0usize, String::new());
    for l in f.lines() {
        last = l.unwrap();
        n += 1;
    }
    assert_eq!(n, rows + 1);
    assert!(
        last.starts_with("5.0000000000000000e-1,9.9925000000000000e2,") && last.ends_with(",ok,md"),
        "{last}"
    );
}

#[test]
fn messages_name_the_input_the_value_and_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.csv");
    std::fs::write(&input, "1,2\n3,4\n").unwrap();
    let o = run(&["solve", "-i", input.to_str().unwrap()]);
    let err = stderr(&o);
    assert!(
        err.contains("no column `lambda`") && err.contains("`lambda,load`"),
        "{err}"
    );
    assert!(!err.contains("`lambda` and `lambda`"), "{err}");
    refused(&["solve", "--lambda", "-1", "--load", "1"], "lambda = -1");
    refused(
        &[
            "solve",
            "--lambda",
            "1",
            "--load",
            "1",
            "--control",
            "displacement",
        ],
        "--approach",
    );
    refused(
        &["curve", "--lambda", "1", "--format", "text"],
        "invalid value 'text' for '--format",
    );
    refused(
        &[
            "cycle",
            "--lambda",
            "1",
            "--control",
            "grips",
            "--stiffness",
            "2",
        ],
        "--control spring",
    );
    refused(
        &[
            "infer",
            "--pulloff",
            "1e-8",
            "--radius",
            "1e-8",
            "--e-star",
            "1e11",
            "--format",
            "csv",
        ],
        "invalid value 'csv' for '--format",
    );
    // atlas into a path that is a file: the message names it.
    let file = dir.path().join("taken");
    std::fs::write(&file, "").unwrap();
    refused(
        &[
            "atlas",
            "--nx",
            "2",
            "--ny",
            "2",
            "--no-gpu",
            "--out-dir",
            file.to_str().unwrap(),
        ],
        "taken",
    );
    // The driver's XDG_RUNTIME_DIR complaint is not ours to print.
    let o = bin()
        .arg("info")
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .unwrap();
    let all = format!("{}{}", stdout(&o), stderr(&o));
    assert!(!all.contains("XDG_RUNTIME_DIR"), "{all}");
}

/// The long options of `tabor SUB` that take a value, from its --help.
fn valued_flags(sub: &str) -> Vec<String> {
    let help = stdout(&run(&[sub, "--help"]));
    let mut flags: Vec<String> = help
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            // `-o, --output`: the long name after the short one.
            let l = match l.as_bytes() {
                [b'-', _, b',', b' ', ..] => &l[4..],
                _ => l,
            };
            let rest = l.strip_prefix("--")?;
            let (name, after) = rest.split_once(' ')?;
            after.starts_with('<').then(|| format!("--{name}"))
        })
        .collect();
    flags.dedup();
    flags
}

#[test]
fn negative_numbers_are_values_of_every_option() {
    // clap took `-1e-3` (a signed exponent) and `-.5` for short flags: "unexpected argument
    // '-1'". Every option of every command that takes a value now takes them; the stray flag
    // after it shows that the value was consumed (parsing stops there, nothing runs).
    let help = stdout(&run(&["--help"]));
    let subs: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|s| *s != "help")
        .collect();
    assert!(subs.len() >= 17, "{subs:?}");
    let mut checked = 0;
    for sub in &subs {
        for flag in valued_flags(sub) {
            for value in ["-1e-3", "-.5", "-1E+2"] {
                let o = run(&[sub, &flag, value, "--no-such-flag"]);
                let err = stderr(&o);
                assert!(
                    err.contains("unexpected argument '--no-such-flag'")
                        || err.contains(&format!("invalid value '{value}' for '{flag}")),
                    "tabor {sub} {flag} {value}: {err}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 300, "{checked} options checked");
    // The values arrive: the approach ends at the smallest separation given.
    let o = run(&[
        "rough",
        "--lambda",
        "1",
        "--sigma",
        "0.5",
        "--min-separation",
        "-1e-3",
        "--points",
        "3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let last = v["approach"]["separation"][2].as_f64().unwrap();
    assert!((last + 1e-3).abs() < 1e-15, "{last}");
    // Several values, a negative one among them, and an option after them.
    refused(
        &["pulloff", "--lambda", "1", "-1e-3", "2", "--format", "json"],
        "lambda = -0.001 is outside",
    );
    // A missing value is still one: the flag after it is not taken for it.
    let o = run(&["solve", "--lambda", "1", "--load", "--format", "json"]);
    assert!(
        stderr(&o).contains("a value is required for '--load"),
        "{}",
        stderr(&o)
    );
}

/// The width of a PNG in pixels (its IHDR).
fn png_width(path: &Path) -> u32 {
    let b = std::fs::read(path).unwrap();
    u32::from_be_bytes([b[16], b[17], b[18], b[19]])
}

#[test]
fn figure_width_help_says_each_commands_default() {
    // `rough --help` said 85 mm; its figure (two panels) is 175 mm wide.
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    for (sub, mm, args) in [
        (
            "rough",
            175.0,
            vec![
                "--lambda",
                "1",
                "--sigma",
                "0.5",
                "--min-separation",
                "-1",
                "--points",
                "3",
                "-o",
                "/dev/null",
                "--plot",
            ],
        ),
        (
            "rough-pulloff",
            85.0,
            vec![
                "--lambda",
                "1",
                "--points",
                "2",
                "-o",
                "/dev/null",
                "--plot",
            ],
        ),
    ] {
        let help = stdout(&run(&[sub, "--help"]));
        let columns = if mm > 100.0 {
            "two journal columns"
        } else {
            "one journal column"
        };
        assert!(
            help.contains(&format!("[default: {mm}, {columns}]")),
            "{sub}: {help}"
        );
        let png = p(&format!("{sub}.png"));
        let mut a = vec![sub];
        a.extend(args);
        a.push(&png);
        let o = run(&a);
        assert!(o.status.success(), "{}", stderr(&o));
        // 300 dpi.
        assert_eq!(
            png_width(Path::new(&png)),
            (mm / 25.4 * 300.0_f64).round() as u32,
            "{sub}"
        );
    }
    for sub in [
        "map",
        "plot",
        "scene",
        "cycle",
        "humidity",
        "profile",
        "fit",
        "rough-map",
    ] {
        let help = stdout(&run(&[sub, "--help"]));
        assert!(
            help.contains("[default: 85, one journal column]"),
            "{sub}: {help}"
        );
    }
}

#[test]
fn rough_refusals_say_what_is_wrong_in_the_inputs_given() {
    // The default largest separation: no --max-separation was given.
    let base = ["rough", "--sigma", "0.5", "--points", "3"];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        base.iter().copied().chain(extra.iter().copied()).collect()
    };
    refused(
        &with(&["--lambda", "1e-7", "--min-separation", "-1"]),
        "the summits feel the flat out to 6366202 approach units",
    );
    refused(
        &with(&["--lambda", "1", "--min-separation", "100"]),
        "--min-separation = 100 is beyond the summits' reach (5.24173 approach units",
    );
    // Two zones: the quantities given, short numbers, the span of the stress numbers.
    refused(
        &["pulloff", "--lambda", "1", "--stress-ratio", "1e-9", "--range-ratio", "3"],
        "--lambda 1, --stress-ratio 1e-9 (rho), --range-ratio 3 (eta): the second zone's stress number rho lambda_s (1 + rho eta)^(-1/3) = 1e-9 is outside 1e-8..1e6",
    );
    refused(
        &["pulloff", "--lambda", "1e20", "--stress-ratio", "0.5", "--range-ratio", "3"],
        "the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 7.36806e19 is outside 1e-8..1e6",
    );
    refused(
        &[
            "cycle",
            "--lambda",
            "1",
            "--stress-ratio",
            "1e-9",
            "--range-ratio",
            "3",
        ],
        "--stress-ratio 1e-9 (rho)",
    );
    // Options of an explicit ensemble on a statistical surface, and others that were ignored.
    for (flag, value) in [
        ("--min-separation-m", "1e-9"),
        ("--summits", "exact"),
        ("--pixel-m", "1e-8"),
        ("--backend", "cpu"),
        ("--precision", "f64"),
        ("--adapter", "x"),
    ] {
        refused(
            &["rough", "--preset", "mems-polysilicon", flag, value],
            &format!("{flag} applies to an explicit ensemble (--asperities, --topography)"),
        );
        refused(
            &with(&["--lambda", "1", "--min-separation", "-1", flag, value]),
            &format!("leave out {flag}"),
        );
    }
    for sub in ["map", "rough-map"] {
        refused(
            &[sub, "--nx", "4", "--ny", "4", "--timings"],
            "--timings puts the computing time into the JSON: give --json FILE too",
        );
    }
    // One press range, from the library.
    refused(
        &["rough-pulloff", "--press-sigmas", "7"],
        "--press-sigmas = 7 is not valid: give how many sigma below the mean summit plane the flat was pressed, -6..6",
    );
    refused(
        &["rough-map", "--nx", "4", "--ny", "4", "--press-sigmas=-6.5"],
        "--press-sigmas = -6.5 is not valid: give how many sigma below the mean summit plane the flat was pressed, -6..6",
    );
    // A bounded sweep.
    refused(
        &[
            "rough",
            "--sigma",
            "0.5",
            "--lambda",
            "1",
            "--min-separation",
            "-1",
            "--points",
            "10001",
        ],
        "the number of separations = 10001 is outside the supported domain 2..10000",
    );
    // solve by a radius beyond the exact solver: what it can answer there.
    refused(
        &["solve", "--lambda", "1e27", "--radius-a", "1"],
        "--lambda 1e27 with --radius-a: a state by its contact radius is solved only for lambda in 1e-26..1e26 (the exact solver); beyond it the JKR limit answers a load or an approach, not a radius",
    );
}

#[test]
fn rough_scene_and_ensemble_refusals_name_the_key_and_the_value_given() {
    let dir = tempfile::tempdir().unwrap();
    let scene = |extra: &str| {
        scene_file(
            dir.path(),
            &format!(
                r#"{{"e_star_pa": 1e9, "work_of_adhesion_j_m2": 0.05, "z0_m": 3e-10,
                "summit_radius_m": 1e-6, "summit_density_m2": 1e12, "nominal_area_m2": 1e-8{extra}}}"#
            ),
        )
    };
    // The approach unit of this scene, (pi^2 w^2 R/K^2)^(1/3) with K = 4/3 E*.
    let k = 4.0 / 3.0 * 1e9;
    let unit = (std::f64::consts::PI.powi(2) * 0.05f64.powi(2) * 1e-6 / (k * k)).cbrt();
    let s = scene(r#", "sigma_m": 1e-3"#);
    refused(&["rough", "--scene", &s], "sigma_m = 0.001 m is ");
    refused(
        &["rough", "--scene", &s],
        "beyond the 1e4 the rough model takes: give sigma_m of at most",
    );
    let s = scene(r#", "sigma_m": 1e-9, "min_separation_m": -1e-1"#);
    let o = run(&["rough", "--scene", &s]);
    let err = stderr(&o);
    assert!(err.contains("min_separation_m = -0.1 m is "), "{err}");
    let shown = format!("{:.5e}", -0.1 / unit);
    let (m, e) = shown.split_once('e').unwrap();
    let shown = format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'));
    assert!(
        err.contains(&format!("-0.1 m is {shown} approach units")),
        "{shown}: {err}"
    );
    let s = scene(r#", "sigma_m": 1e-9, "min_separation_m": 1e-6"#);
    refused(
        &["rough", "--scene", &s],
        "min_separation_m = 1e-6 m is beyond the summits' reach",
    );
    // An ensemble pressed far beyond its summits: the flag and the value, not a NaN.
    let asp = dir.path().join("asp.csv");
    std::fs::write(&asp, "height_m,radius_m\n0,5e-7\n1e-9,6e-7\n2e-9,4e-7\n").unwrap();
    let asp = asp.to_str().unwrap();
    refused(
        &[
            "rough",
            "--preset",
            "mems-polysilicon",
            "--asperities",
            asp,
            "--min-separation-m=-1",
        ],
        "--min-separation-m = -1 m presses a summit more than 1e8 of its approach units",
    );
    refused(
        &[
            "rough",
            "--preset",
            "mems-polysilicon",
            "--asperities",
            asp,
            "--min-separation-m",
            "1",
        ],
        "--min-separation-m = 1 is outside",
    );
}

#[test]
fn an_ensemble_presses_to_its_scenes_own_min_separation() {
    // `tabor rough --scene S --asperities A` used to ignore S's `min_separation_m` (and press to
    // three standard deviations below the mean height). The key is measured from the mean
    // summit height, as for a Gaussian scene; `--min-separation-m` (from the heights' datum)
    // overrides it.
    let dir = tempfile::tempdir().unwrap();
    let asp = dir.path().join("asp.csv");
    // Mean height 1 nm.
    std::fs::write(&asp, "height_m,radius_m\n0,5e-7\n1e-9,6e-7\n2e-9,4e-7\n").unwrap();
    let asp = asp.to_str().unwrap();
    let scene = |extra: &str| {
        let p = dir.path().join(format!("scene{}.json", extra.len()));
        std::fs::write(
            &p,
            format!(
                r#"{{"e_star_pa": 87.2e9, "work_of_adhesion_j_m2": 0.1, "z0_m": 3e-10,
                "summit_radius_m": 5e-7, "summit_density_m2": 1e12, "sigma_m": 1e-9,
                "nominal_area_m2": 1e-8{extra}}}"#
            ),
        )
        .unwrap();
        p.to_str().unwrap().to_string()
    };
    let cycle = |args: &[&str]| {
        let o = run(args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        stdout(&o)
    };
    let keyed = scene(r#", "min_separation_m": -0.5e-9"#);
    let plain = scene("");
    let with_key = cycle(&[
        "rough",
        "--scene",
        &keyed,
        "--asperities",
        asp,
        "--points",
        "20",
    ]);
    // 1 nm (the mean) - 0.5 nm.
    let by_flag = cycle(&[
        "rough",
        "--scene",
        &plain,
        "--asperities",
        asp,
        "--points",
        "20",
        "--min-separation-m",
        "0.5e-9",
    ]);
    let default = cycle(&[
        "rough",
        "--scene",
        &plain,
        "--asperities",
        asp,
        "--points",
        "20",
    ]);
    assert_eq!(with_key, by_flag);
    assert_ne!(with_key, default);
    // The flag overrides the key.
    let overridden = cycle(&[
        "rough",
        "--scene",
        &keyed,
        "--asperities",
        asp,
        "--points",
        "20",
        "--min-separation-m",
        "0.5e-9",
    ]);
    assert_eq!(overridden, by_flag);
    // A key beyond the solver's depth is refused naming the key, the value given and the mean.
    let deep = scene(r#", "min_separation_m": -1"#);
    refused(
        &["rough", "--scene", &deep, "--asperities", asp],
        "(the scene's min_separation_m = -1 m, measured from the mean summit height 1e-9 m)",
    );
}
