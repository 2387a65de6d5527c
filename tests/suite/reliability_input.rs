//! Force-curve input that used to be read wrong or without bound: NPZ members that are corrupt,
//! huge, boolean, or named in capitals or on stdin; /dev/zero; duplicated columns; force maps
//! sized by a stray pixel index; outputs that cannot be written found only after the fits.

use std::io::Write;
use std::process::{Command, Output, Stdio};

fn tabor(args: &[&str], stdin: Option<&[u8]>) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_tabor"));
    c.args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        });
    let mut child = c.spawn().unwrap();
    if let Some(b) = stdin {
        let mut i = child.stdin.take().unwrap();
        let b = b.to_vec();
        std::thread::spawn(move || {
            let _ = i.write_all(&b);
        });
    }
    child.wait_with_output().unwrap()
}

fn refused(o: &Output, needle: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(needle), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// A .npy member: header and little-endian values.
fn npy(descr: &str, values: &[u8], n: usize) -> Vec<u8> {
    npy_shaped(descr, values, &format!("({n},)"))
}

fn npy_shaped(descr: &str, values: &[u8], shape: &str) -> Vec<u8> {
    let dict = format!("{{'descr': '{descr}', 'fortran_order': True, 'shape': {shape}, }}");
    let mut header = dict.into_bytes();
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(b' ');
    }
    header.push(b'\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header);
    out.extend(values);
    out
}

fn f64s(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A synthetic curve (E* 2 GPa, w 0.04, lambda 0.3, R 20 nm, 40 N/m) as columns.
fn curve() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    use tabor::fit::synthetic::{synthetic, Synthetic};
    let c = synthetic(&Synthetic {
        model: tabor::fit::Model::Md,
        params: tabor::fit::Params {
            e_star: 2e9,
            w: 0.04,
            lambda: 0.3,
            zc: 40e-9,
            f0: 0.0,
        },
        radius: 20e-9,
        spring: 40.0,
        points: 300,
        depth: 6.0,
        noise: 0.0,
        seed: 1,
    });
    let seg = c
        .segment
        .iter()
        .map(|s| {
            if *s == tabor::fit::Direction::Approach {
                0.0
            } else {
                1.0
            }
        })
        .collect();
    (seg, c.height.clone(), c.force.clone())
}

fn npz(members: &[(&str, Vec<u8>)], stored: bool) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opt = zip::write::FileOptions::default().compression_method(if stored {
        zip::CompressionMethod::Stored
    } else {
        zip::CompressionMethod::Deflated
    });
    for (name, bytes) in members {
        w.start_file(format!("{name}.npy"), opt).unwrap();
        w.write_all(bytes).unwrap();
    }
    w.finish().unwrap().into_inner()
}

#[test]
fn npz_members_are_checked_and_found_by_content() {
    let (seg, h, f) = curve();
    let n = seg.len();
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("c.csv");
    let mut text = String::from("segment,height_m,force_n\n");
    for i in 0..n {
        text += &format!("{},{:e},{:e}\n", seg[i], h[i], f[i]);
    }
    std::fs::write(&csv, &text).unwrap();
    let fit = |p: &str, stdin: Option<&[u8]>| {
        tabor(
            &[
                "fit",
                "-i",
                p,
                "--radius",
                "20e-9",
                "--spring-n-m",
                "40",
                "--format",
                "csv",
            ],
            stdin,
        )
    };
    let want = fit(csv.to_str().unwrap(), None);
    assert!(
        want.status.success(),
        "{}",
        String::from_utf8_lossy(&want.stderr)
    );
    // Boolean segments, a capitalised name, and the same NPZ on stdin give the CSV's fit.
    let seg_bool: Vec<u8> = seg.iter().map(|s| *s as u8).collect();
    let good = npz(
        &[
            ("segment", npy("|b1", &seg_bool, n)),
            ("height_m", npy("<f8", &f64s(&h), n)),
            ("force_n", npy("<f8", &f64s(&f), n)),
        ],
        true,
    );
    let upper = dir.path().join("C.NPZ");
    std::fs::write(&upper, &good).unwrap();
    for got in [fit(upper.to_str().unwrap(), None), fit("-", Some(&good))] {
        assert!(
            got.status.success(),
            "{}",
            String::from_utf8_lossy(&got.stderr)
        );
        assert_eq!(got.stdout, want.stdout);
    }
    // A flipped byte in a stored member: its CRC no longer matches.
    let mut bad = good.clone();
    let at = bad
        .windows(8)
        .position(|w| w == h[10].to_le_bytes())
        .unwrap();
    bad[at] ^= 0x55;
    let corrupt = dir.path().join("corrupt.npz");
    std::fs::write(&corrupt, &bad).unwrap();
    refused(&fit(corrupt.to_str().unwrap(), None), "corrupt");
    // A 2-D array is refused, not read scrambled.
    let two_d = npy_shaped("<f8", &f64s(&h[..n / 2 * 2]), &format!("(2, {})", n / 2));
    let p = dir.path().join("2d.npz");
    std::fs::write(
        &p,
        npz(
            &[
                ("segment", npy("<f8", &f64s(&seg), n)),
                ("height_m", two_d),
                ("force_n", npy("<f8", &f64s(&f), n)),
            ],
            true,
        ),
    )
    .unwrap();
    refused(&fit(p.to_str().unwrap(), None), "1-D");
    // A zip bomb: 420 MB of zeros packed into well under a megabyte.
    let zeros = vec![0u8; 420_000_000];
    let bomb = npz(&[("segment", npy("<f8", &zeros, 52_500_000))], false);
    assert!(bomb.len() < 1_000_000);
    let p = dir.path().join("bomb.npz");
    std::fs::write(&p, &bomb).unwrap();
    refused(&fit(p.to_str().unwrap(), None), "unpacks to");
}

