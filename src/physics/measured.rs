//! A measured tip (docs/PHYSICS.md section 12.3): the gap profile given as a table (r, z),
//! interpolated by the monotone piecewise cubic of Fritsch and Carlson (1980) and continued
//! beyond its last point by its tangent; its Abel transform and its adhesion-free load in closed
//! form, interval by interval (the cubic's slope is a quadratic in sin phi along r = T sin phi).

use super::domain::short;
use crate::error::Message;
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;

/// An interpolated profile: radii, heights above the apex and the cubic's slopes there.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Profile {
    /// The table's radii (from 0, rising).
    #[serde(skip)]
    r: Vec<f64>,
    /// The heights above the apex (z - z at r = 0; never falling).
    #[serde(skip)]
    z: Vec<f64>,
    /// The interpolant's slopes at the radii.
    #[serde(skip)]
    s: Vec<f64>,
    /// On each interval, the slope `f'` as `c0 + c1 t + c2 t^2` in `t = (r - r_k) / h_k`.
    #[serde(skip)]
    c: Vec<[f64; 3]>,
    /// The number of points.
    pub points: usize,
    /// The largest radius of the table (in the profile's length unit).
    pub largest_radius: f64,
    /// The profile of every other point (and the last), which [`Profile::error_between`]
    /// compares with.
    #[serde(skip)]
    half: Option<Box<Profile>>,
}

/// The monotone cubic's slopes (Fritsch and Carlson 1980): the three-point parabola's slope at
/// each point (exact for a parabola, so that a smooth apex is interpolated to third order), the
/// shape-preserving three-point formula at the ends, then limited on each interval to the
/// region where the cubic cannot fall (alpha^2 + beta^2 <= 9).
fn monotone_slopes(r: &[f64], z: &[f64]) -> Vec<f64> {
    let n = r.len();
    let h: Vec<f64> = r.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|k| (z[k + 1] - z[k]) / h[k]).collect();
    let mut s = vec![0.0; n];
    for k in 1..n - 1 {
        if d[k - 1] > 0.0 && d[k] > 0.0 {
            s[k] = (h[k] * d[k - 1] + h[k - 1] * d[k]) / (h[k - 1] + h[k]);
        }
    }
    let end = |h0: f64, h1: f64, d0: f64, d1: f64| {
        let e = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
        if e * d0 <= 0.0 {
            0.0
        } else if d0 * d1 <= 0.0 && e.abs() > 3.0 * d0.abs() {
            3.0 * d0
        } else {
            e
        }
    };
    s[0] = end(h[0], h[1], d[0], d[1]);
    s[n - 1] = end(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
    for k in 0..n - 1 {
        if d[k] == 0.0 {
            s[k] = 0.0;
            s[k + 1] = 0.0;
            continue;
        }
        let (alpha, beta) = (s[k] / d[k], s[k + 1] / d[k]);
        let q = alpha.hypot(beta);
        if q > 3.0 {
            s[k] = 3.0 * alpha / q * d[k];
            s[k + 1] = 3.0 * beta / q * d[k];
        }
    }
    s
}

