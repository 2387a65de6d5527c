//! Maugis-Dugdale on axisymmetric tips (docs/PHYSICS.md section 12): the sphere (n = 2) is
//! section 2's Maugis-Dugdale to rounding, the power laws tend to their JKR pull-offs (the
//! energy balance of a power-law punch, Borodich et al. 2014) as lambda grows and to the rigid
//! tip's Dugdale force as it falls, the capped cone to its sphere and its cone at its ends, and
//! the SI units are section 12.1's.

use tabor::law::{Drive, Law, Md, Piece, Tip};
use tabor::physics::tip::{k_n, Shape, TipInput};
use tabor::LambdaContext;

fn power(n: f64, lambda: f64) -> Tip {
    Tip::new(Shape::Power { exponent: n }, lambda).unwrap()
}

/// n = 2 gives section 2's states at the same radius, its non-contact piece and its pull-offs
/// to 1e-13 (the slopes to 1e-9).
#[test]
fn the_square_power_law_is_the_sphere() {
    for lambda in [0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 100.0] {
        let (tip, md) = (power(2.0, lambda), Md { lambda });
        let close = |x: f64, y: f64, what: &str| {
            assert!(
                (x - y).abs() <= 1e-13 * y.abs().max(1.0),
                "lambda {lambda} {what}: {x} against {y}"
            )
        };
        for a in [1e-3, 0.05, 0.3, 1.0, 2.5, 6.0] {
            let p = tip.state(Piece::Contact, tip.t_of_radius(a));
            let q = md.state(Piece::Contact, md.t_of_radius(a));
            close(p.a, q.a, "A");
            close(p.load, q.load, "load");
            close(p.approach, q.approach, "approach");
            // Slopes along the branch per unit radius (differences of terms of order one near
            // the A -> 0 end: to 1e-9).
            for (x, y) in [
                (p.dload / p.da, q.dload / q.da),
                (p.dapproach / p.da, q.dapproach / q.da),
            ] {
                assert!(
                    (x - y).abs() <= 1e-9 * y.abs().max(1.0),
                    "lambda {lambda}: {x} {y}"
                );
            }
        }
        let end = tabor::physics::md::zero_radius_end(lambda);
        close(tip.zone_end(), end.c, "the non-contact end");
        let ctx = LambdaContext::new(lambda).unwrap();
        let load = tip.pulloff_state(Drive::DeadLoad);
        close(load.load, ctx.load_pulloff.load, "load-controlled pull-off");
        let grips = tip.pulloff_state(Drive::RigidGrips);
        let exact = ctx.disp_pulloff();
        close(grips.load, exact.load, "displacement-controlled pull-off");
        close(grips.approach, exact.approach, "its approach");
    }
}

/// As lambda grows the pull-offs tend to the JKR power-law punch's:
/// `Pbar_c = -sqrt(6) A_c^(3/2) (2n-1)/(2(n+1))` at `A_c = (sqrt(6)/n)^(2/(2n-1))`, and under
/// rigid grips the state at `A_d = (sqrt(2/3)/n)^(2/(2n-1))`, the difference falling like
/// lambda^(-2/3) or faster.
#[test]
fn power_laws_tend_to_their_jkr_pulloffs() {
    for n in [1.0, 1.5, 2.0, 3.0, 4.0] {
        let e = 2.0 / (2.0 * n - 1.0);
        let a_c = (6f64.sqrt() / n).powf(e);
        let jkr = -6f64.sqrt() * a_c.powf(1.5) * (2.0 * n - 1.0) / (2.0 * (n + 1.0));
        let a_d = ((2.0f64 / 3.0).sqrt() / n).powf(e);
        let jkr_d = 1.5 * n / (n + 1.0) * a_d.powf(n + 1.0) - (6.0 * a_d.powi(3)).sqrt();
        let errs: Vec<(f64, f64)> = [100.0, 1000.0]
            .iter()
            .map(|&l| {
                let t = power(n, l);
                (
                    (t.pulloff_state(Drive::DeadLoad).load / jkr - 1.0).abs(),
                    (t.pulloff_state(Drive::RigidGrips).load / jkr_d - 1.0).abs(),
                )
            })
            .collect();
        assert!(errs[1].0 < 0.02 && errs[1].1 < 0.03, "n {n}: {errs:?}");
        assert!(errs[1].0 < 0.25 * errs[0].0, "n {n}: {errs:?}");
        assert!(errs[1].1 < 0.25 * errs[0].1, "n {n}: {errs:?}");
    }
}

