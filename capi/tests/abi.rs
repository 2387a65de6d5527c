//! The C ABI: its header, its refusals, its agreement with the library, and the C example
//! (examples/c/collision.c) compiled and run against the shared library.

use std::ptr::{null, null_mut};
use tabor::dem::{History, Pair};
use tabor_dem::*;

fn pair() -> TaborDemPair {
    TaborDemPair {
        youngs_modulus1_pa: 3e9,
        poisson_ratio1: 0.35,
        radius1_m: 10e-6,
        youngs_modulus2_pa: 3e9,
        poisson_ratio2: 0.35,
        radius2_m: 10e-6,
        work_of_adhesion_j_m2: 0.1,
        dugdale_stress_pa: 0.0,
        lj_range_m: 0.3e-9,
        overlap_max_m: 2e-6,
        relative_humidity: 0.0,
        contact_angle_deg: 0.0,
    }
}

#[test]
fn the_abi_evaluates_the_library_law_and_refuses_bad_input() {
    unsafe {
        let mut err = [0 as std::ffi::c_char; 200];
        let law = tabor_dem_law_new(&pair(), err.as_mut_ptr(), err.len());
        assert!(!law.is_null());
        let mut info = TaborDemInfo::default();
        assert_eq!(tabor_dem_law_info(law, &mut info), TABOR_DEM_OK);
        // The same law through the library.
        let c = tabor::physics::params::Contact::new(
            5e-6,
            info.reduced_modulus_pa,
            0.1,
            tabor::physics::params::ForceRange::LennardJones(0.3e-9),
        )
        .unwrap();
        let lib = Pair::new(c, 2e-6).unwrap();
        assert_eq!(info.lambda, lib.law.lambda);
        let (mut h, mut hb) = (TABOR_DEM_FREE, History::NEW);
        let (mut f, mut k) = (0.0, 0.0);
        for i in 0..=400 {
            // Approach to 40 nm, then back out to -10 nm.
            let t = i as f64 / 200.0;
            let d = if t <= 1.0 {
                -10e-9 + 50e-9 * t
            } else {
                40e-9 - 50e-9 * (t - 1.0)
            };
            assert_eq!(
                tabor_dem_law_eval(law, d, &mut h, &mut f, &mut k),
                TABOR_DEM_OK
            );
            let e = lib.eval(d, &mut hb);
            assert_eq!((f, k, h), (e.force_n, e.stiffness_n_m, hb.code()), "at {d}");
            assert_eq!(tabor_dem_law_branch(law, h), e.branch as i32, "at {d}");
        }
        assert_eq!(h, TABOR_DEM_FREE);
        assert_eq!(
            tabor_dem_law_branch(law, info.histories as u8),
            TABOR_DEM_INVALID
        );
        assert_eq!(tabor_dem_law_branch(null(), 0), TABOR_DEM_INVALID);
        // Beyond the table: written and flagged.
        h = info.histories as u8 - 1;
        assert_eq!(tabor_dem_law_branch(law, h), TABOR_DEM_CONTACT as i32);
        assert_eq!(
            tabor_dem_law_eval(law, 3e-6, &mut h, &mut f, &mut k),
            TABOR_DEM_BEYOND_TABLE
        );
        assert!(f.is_finite() && f > 0.0);
        // Refused: nothing written.
        f = 7.0;
        assert_eq!(
            tabor_dem_law_eval(law, f64::NAN, &mut h, &mut f, &mut k),
            TABOR_DEM_INVALID
        );
        for bad in [f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                tabor_dem_law_eval(law, bad, &mut h, &mut f, &mut k),
                TABOR_DEM_INVALID
            );
        }
        assert_eq!(TABOR_DEM_ABI_VERSION, 2);
        h = 9;
        assert_eq!(
            tabor_dem_law_eval(law, 1e-9, &mut h, &mut f, &mut k),
            TABOR_DEM_INVALID
        );
        assert_eq!((f, h), (7.0, 9));
        assert_eq!(
            tabor_dem_law_eval(null(), 1e-9, &mut h, &mut f, &mut k),
            TABOR_DEM_INVALID
        );
        assert_eq!(
            tabor_dem_law_eval(law, 1e-9, null_mut(), &mut f, &mut k),
            TABOR_DEM_INVALID
        );
        assert_eq!(tabor_dem_law_info(null(), &mut info), TABOR_DEM_INVALID);
        assert!(tabor_dem_law_loop_energy(null(), 1e-8).is_nan());
        assert!(
            (tabor_dem_law_loop_energy(law, 1e-8) - info.loop_energy_j).abs()
                <= 1e-9 * info.loop_energy_j
        );
        tabor_dem_law_free(law);
        tabor_dem_law_free(null_mut());
        // A bad pair: NULL and the reason.
        let mut bad = pair();
        bad.poisson_ratio1 = 0.7;
        assert!(tabor_dem_law_new(&bad, err.as_mut_ptr(), err.len()).is_null());
        let msg = std::ffi::CStr::from_ptr(err.as_ptr())
            .to_string_lossy()
            .into_owned();
        assert!(msg.contains("0.7"), "{msg}");
        assert!(tabor_dem_law_new(null(), null_mut(), 0).is_null());
        // A short buffer gets a cut, terminated message.
        let mut short = [1 as std::ffi::c_char; 8];
        assert!(tabor_dem_law_new(&bad, short.as_mut_ptr(), short.len()).is_null());
        assert_eq!(short[7], 0);
    }
}