#[test]
fn endless_lines_duplicated_columns_and_stray_pixels_are_refused_up_front() {
    fn args(i: &str) -> Vec<&str> {
        vec!["fit", "-i", i, "--radius", "20e-9", "--spring-n-m", "40"]
    }
    refused(&tabor(&args("/dev/zero"), None), "longer than");
    refused(
        &tabor(&args("-"), Some(&vec![b'1'; 3 << 20])),
        "longer than",
    );
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("dup.csv");
    std::fs::write(&p, "segment,height_m,force_n,force_n\n0,1e-7,0,0\n").unwrap();
    refused(&tabor(&args(p.to_str().unwrap()), None), "appears twice");
    // One curve at pixel (9999, 9999): a 1e8-pixel grid is refused before any fit.
    let (seg, h, f) = curve();
    let mut text = String::from("x,y,segment,height_m,force_n\n");
    for (px, py) in [(0, 0), (9999, 9999)] {
        for i in 0..seg.len() {
            text += &format!("{px},{py},{},{:e},{:e}\n", seg[i], h[i], f[i]);
        }
    }
    let p = dir.path().join("map.csv");
    std::fs::write(&p, text).unwrap();
    let prefix = dir.path().join("m");
    let mut a = args(p.to_str().unwrap());
    a.extend(["--maps", prefix.to_str().unwrap(), "-o", "/dev/null"]);
    let o = tabor(&a, None);
    refused(&o, "10000 x 10000");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        2,
        "nothing written"
    );
    // An output in a missing folder is found before the fits; --svg needs --plot.
    let mut a = args(p.to_str().unwrap());
    a.extend(["-o", "/nonexistent-folder/out.json"]);
    refused(&tabor(&a, None), "out.json");
    let mut a = args(p.to_str().unwrap());
    a.extend(["--svg", "x.svg"]);
    refused(&tabor(&a, None), "--plot");
}

#[test]
fn solve_reads_the_tables_fit_reads() {
    // Comments before and inside, and a tab-separated table: the same rows as plain CSV.
    let plain = tabor(
        &["solve", "-i", "-", "-o", "-"],
        Some(b"lambda,load\n1,0.5\n5,-1.2\n"),
    );
    assert!(
        plain.status.success(),
        "{}",
        String::from_utf8_lossy(&plain.stderr)
    );
    for text in [
        &b"# measured 2026\nlambda\tload\n1\t0.5\n# a note\n5\t-1.2\n"[..],
        &b"#\n\nlambda, load\n1, 0.5\n5, -1.2\n"[..],
    ] {
        let o = tabor(&["solve", "-i", "-", "-o", "-"], Some(text));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(o.stdout, plain.stdout);
    }
}

/// The synthetic curve as a CSV, at pixel (x, y) where given.
fn curve_csv(pixels: &[(i64, i64)]) -> String {
    let (seg, h, f) = curve();
    if pixels.is_empty() {
        let mut text = String::from("segment,height_m,force_n\n");
        for i in 0..seg.len() {
            text += &format!("{},{:e},{:e}\n", seg[i], h[i], f[i]);
        }
        return text;
    }
    let mut text = String::from("x,y,segment,height_m,force_n\n");
    for (px, py) in pixels {
        for i in 0..seg.len() {
            text += &format!("{px},{py},{},{:e},{:e}\n", seg[i], h[i], f[i]);
        }
    }
    text
}

#[test]
fn fit_csv_has_17_digits_and_options_are_not_ignored() {
    let fit = |extra: &[&str]| {
        let mut a = vec!["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", "40"];
        a.extend(extra);
        tabor(&a, Some(curve_csv(&[]).as_bytes()))
    };
    // The CSV's numbers are the JSON's to the last bit: 17 significant digits, as the README
    // says of every CSV (they were 11).
    let json = fit(&[]);
    assert!(
        json.status.success(),
        "{}",
        String::from_utf8_lossy(&json.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let r = &v["curves"][0];
    let csv = fit(&["--format", "csv"]);
    let text = String::from_utf8(csv.stdout).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    for key in [
        "e_star_pa",
        "work_of_adhesion_j_m2",
        "lambda",
        "rms_residual_n",
    ] {
        let cell = row[head.iter().position(|h| *h == key).unwrap()];
        let mantissa = cell.split('e').next().unwrap().trim_start_matches('-');
        assert_eq!(mantissa.len(), 18, "{key}: {cell}");
        assert_eq!(
            cell.parse::<f64>().unwrap(),
            r[key].as_f64().unwrap(),
            "{key}"
        );
    }
    // --curve chooses the curve --plot draws: without --plot it did nothing.
    refused(
        &fit(&["--curve", "0"]),
        "--curve 0 chooses the curve that --plot draws: give --plot FILE too",
    );
}

#[test]
fn out_of_range_pixel_indices_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("m");
    let a = [
        "fit",
        "-i",
        "-",
        "--radius",
        "20e-9",
        "--spring-n-m",
        "40",
        "--maps",
        prefix.to_str().unwrap(),
        "-o",
        "/dev/null",
    ];
    let o = tabor(&a, Some(curve_csv(&[(0, 0), (100_000, 0)]).as_bytes()));
    refused(&o, "has pixel index x = 100000, outside 0..99999");
    let o = tabor(&a, Some(curve_csv(&[(0, -1)]).as_bytes()));
    refused(&o, "has pixel index y = -1, outside 0..99999");
}
