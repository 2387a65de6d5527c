//! The number types the Maugis-Dugdale formulas are written for.
//!
//! The curve formulas in [`super::md`] are generic over [`Real`] so that one text serves the bulk
//! solves in `f64`, the pull-off search in double-double (whose condition number grows like
//! lambda^-3 at small lambda) and the `f32` mirror of the shaders.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// The number types the MD curve is written for (f64, f32, and the f64 pair of the kernels' host), so that one source serves every precision.
pub trait Real:
    Copy
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The value of an f64 in this type.
    fn of(x: f64) -> Self;
    /// This value as an f64.
    fn to_f64(self) -> f64;
    /// The square root.
    fn sqrt(self) -> Self;
    /// `(atan(mu), mu - atan(mu))` for `mu >= 0`, both to full relative precision: the
    /// difference is what f1 needs at small mu, where subtracting the two loses every digit.
    fn atan_parts(self) -> (Self, Self);
    /// 1 / (2k + 1), the atan series' coefficients, correctly rounded (a table for
    /// double-double: dividing there cost a fifth of the time of scattered solves).
    fn inv_odd(k: usize) -> Self {
        Self::of(1.0) / Self::of((2 * k + 1) as f64)
    }
}

/// `t - atan(t)` by its Maclaurin series, `terms` terms; accurate for `t <= 0.1`.
fn series_mu_minus_atan<T: Real>(t: T, terms: usize) -> T {
    let z = t * t;
    let mut acc = T::of(0.0);
    for k in (1..=terms).rev() {
        acc = T::inv_odd(k) - z * acc;
    }
    t * z * acc
}

/// Half-angle reduction: `atan(t) = 2 atan(t / (1 + sqrt(1 + t^2)))`, and
/// `t - atan(t) = t^3/(1+sqrt(1+t^2))^2 + 2 (t' - atan(t'))`: every term is positive, so
/// `mu - atan(mu)` keeps full precision for all mu up to 2 (beyond, plain subtraction is fine).
fn reduced_mu_minus_atan<T: Real>(mu: T, terms: usize) -> T {
    let mut t = mu;
    let mut weight = 1.0;
    let mut acc = T::of(0.0);
    while t > T::of(0.1) {
        let onem = T::of(1.0) + (T::of(1.0) + t * t).sqrt();
        acc = acc + T::of(weight) * t * t * t / (onem * onem);
        t = t / onem;
        weight *= 2.0;
    }
    acc + T::of(weight) * series_mu_minus_atan(t, terms)
}

impl Real for f64 {
    #[inline(always)]
    fn of(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn atan_parts(self) -> (Self, Self) {
        let mu = self;
        if mu < 0.1 {
            let d = series_mu_minus_atan(mu, 8);
            (mu - d, d)
        } else if mu < 2.0 {
            (mu.atan(), reduced_mu_minus_atan(mu, 8))
        } else {
            let at = mu.atan();
            (at, mu - at)
        }
    }
}

/// Double-double number: the unevaluated sum `hi + lo`, about 32 significant digits, from the
/// error-free transformations two-sum and two-product (Dekker 1971; Hida, Li and Bailey's QD).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Dd {
    /// The leading part.
    pub hi: f64,
    /// The trailing part (below half an ulp of `hi`).
    pub lo: f64,
}

#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

#[inline]
fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl Add for Dd {
    type Output = Dd;
    fn add(self, b: Dd) -> Dd {
        let (s1, s2) = two_sum(self.hi, b.hi);
        let (t1, t2) = two_sum(self.lo, b.lo);
        let r = quick_two_sum(s1, s2 + t1);
        quick_two_sum(r.hi, r.lo + t2)
    }
}
impl Neg for Dd {
    type Output = Dd;
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}
impl Sub for Dd {
    type Output = Dd;
    fn sub(self, b: Dd) -> Dd {
        self + (-b)
    }
}
impl Mul for Dd {
    type Output = Dd;
    fn mul(self, b: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, b.hi);
        quick_two_sum(p, e + (self.hi * b.lo + self.lo * b.hi))
    }
}
impl Div for Dd {
    type Output = Dd;
    fn div(self, b: Dd) -> Dd {
        // Long division with three partial quotients (QD's accurate division).
        let q1 = self.hi / b.hi;
        let r = self - b * Dd::of(q1);
        let q2 = r.hi / b.hi;
        let r = r - b * Dd::of(q2);
        let q3 = r.hi / b.hi;
        quick_two_sum(q1, q2) + Dd::of(q3)
    }
}