/// With a relative humidity the ABI's law is the library's pair with the Kelvin meniscus of
/// water, and the meniscus widens the loop.
#[test]
fn a_humid_pair_is_the_library_pair_with_its_meniscus() {
    unsafe {
        let mut p = pair();
        p.relative_humidity = 0.5;
        p.contact_angle_deg = 20.0;
        let mut err = [0 as std::ffi::c_char; 300];
        let law = tabor_dem_law_new(&p, err.as_mut_ptr(), err.len());
        assert!(
            !law.is_null(),
            "{}",
            std::ffi::CStr::from_ptr(err.as_ptr()).to_string_lossy()
        );
        let mut info = TaborDemInfo::default();
        assert_eq!(tabor_dem_law_info(law, &mut info), TABOR_DEM_OK);
        let c = tabor::physics::params::Contact::new(
            5e-6,
            info.reduced_modulus_pa,
            0.1,
            tabor::physics::params::ForceRange::LennardJones(0.3e-9),
        )
        .unwrap();
        let m = tabor::scene::humidity::HumidityInput::water(0.5, 20.0)
            .meniscus(&c)
            .unwrap()
            .unwrap();
        assert_eq!(info.meniscus_work_j_m2, m.work_of_adhesion_j_m2);
        assert_eq!(info.meniscus_range_m, m.range_m);
        let lib = Pair::with_meniscus(c, Some(m), Some(2e-6)).unwrap();
        let (mut h, mut hb) = (TABOR_DEM_FREE, History::NEW);
        let (mut f, mut k) = (0.0, 0.0);
        for i in 0..=400 {
            let t = i as f64 / 200.0;
            let d = if t <= 1.0 {
                -10e-9 + 50e-9 * t
            } else {
                40e-9 - 50e-9 * (t - 1.0)
            };
            assert_eq!(
                tabor_dem_law_eval(law, d, &mut h, &mut f, &mut k),
                TABOR_DEM_OK
            );
            let e = lib.eval(d, &mut hb);
            assert_eq!((f, k, h), (e.force_n, e.stiffness_n_m, hb.code()), "at {d}");
        }
        // The meniscus reaches across a wider gap and pulls harder: a larger loop than dry.
        let dry = tabor_dem_law_new(&pair(), null_mut(), 0);
        let mut dry_info = TaborDemInfo::default();
        assert_eq!(tabor_dem_law_info(dry, &mut dry_info), TABOR_DEM_OK);
        assert!(info.attraction_from_m < dry_info.attraction_from_m);
        assert!(info.loop_energy_j > dry_info.loop_energy_j);
        assert_eq!(dry_info.meniscus_work_j_m2, 0.0);
        // A humidity out of range is refused with its value.
        p.relative_humidity = 1.5;
        assert!(tabor_dem_law_new(&p, err.as_mut_ptr(), err.len()).is_null());
        let msg = std::ffi::CStr::from_ptr(err.as_ptr()).to_string_lossy();
        assert!(msg.contains("1.5"), "{msg}");
        tabor_dem_law_free(law);
        tabor_dem_law_free(dry);
    }
}

/// examples/c/collision.c, compiled against the shared library (built by
/// `cargo build --release -p tabor-capi`, as tests/run_all.sh does first) and run: every
/// collision that separates loses the loop energy, slower ones stick.
#[test]
fn the_c_example_loses_the_loop_energy_per_collision() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap();
    let lib_dir = ["release", "debug"]
        .iter()
        .map(|p| root.join("target").join(p))
        .find(|d| d.join("libtabor_dem.so").exists() || d.join("libtabor_dem.dylib").exists())
        .expect("the shared library libtabor_dem: run `cargo build --release -p tabor-capi` first");
    let dir = tempfile::tempdir().unwrap();
    let exe = dir.path().join("collision");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let out = std::process::Command::new(&cc)
        .args([
            "-O2",
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-D_DEFAULT_SOURCE",
        ])
        .arg(root.join("examples/c/collision.c"))
        .arg(format!("-I{}", root.join("capi/include").display()))
        .arg(format!("-L{}", lib_dir.display()))
        .args(["-ltabor_dem", "-lm", "-o"])
        .arg(&exe)
        .output()
        .expect("a C compiler (cc, or $CC)");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Dry, and in air of 50% relative humidity.
    for args in [&[][..], &["0.5"][..]] {
        let run = std::process::Command::new(&exe)
            .args(args)
            .env("LD_LIBRARY_PATH", &lib_dir)
            .env("DYLD_LIBRARY_PATH", &lib_dir)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&run.stdout).into_owned();
        assert!(
            run.status.success(),
            "{text}{}",
            String::from_utf8_lossy(&run.stderr)
        );
        println!("{text}");
        assert_eq!(
            text.contains("meniscus at RH 0.5"),
            !args.is_empty(),
            "{text}"
        );
        let rows: Vec<Vec<f64>> = text
            .lines()
            .skip_while(|l| !l.starts_with("v0_m_s"))
            .skip(1)
            .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 10);
        let mut last_e = 0.0;
        for r in &rows {
            let (e, lost, loop_e) = (r[1], r[2], r[3]);
            if e > 0.0 {
                assert!((lost - loop_e).abs() <= 1e-3 * loop_e, "{args:?}: {r:?}");
                assert!(e > last_e, "{args:?}: {r:?}");
                last_e = e;
            } else {
                assert_eq!(last_e, 0.0, "stuck after a bounce: {args:?}: {r:?}");
            }
        }
        // The first three impacts are below the loop's sticking velocity (0.5, 0.9, 0.99 of
        // it), the rest above.
        assert!(
            rows[..3].iter().all(|r| r[1] == 0.0) && rows[3..].iter().all(|r| r[1] > 0.0),
            "{args:?}"
        );
    }
}