/// As lambda falls the tip barely deforms: the load-controlled pull-off tends to the Dugdale
/// tension over the disc where the undeformed gap is below h0, `-(pi lambda/2) C0^2` with
/// `fbar(C0) = 2/(pi lambda)` (the sphere's -2).
#[test]
fn power_laws_tend_to_the_rigid_tips_force() {
    for n in [1.0, 1.5, 2.0, 3.0, 4.0] {
        let rigid = |l: f64| {
            let c0 = (2.0 * k_n(n) / (std::f64::consts::PI * l)).powf(1.0 / n);
            -std::f64::consts::PI * l / 2.0 * c0 * c0
        };
        let errs: Vec<f64> = [1e-2, 1e-3]
            .iter()
            .map(|&l| (power(n, l).pulloff_state(Drive::DeadLoad).load / rigid(l) - 1.0).abs())
            .collect();
        assert!(errs[1] < 0.05 && errs[1] < 0.6 * errs[0], "n {n}: {errs:?}");
    }
}

/// A capped cone whose cap is large against the contact is the sphere (to order (A/rho)^2),
/// and one whose cap is small is the cone: their pull-off forces in newtons agree.
#[test]
fn capped_cones_are_their_sphere_and_their_cone_at_the_ends() {
    let lambda = 1.0;
    let big = Tip::new(
        Shape::CappedCone {
            rho: 1e3,
            half_angle: 20f64.to_radians(),
        },
        lambda,
    )
    .unwrap()
    .pulloff_state(Drive::DeadLoad)
    .load;
    let sphere = LambdaContext::new(lambda).unwrap().load_pulloff.load;
    assert!((big / sphere - 1.0).abs() < 1e-5, "{big} {sphere}");
    // E* = w = 1; s0 gives the cone lambda 1; a cap of 1e-4 against a contact of order 0.1.
    let (e, w) = (1.0, 1.0);
    let s0 = std::f64::consts::PI / 3.0 / 20f64.to_radians().tan();
    let newtons = |tip: TipInput| {
        let u = tip.units(e, w, s0).unwrap();
        let law = Tip::new(u.shape, u.lambda).unwrap();
        law.pulloff_state(Drive::DeadLoad).load * u.force_n
    };
    let cone = newtons(TipInput::Cone {
        half_angle_deg: 20.0,
    });
    let capped = newtons(TipInput::CappedCone {
        radius_m: 1e-4,
        half_angle_deg: 20.0,
    });
    assert!((capped / cone - 1.0).abs() < 1e-2, "{capped} {cone}");
}

/// The SI units: the sphere's are section 1's, and every tip's satisfy `E* d^2 / l = 3 pi w / 4`
/// with `lambda = (3/2) s0 l / (E* d)`; a pyramid is the cone of its area (Berkovich: 70.30 deg).
#[test]
fn tip_units_are_section_twelves() {
    let (e, w, s0) = (1e9, 0.05, 1e8);
    let r = 20e-9;
    let u = TipInput::Sphere { radius_m: r }.units(e, w, s0).unwrap();
    let k = 4.0 / 3.0 * e;
    let pi = std::f64::consts::PI;
    let lambda = 2.0 * s0 * (r / (pi * w * k * k)).cbrt();
    assert!((u.lambda / lambda - 1.0).abs() < 1e-14);
    assert!((u.force_n / (pi * w * r) - 1.0).abs() < 1e-14);
    assert!((u.length_m / (pi * w * r * r / k).cbrt() - 1.0).abs() < 1e-14);
    for tip in [
        TipInput::Cone {
            half_angle_deg: 20.0,
        },
        TipInput::Power {
            exponent: 4.0,
            coefficient: 1e21,
        },
        TipInput::CappedCone {
            radius_m: r,
            half_angle_deg: 20.0,
        },
    ] {
        let u = tip.units(e, w, s0).unwrap();
        let balance = e * u.approach_m * u.approach_m / u.length_m / (3.0 * pi * w / 4.0);
        assert!((balance - 1.0).abs() < 1e-13, "{tip:?}: {balance}");
    }
    let berkovich = TipInput::Pyramid {
        faces: 3,
        face_angle_deg: 65.27,
    };
    let alpha = berkovich.equivalent_cone_deg().unwrap();
    assert!((alpha - 70.30).abs() < 0.01, "{alpha}");
    let e = TipInput::Cone {
        half_angle_deg: 95.0,
    }
    .units(1e9, 0.05, 1e8)
    .unwrap_err();
    assert!(e.to_string().contains("half_angle_deg = 95"), "{e}");
}

