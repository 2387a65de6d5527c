//! The command line's refusals, word for word: each library error rendered with the command's
//! flags (`cli::in_flags` over `tabor::error::Named`), never with the library's keys where a flag
//! was given. The lines were those of the build before the errors were typed, but for two stated
//! in the CHANGELOG (a domain hint's "lambda" and a tip profile's "sampling points").

use std::process::Command;

/// (arguments, the message after "error: ").
const REFUSALS: &[(&str, &str)] = &[
    (
        r"map --lambda-min 5 --lambda-max 1 --out o.png",
        r"--lambda-min must be below --lambda-max, got 5 and 1",
    ),
    (
        r"map --lambda-min 1e-30 --lambda-max 1 --out o.png",
        r"--lambda-min: lambda = 1e-30 is outside the supported domain 1e-26..1e26: outside it the exact solver cannot certify its answer; single states (solve) are answered by the DMT limit for lambda in 1e-300..1e-26 and by the JKR limit for lambda in 1e26..1e150 (method field), where each is within 1e-13 of MD",
    ),
    (
        r"map --nx 1 --out o.png",
        r"--nx and --ny must be in 2..=16384, got 1 and 1024",
    ),
    (
        r"map --nx 5000 --ny 5000 --quantity a --out o.png",
        r"--nx 5000 x --ny 5000 is 25000000 points, more than the 16777216 (4096 x 4096) a map holds in memory (about 300 MB, or 700 MB with --npy or --json-full), a map of regions alone (without --quantity, --npy or --json-full) up to 16384 x 16384; use fewer points, or split the range into several maps",
    ),
    (
        r"map --nx 5000 --ny 5000 --tip cone --out o.png",
        r"--nx 5000 x --ny 5000 is 25000000 points, more than the 16777216 (4096 x 4096) a tip's map holds in memory (every point's values are kept); use fewer points, or split the range into several maps",
    ),
    (
        r"map --load-min 5 --load-max 1 --out o.png",
        r"--load-min must be below --load-max, got 5 and 1",
    ),
    (
        r"map --load-min -1 --out o.png",
        r"a log load axis needs --load-min > 0 (got -1); use --load-axis linear for tensile loads",
    ),
    (
        r"map --load-min 1e-20 --out o.png",
        r"--load-min 1e-20 and --load-max 1000 must lie within 1e-15..1e12 on this load axis (the solver's domain); narrow the range",
    ),
    (
        r"map --load-axis linear --load-min -1e13 --out o.png",
        r"--load-min -1e13 and --load-max 10 must lie within -1e12..1e12 on this load axis (the solver's domain); narrow the range",
    ),
    (
        r"map --tolerance 2 --out o.png",
        r"--tolerance must be in (0, 1), got 2",
    ),
    (
        r"map --strength-ratio -1 --out o.png",
        r"--strength-ratio values must be > 0",
    ),
    (
        r"map --width-mm 10 --out o.png",
        r"--width-mm 10 is outside 40..600: give the printed width in millimetres (85 for one column, 175 for two)",
    ),
    (
        r"map --dpi 10 --out o.png",
        r"--dpi 10 is outside 50..2400: give the PNG resolution in dots per inch (300 is usual for print)",
    ),
    (
        r"map --width-mm 600 --dpi 2400 --out o.png",
        r"--width-mm 600 at --dpi 2400 makes a PNG 56693 pixels wide, more than 16000: lower one of them",
    ),
    (
        r"rough-map --sigma-min 0 --out o.png",
        r"--sigma-min 0 and --sigma-max 100 are not a roughness range: give 0 < --sigma-min < --sigma-max <= 1e4 (approach units)",
    ),
    (
        r"rough-map --nx 1 --out o.png",
        r"--nx and --ny must be in 2..=4096, got 1 and 256",
    ),
    (
        r"rough-map --tolerance 2 --out o.png",
        r"--tolerance must be in (0, 1), got 2",
    ),
    (
        r"rough-map --press-sigmas 100 --out o.png",
        r"--press-sigmas = 100 is not valid: give how many sigma below the mean summit plane the flat was pressed, -6..6 (pressed 6 sigma, all but 1e-9 of the summits have touched: a deeper press changes nothing more)",
    ),
    (
        r"rough-map --check 200000 --out o.png",
        r"--check 200000: give at most 100000 points to re-solve",
    ),
    (
        r"rough-map --lambda-min 3 --lambda-max 1 --out o.png",
        r"--lambda-min must be below --lambda-max, got 3 and 1",
    ),
    (
        r"rough-pulloff --sigma-min 0",
        r"--sigma-min 0 and --sigma-max 10 are not a roughness range: give 0 < --sigma-min < --sigma-max <= 1e4 (approach units)",
    ),
    (
        r"rough-pulloff --points 1",
        r"--points = 1: give 2..1000 roughnesses",
    ),
    (
        r"rough-pulloff --press-sigmas 100",
        r"--press-sigmas = 100 is not valid: give how many sigma below the mean summit plane the flat was pressed, -6..6 (pressed 6 sigma, all but 1e-9 of the summits have touched: a deeper press changes nothing more)",
    ),
    (
        r"rough-pulloff --lambda 1 --lambda 2 --lambda 3 --lambda 4 --lambda 5 --lambda 6 --lambda 7 --lambda 8 --lambda 9 --lambda 10 --lambda 11 --lambda 12 --lambda 13 --lambda 14 --lambda 15 --lambda 16 --lambda 17 --lambda 18 --lambda 19 --lambda 20 --lambda 21",
        r"21 --lambda values: give 1..20",
    ),
    (
        r"rough --lambda 1 --sigma 1 --min-separation 1e5",
        r"the separations (--min-separation, --max-separation, --points): --min-separation = 100000 is beyond the summits' reach (9.49173 approach units: no summit feels the flat there), so nothing would touch: give a smaller --min-separation",
    ),
    (
        r"rough --lambda 1 --sigma 1 --min-separation 1e9",
        r"the separations (--min-separation, --max-separation, --points): --min-separation = 1e9 is beyond the summits' reach (9.49173 approach units: no summit feels the flat there), so nothing would touch: give a smaller --min-separation",
    ),
    (
        r"rough --lambda 1e-30 --sigma 1 --min-separation 0",
        r"--lambda = 1e-30 is outside the supported domain 1e-26..1e26: outside it the exact solver cannot certify its answer; single states (solve) are answered by the DMT limit for lambda in 1e-300..1e-26 and by the JKR limit for lambda in 1e26..1e150 (method field), where each is within 1e-13 of MD",
    ),
    (
        r"rough --lambda 1 --sigma 1 --min-separation 0 --stress-ratio 1",
        r"give --stress-ratio and --range-ratio together (the second zone's stress and range over the solid's), or neither for one zone",
    ),
    (
        r"rough --lambda 1e-12 --sigma 1 --min-separation 0 --stress-ratio 1e6 --range-ratio 1",
        r"the wet summit could not be solved: --lambda 1e-12, --stress-ratio 1000000 (rho), --range-ratio 1 (eta): the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 1e-14 is outside 1e-8..1e6, where the two-zone law is solved: give a --lambda that brings it inside, or no --stress-ratio and --range-ratio for the one-zone law, whose --lambda may be 1e-26..1e26",
    ),
    (
        r"profile --lambda 1 --load 1 --points 3",
        r"--points 3 is out of range: give 16..=100000 sampling radii",
    ),
    (
        r"profile --lambda 1 --load 1 --points 3 --stress-ratio 1 --range-ratio 2",
        r"--points 3 is out of range: give 16..=100000 sampling radii",
    ),
    (
        r"profile --lambda 1e-12 --load 1 --stress-ratio 1e6 --range-ratio 2",
        r"--lambda 1e-12, --stress-ratio 1000000 (rho), --range-ratio 2 (eta): the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 7.937e-15 is outside 1e-8..1e6, where the two-zone law is solved: give a --lambda that brings it inside, or no --stress-ratio and --range-ratio for the one-zone law, whose --lambda may be 1e-26..1e26",
    ),
    (
        r"profile --lambda 1 --load 1 --points 3 --tip cone:70",
        r"--tip cone:70: give cone, sphere, power:N or capped-cone:R_OVER_L:HALF_ANGLE_DEG (or scene:FILE, a scene's tip)",
    ),
    (
        r"profile --lambda 1 --load 1 --stress-ratio 1",
        r"give --stress-ratio and --range-ratio together (the second zone's stress and range over the solid's), or neither for one zone",
    ),
    (
        r"dem-law --lambda 1 --overlap-max 1e9",
        r"--lambda 1: --overlap-max = 1e9 is outside the supported domain (delta_out, 1e4] approach units: give a largest overlap above the contact branch's fold and at most 1e4 approach units",
    ),
    (
        r"dem-law --lambda 1 --overlap-max -1",
        r"--lambda 1: --overlap-max = -1 is outside the supported domain (delta_out, 1e4] approach units: give a largest overlap above the contact branch's fold and at most 1e4 approach units",
    ),
    (
        r"dem-law --lambda 1 --stress-ratio 1",
        r"give --stress-ratio and --range-ratio together (the second zone's stress and range over the solid's), or neither for one zone",
    ),
    (
        r"dem-law --lambda 1e-12 --stress-ratio 1e6 --range-ratio 1",
        r"--lambda 0.000000000001: lambda 1e-12, --stress-ratio 1000000 (rho), --range-ratio 1 (eta): the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 1e-14 is outside 1e-8..1e6, where the two-zone law is solved: give a lambda that brings it inside, or no --stress-ratio and --range-ratio for the one-zone law, whose lambda may be 1e-26..1e26",
    ),
    (
        r"dem-law --lambda 1 --stress-ratio -1 --range-ratio 1",
        r"--lambda 1: stress ratio = -1 must be a finite number >= 0",
    ),
    (
        r"solve --lambda 1 --load 1 --stress-ratio 1",
        r"give --stress-ratio and --range-ratio together (the second zone's stress and range over the solid's), or neither for one zone",
    ),
    (
        r"solve --lambda 1e-9 --stress-ratio 1e6 --range-ratio 1 --load 0",
        r"--lambda 1e-9, --stress-ratio 1000000 (rho), --range-ratio 1 (eta): the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 1e-11 is outside 1e-8..1e6, where the two-zone law is solved: give a --lambda that brings it inside, or no --stress-ratio and --range-ratio for the one-zone law, whose --lambda may be 1e-26..1e26",
    ),
    (
        r"solve --lambda 1 --stress-ratio -1 --range-ratio 1 --load 0",
        r"stress ratio = -1 must be a finite number >= 0",
    ),
    (
        r"solve --lambda 0 --stress-ratio 1 --range-ratio 1 --load 0",
        r"--lambda = 0 must be > 0",
    ),
    (
        r"solve --lambda -1 --stress-ratio 1 --range-ratio 1 --load 0",
        r"--lambda = -1 must be a finite number >= 0",
    ),
    (
        r"solve --lambda nan --stress-ratio 1 --range-ratio 1 --load 0",
        r"--lambda = NaN must be a finite number >= 0",
    ),
    (
        r"pulloff --lambda 1 --stress-ratio -1 --range-ratio 1",
        r"stress ratio = -1 must be a finite number >= 0",
    ),
    (
        r"pulloff --lambda 1e-12 --stress-ratio 1e6 --range-ratio 1",
        r"--lambda 1e-12, --stress-ratio 1000000 (rho), --range-ratio 1 (eta): the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 1e-14 is outside 1e-8..1e6, where the two-zone law is solved: give a --lambda that brings it inside, or no --stress-ratio and --range-ratio for the one-zone law, whose --lambda may be 1e-26..1e26",
    ),
    (
        r"cycle --lambda 1e-30 --stress-ratio 1 --range-ratio 1",
        r"--lambda: lambda = 1e-30 is outside the supported domain 1e-26..1e26: outside it the exact solver cannot certify its answer; single states (solve) are answered by the DMT limit for lambda in 1e-300..1e-26 and by the JKR limit for lambda in 1e26..1e150 (method field), where each is within 1e-13 of MD",
    ),
    (
        r"cycle --lambda 1e-30",
        r"--lambda: lambda = 1e-30 is outside the supported domain 1e-26..1e26: outside it the exact solver cannot certify its answer; single states (solve) are answered by the DMT limit for lambda in 1e-300..1e-26 and by the JKR limit for lambda in 1e26..1e150 (method field), where each is within 1e-13 of MD",
    ),
    (
        r"cycle --lambda 1e-12 --stress-ratio 1e6 --range-ratio 1",
        r"--lambda 1e-12, --stress-ratio 1000000 (rho), --range-ratio 1 (eta): the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = 1e-14 is outside 1e-8..1e6, where the two-zone law is solved: give a --lambda that brings it inside, or no --stress-ratio and --range-ratio for the one-zone law, whose --lambda may be 1e-26..1e26",
    ),
    (
        r"cycle --lambda 1 --stress-ratio 1",
        r"give --stress-ratio and --range-ratio together (the second zone's stress and range over the solid's), or neither for one zone",
    ),
    (
        r"infer --pulloff 1e-7 --radius 1e-6 --e-star 1e9 --z0 3e-10 --relative-humidity 0",
        r"--relative-humidity = 0 is dry air, where no meniscus forms: leave the humidity out for the dry inference",
    ),
    (
        r"infer --pulloff 1e-7 --radius 1e-6 --e-star 1e9 --z0 3e-10 --relative-humidity 1.5",
        r"--relative-humidity = 1.5 is out of range: it must be in 0..1 (a fraction, below 1: at 1 the Kelvin radius is infinite)",
    ),
    (
        r"humidity --preset afm-si --rh-min 0.9 --rh-max 0.5",
        r"--rh-max = 0.5 is out of range: it must be above --rh-min and below 1",
    ),
    (
        r"humidity --preset afm-si --points 1",
        r"--points = 1 is out of range: it must be in 2..10000",
    ),
    (
        r"humidity --preset afm-si --rh-max 0.9999999999",
        r"--rh-max = 0.9999999999: the meniscus (Kelvin radius 5.228 m, Laplace pressure 0.013772 Pa) has the stress number 3.32974e-12 beside the solid's 0.0827199, outside 1e-8..1e6 where the two-zone law is solved: give a relative humidity below 0.99999969 (the meniscus model fails already where its height nears a tenth of R)",
    ),
    (
        r"humidity --preset afm-si --rh-min -1",
        r"--rh-min = -1 is out of range: it must be in (0, 1)",
    ),
    (
        r"humidity --preset afm-si --contact-angle-deg 95",
        r"humidity.contact_angle_deg = 95 is out of range: it must be below 90 for a meniscus (at 90 or more water does not bridge the gap: the dry scene)",
    ),
    (
        r"humidity --preset afm-si --width-mm 10 --plot o.png",
        r"--width-mm 10 is outside 40..600: give the printed width in millimetres (85 for one column, 175 for two)",
    ),
    (
        r"scene --preset afm-si --plot o.png --dpi 3000",
        r"--dpi 3000 is outside 50..2400: give the PNG resolution in dots per inch (300 is usual for print)",
    ),
    (
        r"profile --tip cone --lambda 1 --load 1 --points 5",
        r"--points = 5: give 16 to 100000 sampling points",
    ),
];

#[test]
fn every_refusal_names_the_flags_given() {
    let dir = std::env::temp_dir().join(format!("tabor-refusals-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut wrong = Vec::new();
    for (args, want) in REFUSALS {
        let o = Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(args.split(' '))
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        let got = err.lines().find_map(|l| l.strip_prefix("error: "));
        if o.status.success() || got != Some(*want) {
            wrong.push(format!("tabor {args}\n  want: {want}\n  got:  {err}"));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