impl Profile {
    /// The profile of the table `r`, `z` (any one length unit): `r` from 0 (the axis) strictly
    /// rising, `z` never falling (its value at r = 0 is the apex). Errors name the first bad
    /// point.
    pub fn new(r: &[f64], z: &[f64]) -> Result<Profile, Message> {
        let rk = || Message::new().key("r_m");
        let zk = || Message::new().key("z_m");
        if r.len() != z.len() {
            return Err(rk()
                .text(format!(" has {} values and ", r.len()))
                .then(zk().text(format!(" {}: give one height per radius", z.len()))));
        }
        if r.len() < 4 {
            return Err(format!(
                "the profile has {} points: give at least 4 (r, z) pairs from the axis outwards",
                r.len()
            )
            .into());
        }
        if let Some(i) = (0..r.len()).find(|&i| !(r[i].is_finite() && z[i].is_finite())) {
            return Err(Message::new()
                .text(format!("point {i} of the profile ("))
                .then(rk().text(format!(" = {}, ", short(r[i]))))
                .then(zk().text(format!(" = {}) is not a finite number", short(z[i])))));
        }
        if r[0] != 0.0 {
            return Err(rk().text(format!(
                "[0] = {} is not 0: the profile starts on the tip's axis (r = 0 at the apex)",
                short(r[0])
            )));
        }
        if let Some(i) = (1..r.len()).find(|&i| r[i] <= r[i - 1]) {
            return Err(rk()
                .text(format!("[{i}] = {} does not rise from ", short(r[i])))
                .then(rk().text(format!(
                    "[{}] = {}: give the radii in increasing order",
                    i - 1,
                    short(r[i - 1])
                ))));
        }
        if let Some(i) = (1..z.len()).find(|&i| z[i] < z[i - 1]) {
            return Err(zk()
                .text(format!("[{i}] = {} falls below ", short(z[i])))
                .then(zk().text(format!(
                    "[{}] = {}: the tip's height must not fall away from its apex (smooth the \
                     measured profile, or cut it where it turns)",
                    i - 1,
                    short(z[i - 1])
                ))));
        }
        let z: Vec<f64> = z.iter().map(|v| v - z[0]).collect();
        if !(z[z.len() - 1] > 0.0) {
            return Err(Message::new()
                .key("z_m")
                .text(" is flat: the tip's height must rise away from its apex"));
        }
        Ok(Profile::with_half(r.to_vec(), z))
    }