fn scene(json: &str) -> Result<tabor::scene::Solved, String> {
    let input: tabor::scene::SceneInput = serde_json::from_str(json).map_err(|e| e.to_string())?;
    tabor::scene::solve(&input).map_err(|e| e.to_string())
}

/// A cone's scene in SI units, near the JKR end (a short force range): its load-controlled
/// pull-off is the JKR cone's `-(54/pi) w^2 tan^3(alpha) / E*` (section 12.1) and its contact
/// radius there `18 w tan^2(alpha) / (pi E*)`; every load's zone lies outside its contact.
#[test]
fn a_cone_scene_pulls_off_at_the_jkr_cones_force() {
    let (e, w, alpha) = (1e6, 0.05, 70f64.to_radians());
    let json = format!(
        r#"{{"e_star_pa": {e}, "work_of_adhesion_j_m2": {w}, "h0_m": 3e-10,
            "tip": {{"shape": "cone", "half_angle_deg": 70}}, "loads_n": [0, 1e-6]}}"#
    );
    let tabor::scene::Solved::Tip(r) = scene(&json).unwrap() else {
        panic!("a cone is a tip scene")
    };
    assert!(r.lambda > 100.0, "{}", r.lambda);
    let jkr = -54.0 / std::f64::consts::PI * w * w * alpha.tan().powi(3) / e;
    assert!(
        (r.pulloff_force_load_control_N / jkr - 1.0).abs() < 2e-3,
        "{} {jkr}",
        r.pulloff_force_load_control_N
    );
    let a_c = 18.0 * w * alpha.tan().powi(2) / (std::f64::consts::PI * e);
    assert!((r.pulloff_contact_radius_load_control_m / a_c - 1.0).abs() < 1e-2);
    for l in &r.loads {
        assert!(l.zone_radius_m.unwrap() > l.contact_radius_m.unwrap());
        assert_eq!(l.model, "jkr", "{l:?}");
    }
}