const HALF_PI_DD: Dd = Dd {
    hi: std::f64::consts::FRAC_PI_2,
    lo: 6.123233995736766e-17,
};

/// 1 / (2k + 1) for k = 1..=16 in double-double (exact rationals rounded to 106 bits).
const INV_ODD_DD: [Dd; 16] = [
    Dd {
        hi: 0.3333333333333333,
        lo: 1.850371707708594e-17,
    },
    Dd {
        hi: 0.2,
        lo: -1.1102230246251566e-17,
    },
    Dd {
        hi: 0.14285714285714285,
        lo: 7.93016446160826e-18,
    },
    Dd {
        hi: 0.1111111111111111,
        lo: 6.1679056923619804e-18,
    },
    Dd {
        hi: 0.09090909090909091,
        lo: -2.523234146875356e-18,
    },
    Dd {
        hi: 0.07692307692307693,
        lo: -4.270088556250602e-18,
    },
    Dd {
        hi: 0.06666666666666667,
        lo: 9.251858538542971e-19,
    },
    Dd {
        hi: 0.058823529411764705,
        lo: 8.163404592832033e-19,
    },
    Dd {
        hi: 0.05263157894736842,
        lo: 2.921639538487254e-18,
    },
    Dd {
        hi: 0.047619047619047616,
        lo: 2.64338815386942e-18,
    },
    Dd {
        hi: 0.043478260869565216,
        lo: 1.206764157201257e-18,
    },
    Dd {
        hi: 0.04,
        lo: -8.326672684688674e-19,
    },
    Dd {
        hi: 0.037037037037037035,
        lo: 2.05596856412066e-18,
    },
    Dd {
        hi: 0.034482758620689655,
        lo: 4.785444071660157e-19,
    },
    Dd {
        hi: 0.03225806451612903,
        lo: 8.953411488912552e-19,
    },
    Dd {
        hi: 0.030303030303030304,
        lo: -8.410780489584519e-19,
    },
];

impl Real for Dd {
    fn inv_odd(k: usize) -> Self {
        INV_ODD_DD[k - 1]
    }
    fn of(x: f64) -> Self {
        Dd { hi: x, lo: 0.0 }
    }
    fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
    fn sqrt(self) -> Self {
        if self.hi <= 0.0 {
            return Dd::of(0.0);
        }
        // One Newton correction of the f64 root: sqrt(a) = q + (a - q^2) / (2q).
        let q = self.hi.sqrt();
        let (p, e) = two_prod(q, q);
        let r = (self - Dd { hi: p, lo: e }).to_f64();
        quick_two_sum(q, r / (2.0 * q))
    }
    fn atan_parts(self) -> (Self, Self) {
        let mu = self;
        if mu > Dd::of(1.0) {
            let v = Dd::of(1.0) / mu;
            let atan_v = v - reduced_mu_minus_atan(v, 16);
            let at = HALF_PI_DD - atan_v;
            (at, mu - at)
        } else {
            let d = reduced_mu_minus_atan(mu, 16);
            (mu - d, d)
        }
    }
}

/// The shader's arithmetic on the CPU: the same atan polynomial as `shaders/md.wgsl`, so the
/// f32 mirror and the GPU can be compared term by term.
impl Real for f32 {
    #[inline(always)]
    fn of(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn atan_parts(self) -> (Self, Self) {
        crate::physics::f32math::atan_parts_f32(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_double_series_coefficients_are_the_reciprocals() {
        for k in 1..=16 {
            let d = INV_ODD_DD[k - 1] * Dd::of((2 * k + 1) as f64) - Dd::of(1.0);
            assert!(d.to_f64().abs() < 2e-32, "k = {k}: {:e}", d.to_f64());
        }
    }

    #[test]
    fn double_double_arithmetic_has_32_digits() {
        let one = Dd::of(1.0);
        let three = Dd::of(3.0);
        assert!((one / three * three - one).to_f64().abs() < 1e-32);
        let x = Dd::of(538763.6808318263);
        assert!(((x * x) / x - x).to_f64().abs() < 1e-26);
        let s = (one + x * x).sqrt();
        assert!((s * s - (one + x * x)).to_f64().abs() < 1e-20);
        let r = Dd::of(2.0).sqrt();
        assert!((r * r - Dd::of(2.0)).to_f64().abs() < 1e-31);
    }
}