    /// [`Profile::new`] held for the life of the process, once per distinct table (a shape is
    /// `Copy` and holds a reference to it): the tips a fleet's every curve and a fit's every
    /// step build from the same table share one. Memory grows by one table (a few kilobytes)
    /// per distinct table a process reads, bit for bit: a study of many measured tips holds
    /// them all.
    pub fn interned(r: &[f64], z: &[f64]) -> Result<&'static Profile, Message> {
        use std::collections::HashMap;
        use std::sync::{Mutex, OnceLock};
        static TABLES: OnceLock<Mutex<HashMap<Vec<u64>, &'static Profile>>> = OnceLock::new();
        let key: Vec<u64> = r
            .iter()
            .chain(z)
            .map(|v| v.to_bits())
            .chain([r.len() as u64])
            .collect();
        let tables = TABLES.get_or_init(Default::default);
        if let Some(&p) = tables.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return Ok(p);
        }
        let p: &'static Profile = Box::leak(Box::new(Profile::new(r, z)?));
        Ok(*tables
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .entry(key)
            .or_insert(p))
    }

    fn interpolant(r: Vec<f64>, z: Vec<f64>) -> Profile {
        let s = monotone_slopes(&r, &z);
        let c = (0..r.len() - 1)
            .map(|k| {
                let d = (z[k + 1] - z[k]) / (r[k + 1] - r[k]);
                [
                    s[k],
                    6.0 * d - 4.0 * s[k] - 2.0 * s[k + 1],
                    3.0 * (s[k] + s[k + 1]) - 6.0 * d,
                ]
            })
            .collect();
        Profile {
            points: r.len(),
            largest_radius: r[r.len() - 1],
            half: None,
            r,
            z,
            s,
            c,
        }
    }

    /// The interpolant of `r`, `z` with that of every other point beside it.
    fn with_half(r: Vec<f64>, z: Vec<f64>) -> Profile {
        let n = r.len();
        let keep: Vec<usize> = (0..n).filter(|i| i % 2 == 0 || *i == n - 1).collect();
        let half = (keep.len() >= 3).then(|| {
            Box::new(Profile::interpolant(
                keep.iter().map(|&i| r[i]).collect(),
                keep.iter().map(|&i| z[i]).collect(),
            ))
        });
        let mut p = Profile::interpolant(r, z);
        p.half = half;
        p
    }

    /// The interpolation's error estimate over the contact radii `lo..hi`: the largest relative
    /// difference between this profile's Abel transform (the approach at contact radius T,
    /// which every state rests on) and that of every other point's (an upper estimate:
    /// halving the spacing divides the cubic's error by about 8).
    pub fn error_between(&self, lo: f64, hi: f64) -> f64 {
        let Some(half) = &self.half else {
            return f64::INFINITY;
        };
        let lo = lo.max(self.r[1]);
        (0..=64)
            .map(|i| lo * (hi / lo).max(1.0).powf(i as f64 / 64.0))
            .map(|t| {
                let f = self.abel(t).0;
                (f - half.abel(t).0).abs() / f
            })
            .fold(0.0, f64::max)
    }

    /// The height, slope and curvature at radius `x >= 0` (the tangent beyond the table).
    pub fn eval(&self, x: f64) -> (f64, f64, f64) {
        let n = self.r.len();
        if x >= self.r[n - 1] {
            return (
                self.z[n - 1] + self.s[n - 1] * (x - self.r[n - 1]),
                self.s[n - 1],
                0.0,
            );
        }
        let k = self.r.partition_point(|&v| v <= x).clamp(1, n - 1) - 1;
        let h = self.r[k + 1] - self.r[k];
        let t = (x - self.r[k]) / h;
        let (z0, z1, s0, s1) = (self.z[k], self.z[k + 1], self.s[k], self.s[k + 1]);
        let t2 = t * t;
        let f = (2.0 * t2 * t - 3.0 * t2 + 1.0) * z0
            + (t2 * t - 2.0 * t2 + t) * h * s0
            + (3.0 * t2 - 2.0 * t2 * t) * z1
            + (t2 * t - t2) * h * s1;
        // The slope and curvature from the interval's slope polynomial (the closed forms' too).
        let [c0, c1, c2] = self.c[k];
        (f, c0 + (c1 + c2 * t) * t, (c1 + 2.0 * c2 * t) / h)
    }

    /// `int_0^(pi/2) sin^j(phi) f'(T sin phi) dphi` combined into `F/T`, `F'` (weights 1, 2, 3
    /// on the powers of sin phi: `f' + r f''`) and Sneddon's load integral over A^2 (j + 2), in
    /// closed form interval by interval: on interval k, f' is `a0 + a1 sin + a2 sin^2`. The
    /// load's moment only when `LOAD` (the gap integrals call the transform alone, most often).
    fn moments<const LOAD: bool>(&self, t: f64) -> [f64; 3] {
        let (mut f, mut df, mut q) = (0.0, 0.0, 0.0);
        // sin, cos and phi at the interval's start.
        let (mut sa, mut ca, mut pa) = (0.0f64, 1.0f64, 0.0f64);
        let n = self.r.len();
        for k in 0..n - 1 {
            let (sb, cb, pb) = if self.r[k + 1] < t {
                let s = self.r[k + 1] / t;
                (s, ((1.0 - s) * (1.0 + s)).sqrt(), s.asin())
            } else {
                (1.0, 0.0, FRAC_PI_2)
            };
            let h = self.r[k + 1] - self.r[k];
            let (u, v) = (t / h, self.r[k] / h);
            let [c0, c1, c2] = self.c[k];
            let a0 = c0 - c1 * v + c2 * v * v;
            let a1 = (c1 - 2.0 * c2 * v) * u;
            let a2 = c2 * u * u;
            let dp = pb - pa;
            let (sca, scb) = (sa * ca, sb * cb);
            let i0 = dp;
            let i1 = ca - cb;
            let i2 = 0.5 * dp - 0.5 * (scb - sca);
            f += a0 * i0 + a1 * i1 + a2 * i2;
            df += a0 * i0 + 2.0 * a1 * i1 + 3.0 * a2 * i2;
            if LOAD {
                let i3 = (ca - cb) - (ca.powi(3) - cb.powi(3)) / 3.0;
                // int sin^4 = 3 phi/8 - sin(2 phi)/4 + sin(4 phi)/32, sin 4phi = 4 s c (1 - 2 s^2).
                let i4 = 0.375 * dp - 0.5 * (scb - sca)
                    + (scb * (1.0 - 2.0 * sb * sb) - sca * (1.0 - 2.0 * sa * sa)) / 8.0;
                q += a0 * i2 + a1 * i3 + a2 * i4;
            }
            if pb == FRAC_PI_2 {
                return [f, df, q];
            }
            (sa, ca, pa) = (sb, cb, pb);
        }
        // Beyond the table: the tangent's constant slope.
        let sn = self.s[n - 1];
        let rest = FRAC_PI_2 - pa;
        [
            f + sn * rest,
            df + sn * rest,
            q + sn * (0.5 * rest + 0.5 * sa * ca),
        ]
    }

    /// The Abel transform `F(T) = T int_0^(pi/2) f'(T sin phi) dphi` (the adhesion-free approach
    /// at contact radius T) and its slope `int_0^(pi/2) (f' + r f'')(T sin phi) dphi`.
    pub fn abel(&self, t: f64) -> (f64, f64) {
        if t <= 0.0 {
            return (0.0, self.s[0] * FRAC_PI_2);
        }
        let [f, df, _] = self.moments::<false>(t);
        (t * f, df)
    }

    /// Sneddon's load integral `int_0^A r^2 f'(r) / sqrt(A^2 - r^2) dr
    /// = A^2 int_0^(pi/2) sin^2 phi f'(A sin phi) dphi`.
    pub fn load_integral(&self, a: f64) -> f64 {
        if a <= 0.0 {
            return 0.0;
        }
        a * a * self.moments::<true>(a)[2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A line's table is reproduced exactly (a cone: F = (pi/2) B T), and a tabulated parabola
    /// r^2 transforms to its closed forms: F = k_2 T^2 = 2 T^2 (F = k_n T^n for r^n), F' = 4 T,
    /// Sneddon's load integral (4/3) A^3.
    #[test]
    fn a_line_is_exact_and_a_parabola_transforms_to_its_closed_form() {
        let r: Vec<f64> = (0..50).map(|i| i as f64 * 0.1).collect();
        let line = Profile::new(&r, &r.iter().map(|x| 2.0 * x).collect::<Vec<_>>()).unwrap();
        for x in [0.05, 1.234, 4.9, 7.0] {
            let (f, d, dd) = line.eval(x);
            assert!((f - 2.0 * x).abs() < 1e-14 && (d - 2.0).abs() < 1e-14 && dd.abs() < 1e-12);
            // The cone's F = (pi/2) B T.
            let (ft, dft) = line.abel(x);
            assert!(
                (ft - FRAC_PI_2 * 2.0 * x).abs() < 1e-13 * x
                    && (dft - FRAC_PI_2 * 2.0).abs() < 1e-13
            );
        }
        let fine: Vec<f64> = (0..=400).map(|i| i as f64 * 0.01).collect();
        let p = Profile::new(&fine, &fine.iter().map(|x| x * x).collect::<Vec<_>>()).unwrap();
        for t in [0.3, 1.0, 3.5] {
            let (f, d) = p.abel(t);
            assert!((f / (2.0 * t * t) - 1.0).abs() < 1e-6, "{t}: {f}");
            assert!((d / (4.0 * t) - 1.0).abs() < 1e-5, "{t}: {d}");
            assert!((p.load_integral(t) / (4.0 / 3.0 * t.powi(3)) - 1.0).abs() < 1e-6);
        }
        // The three-point slopes are exact for a parabola: so are both interpolants.
        assert!(p.error_between(0.1, 4.0) < 1e-12);
    }

    #[test]
    fn bad_tables_are_refused_naming_the_point() {
        let e = Profile::new(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, 0.5, 2.0]).unwrap_err();
        assert!(e.to_string().contains("z_m[2] = 0.5"), "{e}");
        let e = Profile::new(&[0.1, 1.0, 2.0, 3.0], &[0.0, 1.0, 1.5, 2.0]).unwrap_err();
        assert!(e.to_string().contains("r_m[0]"), "{e}");
        let e = Profile::new(&[0.0, 1.0, 1.0, 3.0], &[0.0, 1.0, 1.5, 2.0]).unwrap_err();
        assert!(e.to_string().contains("r_m[2]"), "{e}");
    }
}