/// A sphere given as the tip is the sphere's scene, key for key; bad tips get one line naming
/// the key and the value.
#[test]
fn a_spherical_tip_is_the_sphere_and_bad_tips_are_refused() {
    let base =
        r#""e_star_pa": 1e9, "work_of_adhesion_j_m2": 0.05, "s0_pa": 1e8, "loads_n": [0, 1e-8]"#;
    let as_tip = scene(&format!(
        r#"{{{base}, "tip": {{"shape": "sphere", "radius_m": 2e-8}}}}"#
    ))
    .unwrap();
    let as_radius = scene(&format!(r#"{{{base}, "radius_m": 2e-8}}"#)).unwrap();
    assert_eq!(
        serde_json::to_string(&as_tip).unwrap(),
        serde_json::to_string(&as_radius).unwrap()
    );
    for (tip, words) in [
        (
            r#"{"shape": "cone", "half_angle_deg": 95}"#,
            "half_angle_deg = 95",
        ),
        (
            r#"{"shape": "power", "exponent": 0.5, "coefficient": 1}"#,
            "exponent = 0.5",
        ),
        (
            r#"{"shape": "pyramid", "faces": 2, "face_angle_deg": 60}"#,
            "faces = 2",
        ),
    ] {
        let e = scene(&format!(r#"{{{base}, "tip": {tip}}}"#)).unwrap_err();
        assert!(e.contains(words) && !e.contains('\n'), "{e}");
    }
    let both = scene(&format!(
        r#"{{{base}, "radius_m": 2e-8, "tip": {{"shape": "cone", "half_angle_deg": 70}}}}"#
    ))
    .unwrap_err();
    assert!(both.contains("radius_m"), "{both}");
    let wet = scene(&format!(
        r#"{{{base}, "humidity": {{"relative_humidity": 0.4, "contact_angle_deg": 20}}, "tip": {{"shape": "cone", "half_angle_deg": 70}}}}"#
    ))
    .unwrap_err();
    assert!(wet.contains("humidity") && !wet.contains('\n'), "{wet}");
}

/// A tip scene under each control: load and displacement give the two pull-offs; a cantilever
/// gives the retract's jump of `tabor cycle --tip` (the command line, in the scene's own units
/// and kbar = k d / force unit) and, soft, the load-controlled pull-off; a bad one is refused.
#[test]
fn a_tip_scenes_control_is_its_cycles() {
    let with = |control: &str| {
        let json = format!(
            r#"{{"e_star_pa": 3.3e9, "work_of_adhesion_j_m2": 0.06, "h0_m": 0.5e-9,
                "tip": {{"shape": "capped_cone", "radius_m": 20e-9, "half_angle_deg": 20}},
                "loads_n": [0, 5e-9], "control": {control}}}"#
        );
        match scene(&json) {
            Ok(tabor::scene::Solved::Tip(r)) => Ok(r),
            Ok(_) => panic!("a tip scene"),
            Err(e) => Err(e),
        }
    };
    let load = with(r#""load""#).unwrap();
    assert_eq!(load.control, "load");
    assert_eq!(
        load.pulloff_force_under_control_N,
        load.pulloff_force_load_control_N
    );
    let grips = with(r#""displacement""#).unwrap();
    assert_eq!(
        grips.pulloff_force_under_control_N,
        grips.pulloff_force_displacement_control_N
    );
    let soft = with(r#"{"cantilever_n_m": 1e-4}"#).unwrap();
    assert!(
        (soft.pulloff_force_under_control_N / soft.pulloff_force_load_control_N - 1.0).abs() < 1e-4,
        "{} {}",
        soft.pulloff_force_under_control_N,
        soft.pulloff_force_load_control_N
    );
    let k = 0.5;
    let r = with(&format!(r#"{{"cantilever_n_m": {k}}}"#)).unwrap();
    let tabor::physics::tip::Shape::CappedCone { rho, half_angle } = r.units.shape else {
        panic!("a capped cone")
    };
    let kbar = k * r.units.approach_m / r.units.force_n;
    assert!(
        r.control.contains("cantilever k = 0.5 N/m"),
        "{}",
        r.control
    );
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args([
            "cycle",
            "--tip",
            &format!("capped-cone:{rho}:{}", half_angle.to_degrees()),
            "--lambda",
            &r.lambda.to_string(),
            "--control",
            "spring",
            "--stiffness",
            &kbar.to_string(),
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let c: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let jump = c["jumps"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["phase"] == "retract")
        .expect("a retract jump");
    let want = jump["from"]["load"].as_f64().unwrap() * r.units.force_n;
    assert!(
        (r.pulloff_force_under_control_N / want - 1.0).abs() < 1e-9,
        "{} {want}",
        r.pulloff_force_under_control_N
    );
    let e = with(r#"{"cantilever_n_m": -1}"#).unwrap_err();
    assert!(
        e.contains("control.cantilever_n_m") && !e.contains('\n'),
        "{e}"
    );
}

/// `tabor cycle --tip cone --lambda 1`: a cycle of the cone's law through the command line,
/// whose retract leaves contact at the law's rigid-grip fold; a tip with a scene is refused.
#[test]
fn a_cones_cycle_from_the_command_line() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(args)
            .output()
            .unwrap()
    };
    let out = run(&[
        "cycle", "--tip", "cone", "--lambda", "1", "--format", "json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let c: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let fold = power(1.0, 1.0).pulloff_state(Drive::RigidGrips);
    let jump = c["jumps"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["phase"] == "retract" && j["from"]["branch"] == "contact")
        .expect("a retract jump off contact");
    let load = jump["from"]["load"].as_f64().unwrap();
    assert!(
        (load - fold.load).abs() <= 1e-12 * fold.load.abs(),
        "{load} {}",
        fold.load
    );
    let bad = run(&["cycle", "--tip", "wedge", "--lambda", "1"]);
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success() && e.contains("--tip wedge"), "{e}");
}

/// `tabor solve --tip`: `power:2` gives `tabor solve`'s Maugis-Dugdale states (another code
/// path) at a load, an approach and a radius; a table gives the single states' bytes; below a
/// pull-off the status is `no_contact` with no numbers.
#[test]
fn tip_states_from_the_command_line() {
    let run = |args: &[&str], stdin: Option<&str>| {
        use std::io::Write;
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let mut input = child.stdin.take().unwrap();
        input.write_all(stdin.unwrap_or("").as_bytes()).unwrap();
        drop(input);
        let out = child.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let json = |args: &[&str]| -> serde_json::Value {
        let mut all = args.to_vec();
        all.extend(["--format", "json"]);
        serde_json::from_str(&run(&all, None)).unwrap()
    };
    for (flag, value) in [
        ("--load", "0.5"),
        ("--approach", "0.3"),
        ("--radius-a", "0.7"),
    ] {
        for lambda in ["0.3", "1", "5"] {
            let tip = json(&["solve", "--tip", "power:2", "--lambda", lambda, flag, value]);
            let md = json(&["solve", "--lambda", lambda, flag, value]);
            let (t, m) = (&tip["results"][0], &md["results"][0]);
            assert_eq!(t["status"], "ok", "{flag} {value} lambda {lambda}: {t}");
            for (a, b) in [("load", "load"), ("approach", "approach"), ("A", "A")] {
                let (x, y) = (t[a].as_f64().unwrap(), m[b].as_f64().unwrap());
                assert!(
                    (x - y).abs() <= 1e-12 * y.abs().max(1.0),
                    "{flag} {value} lambda {lambda}: {a} {x} against {y}"
                );
            }
        }
    }
    // `tabor pulloff --tip power:2` is `tabor pulloff` (the sphere's solver) at both controls.
    let tip = json(&["pulloff", "--tip", "power:2", "--lambda", "0.3,1,5"]);
    let md = json(&["pulloff", "--lambda", "0.3,1,5"]);
    for (t, m) in tip["results"]
        .as_array()
        .unwrap()
        .iter()
        .zip(md["results"].as_array().unwrap())
    {
        for k in [
            "load_control_load",
            "load_control_A",
            "displacement_control_load",
        ] {
            let (x, y) = (t[k].as_f64().unwrap(), m[k].as_f64().unwrap());
            assert!((x - y).abs() <= 1e-11, "{k}: {x} against {y}");
        }
    }
    let none = json(&["solve", "--tip", "cone", "--lambda", "1", "--load", "-50"]);
    assert_eq!(none["results"][0]["status"], "no_contact");
    assert!(none["results"][0]["A"].is_null(), "{none}");
    let one = |load: &str| {
        run(
            &[
                "solve",
                "--tip",
                "capped-cone:1:20",
                "--lambda",
                "2",
                "--load",
                load,
                "--format",
                "csv",
            ],
            None,
        )
    };
    let table = run(
        &["solve", "--tip", "capped-cone:1:20", "--input", "-"],
        Some("lambda,load\n2,0.5\n2,-50\n"),
    );
    let (a, b) = (one("0.5"), one("-50"));
    let expect = format!("{}{}", a, b.lines().nth(1).unwrap().to_string() + "\n");
    assert_eq!(table, expect);
}

/// Tip profiles: the adhesion-free pressure integrates to the shape's load `Qbar(A)` (the
/// cone's log-singular apex included), `power:2` is `tabor profile`'s Maugis-Dugdale field, and
/// the gap at the zone's edge is the range (J = w) for a cone and a capped cone.
#[test]
fn tip_profiles_carry_their_load_and_close_at_the_range() {
    use tabor::law::ContactLaw;
    use tabor::profile::spec::{LawProfile, ProfileSpec};
    use tabor::profile::Given;
    // 2 pi int_0^A p r dr by r = A sin(theta) and a fine composite Simpson rule.
    let load_of = |shape: Shape, a: f64| {
        let n = 20_000;
        let h = std::f64::consts::FRAC_PI_2 / n as f64;
        let f = |th: f64| {
            let r = a * th.sin();
            shape.hertz_pressure(a, r).unwrap_or(0.0) * r * a * th.cos()
        };
        let mut s = f(0.0) + f(std::f64::consts::FRAC_PI_2);
        for i in 1..n {
            s += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        2.0 * std::f64::consts::PI * s * h / 3.0
    };
    let capped = Shape::CappedCone {
        rho: 1.0,
        half_angle: 20f64.to_radians(),
    };
    for shape in [
        Shape::Power { exponent: 1.0 },
        Shape::Power { exponent: 1.5 },
        Shape::Power { exponent: 3.0 },
        capped,
    ] {
        for a in [0.3, 1.0, 2.5] {
            let (want, _) = shape.load(a);
            let got = load_of(shape, a);
            assert!(
                (got - want).abs() <= 1e-6 * want,
                "{shape:?} A {a}: pressure integrates to {got}, the load is {want}"
            );
        }
    }
    let run = |law: ContactLaw| {
        ProfileSpec {
            law,
            given: Given::Load(0.5),
            points: 200,
        }
        .run()
        .unwrap()
    };
    let (LawProfile::Tip(t), LawProfile::Md(m)) = (
        run(ContactLaw::Tip(power(2.0, 1.0))),
        run(ContactLaw::md(1.0)),
    ) else {
        panic!("the laws' own profiles")
    };
    // The same state, and at each of the tip's radii section 8's closed-form field.
    let md = &m.models[0];
    let (a, c) = (md.a.unwrap(), md.c.unwrap());
    assert!((t.a.unwrap() - a).abs() <= 1e-13 * a && (t.c.unwrap() - c).abs() <= 1e-13 * c);
    let field = tabor::physics::fields::MdGeometry {
        lambda: 1.0,
        a,
        mu: ((c - a) * (c + a)).sqrt() / a,
    };
    for i in 0..t.r.len() {
        let r = t.r[i];
        if (r - c).abs() <= 1e-12 * c {
            continue; // the Dugdale stress ends at C: the two C differ by rounding
        }
        let (p, q) = (t.pressure[i].unwrap(), field.pressure(r));
        assert!((p - q).abs() <= 1e-11, "r {r}: pressure {p} against {q}");
        let (g, h) = (t.gap[i], field.gap(r));
        assert!(
            (g - h).abs() <= 1e-11 * h.max(1.0),
            "r {r}: gap {g} against {h}"
        );
    }
    for law in [power(1.0, 0.3), Tip::new(capped, 3.0).unwrap()] {
        let LawProfile::Tip(p) = run(ContactLaw::Tip(law)) else {
            panic!("a tip's profile")
        };
        let j = p.energy_release_rate_over_w.unwrap();
        assert!((j - 1.0).abs() <= 1e-10, "{:?}: J/w = {j}", law.shape);
        // Zero gap inside the contact, open and rising outside it.
        let a = p.a.unwrap();
        for (r, g) in p.r.iter().zip(&p.gap) {
            assert!(if *r <= a { *g == 0.0 } else { *g > 0.0 }, "r {r}: gap {g}");
        }
    }
}

/// A scene's tip as a measured table of heights at `n` radii up to `r_max` (m).
fn tabulated(f: impl Fn(f64) -> f64, r_max: f64, n: usize) -> String {
    let r: Vec<f64> = (0..n).map(|i| r_max * i as f64 / (n - 1) as f64).collect();
    let z: Vec<f64> = r.iter().map(|&x| f(x)).collect();
    format!(
        r#"{{"shape": "profile", "r_m": {}, "z_m": {}}}"#,
        serde_json::to_string(&r).unwrap(),
        serde_json::to_string(&z).unwrap()
    )
}

/// A measured profile of a sphere, a blunt power law and a capped cone gives the exact tip's
/// pull-offs and per-load radii and approach within the error the scene states for its table
/// (the sphere's table is exact: the monotone cubic's three-point slopes are a parabola's)
/// (section 12.3); the table's tangent beyond its last point is said where the zone reaches it,
/// and bad tables are refused in one line naming the point.
#[test]
fn a_tabulated_tip_is_its_shape_within_the_stated_error() {
    let base = r#""e_star_pa": 1e9, "work_of_adhesion_j_m2": 0.05, "s0_pa": 5e7, "loads_n": [0, 2e-9, 1e-8]"#;
    let theta = 20f64.to_radians();
    let (r_cap, b) = (2e-8, 2e-8 * theta.cos());
    let capped = move |r: f64| {
        if r <= b {
            r_cap - (r_cap * r_cap - r * r).sqrt()
        } else {
            r_cap - r_cap / theta.sin() + r / theta.tan()
        }
    };
    let cases: [(&str, String, String); 3] = [
        (
            "sphere",
            r#"{"shape": "sphere", "radius_m": 2e-8}"#.into(),
            tabulated(|r| r * r / 4e-8, 3e-8, 60),
        ),
        (
            "power 3",
            r#"{"shape": "power", "exponent": 3, "coefficient": 1e15}"#.into(),
            tabulated(|r| 1e15 * r.powi(3), 3e-8, 100),
        ),
        (
            "capped cone",
            r#"{"shape": "capped_cone", "radius_m": 2e-8, "half_angle_deg": 20}"#.into(),
            tabulated(capped, 4e-8, 150),
        ),
    ];
    for (what, exact, table) in cases {
        let exact = match scene(&format!(r#"{{{base}, "tip": {exact}}}"#)).unwrap() {
            tabor::scene::Solved::Tip(r) => *r,
            // The sphere given as a tip is solved as the sphere's scene: take its exact tip law
            // through the square power law instead.
            tabor::scene::Solved::Sphere(_) => match scene(&format!(
                r#"{{{base}, "tip": {{"shape": "power", "exponent": 2, "coefficient": 2.5e7}}}}"#
            ))
            .unwrap()
            {
                tabor::scene::Solved::Tip(r) => *r,
                _ => unreachable!(),
            },
        };
        let tabor::scene::Solved::Tip(m) = scene(&format!(r#"{{{base}, "tip": {table}}}"#))
            .unwrap_or_else(|e| panic!("{what}: {e}"))
        else {
            panic!("a table is a tip scene")
        };
        let stated = m.profile_error.unwrap();
        assert!(
            m.warnings
                .iter()
                .any(|w| w.contains("gives these results within")),
            "{:?}",
            m.warnings
        );
        let mut worst: f64 = 0.0;
        let mut rel = |a: f64, b: f64| worst = worst.max((a / b - 1.0).abs());
        rel(
            m.pulloff_force_load_control_N,
            exact.pulloff_force_load_control_N,
        );
        rel(
            m.pulloff_force_displacement_control_N,
            exact.pulloff_force_displacement_control_N,
        );
        for (x, y) in m.loads.iter().zip(&exact.loads) {
            rel(x.contact_radius_m.unwrap(), y.contact_radius_m.unwrap());
            rel(x.zone_radius_m.unwrap(), y.zone_radius_m.unwrap());
            rel(x.approach_m.unwrap(), y.approach_m.unwrap());
        }
        println!("{what}: stated error {stated:.2e}, largest relative difference {worst:.2e}");
        assert!(
            // The stated error bounds the table's; 1e-10 is the solver's and quadrature's floor.
            stated < 1e-2 && worst <= stated + 1e-10,
            "{what}: {worst} against {stated}"
        );
    }
    // A table ending inside the zone is continued by its tangent, and said so.
    let short = tabulated(|r| r * r / 4e-8, 4e-9, 40);
    let tabor::scene::Solved::Tip(m) = scene(&format!(r#"{{{base}, "tip": {short}}}"#)).unwrap()
    else {
        panic!()
    };
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("beyond the measured profile")),
        "{:?}",
        m.warnings
    );
    for (table, words) in [
        (
            r#"{"shape": "profile", "r_m": [0, 1e-9, 2e-9, 3e-9], "z_m": [0, 1e-10, 5e-11, 2e-10]}"#,
            "z_m[2] = 5e-11",
        ),
        (
            r#"{"shape": "profile", "r_m": [0, 1e-9, 2e-9], "z_m": [0, 1e-10, 2e-10]}"#,
            "at least 4",
        ),
        (
            r#"{"shape": "profile", "r_m": [0, 1e-9, 2e-9, 3e-9], "z_m": [0, 1e-10, 2e-10]}"#,
            "one height per radius",
        ),
    ] {
        let e = scene(&format!(r#"{{{base}, "tip": {table}}}"#)).unwrap_err();
        assert!(e.contains(words) && !e.contains('\n'), "{e}");
    }
}

/// A scene's tip in the normalised commands (`--tip scene:FILE`, its shape in the units of the
/// scene's E* and w): a measured table of the cubic power law gives `power:3`'s state, pull-offs,
/// map thresholds, cycle and profile within the error the scene states for its table; the
/// command says the units and the scene's own lambda; a scene without a tip is refused.
#[test]
fn a_scenes_tip_in_its_units_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("cubic.json");
    let base =
        r#""e_star_pa": 1e9, "work_of_adhesion_j_m2": 0.05, "s0_pa": 5e7, "loads_n": [0, 2e-9]"#;
    let table = tabulated(|r| 1e15 * r.powi(3), 3e-8, 100);
    std::fs::write(&file, format!(r#"{{{base}, "tip": {table}}}"#)).unwrap();
    let tabor::scene::Solved::Tip(stated) =
        scene(&format!(r#"{{{base}, "tip": {table}}}"#)).unwrap()
    else {
        panic!("a table is a tip scene")
    };
    let (error, scene_lambda) = (stated.profile_error.unwrap(), stated.lambda);
    assert!(error > 1e-5 && error < 1e-2, "{error}");
    let tip = format!("scene:{}", file.display());
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{args:?}: {err}");
        (String::from_utf8(out.stdout).unwrap(), err)
    };
    let json = |args: &[&str]| -> (serde_json::Value, String) {
        let (out, err) = run(args);
        (serde_json::from_str(&out).unwrap(), err)
    };
    let near = |x: &serde_json::Value, y: &serde_json::Value, what: &str| {
        let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
        assert!(
            (x - y).abs() <= error * y.abs().max(1e-12),
            "{what}: {x} against {y} (stated {error:e})"
        );
    };
    // One state, with the pull-offs.
    let state = |t: &str| {
        json(&[
            "solve", "--tip", t, "--lambda", "1", "--load", "0.5", "--format", "json",
        ])
    };
    let ((m, said), (p, _)) = (state(&tip), state("power:3"));
    assert!(
        said.contains("a measured profile (100 points")
            && said.contains(&format!("the scene's own lambda is {scene_lambda:.6}")),
        "{said}"
    );
    let (m, p) = (&m["results"][0], &p["results"][0]);
    for k in ["A", "C", "approach"] {
        near(&m[k], &p[k], k);
    }
    let pulloffs = |t: &str| json(&["pulloff", "--tip", t, "--lambda", "1", "--format", "json"]).0;
    let (mp, pp) = (pulloffs(&tip), pulloffs("power:3"));
    for k in ["load_control_load", "displacement_control_load"] {
        near(&mp["results"][0][k], &pp["results"][0][k], k);
    }
    // The map: pull-off per lambda, and where each closed form becomes adequate.
    let map = |t: &str| {
        let out = dir.path().join(format!("{}.json", t.len()));
        let png = dir.path().join(format!("{}.png", t.len()));
        let (o, p) = (out.to_str().unwrap(), png.to_str().unwrap());
        let args = [
            "map",
            "--tip",
            t,
            "--nx",
            "6",
            "--ny",
            "8",
            "--lambda-min",
            "0.1",
            "--lambda-max",
            "10",
            "--out",
            p,
            "--json",
            o,
        ];
        run(&args);
        serde_json::from_str::<serde_json::Value>(&std::fs::read_to_string(&out).unwrap()).unwrap()
    };
    let (mm, pm) = (map(&tip), map("power:3"));
    assert_eq!(
        mm["metadata"]["tip"]["shape"], "measured",
        "{}",
        mm["metadata"]["tip"]
    );
    let (mt, pt) = (
        mm["thresholds"].as_array().unwrap(),
        pm["thresholds"].as_array().unwrap(),
    );
    assert_eq!(mt.len(), 6);
    for (a, b) in mt.iter().zip(pt) {
        near(&a["pulloff_load"], &b["pulloff_load"], "the map's pull-off");
        for k in ["hertz", "rigid", "dmt", "jkr"] {
            let key = format!("{k}_adequate_above_load");
            assert_eq!(a[&key], b[&key], "{key} at lambda {}", a["lambda"]);
        }
    }
    // The cycle's loop and its separation (the non-contact branch's fold: the table's path,
    // nearly flat where the contact shrinks to nothing, may add a jump of 6e-5 in approach
    // before it), and the profile's radii.
    let cycle = |t: &str| json(&["cycle", "--tip", t, "--lambda", "1", "--format", "json"]).0;
    let (mc, pc) = (cycle(&tip), cycle("power:3"));
    near(&mc["hysteresis"], &pc["hysteresis"], "the loop");
    let last =
        |c: &serde_json::Value| c["jumps"].as_array().unwrap().last().unwrap()["from"].clone();
    near(
        &last(&mc)["load"],
        &last(&pc)["load"],
        "the separation's load",
    );
    let profile = |t: &str| {
        json(&[
            "profile", "--tip", t, "--lambda", "1", "--load", "0.5", "--format", "json",
        ])
        .0
    };
    let (mp, pp) = (profile(&tip), profile("power:3"));
    for k in ["a", "c"] {
        near(&mp[k], &pp[k], k);
    }
    // A sphere's scene has no tip to take.
    std::fs::write(&file, format!(r#"{{{base}, "radius_m": 1e-8}}"#)).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(["solve", "--tip", &tip, "--lambda", "1", "--load", "0.5"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("has no \"tip\""),
        "{err}"
    );
}
