//! Gauss-Legendre quadrature on [0, 1].

use std::f64::consts::PI;

/// The order of a rule's nodes on [0, 1]: both come from the roots x of P_n found largest
/// first, mapped by `(1 + x) / 2` or by `(1 - x) / 2`. A caller keeps the order its sums were
/// written in (the sums round differently in the other).
#[derive(Clone, Copy, Debug)]
pub enum Order {
    /// `(1 + x) / 2`: from the node next to 1 down.
    FromOne,
    /// `(1 - x) / 2`: from the node next to 0 up.
    FromZero,
}

/// The `n`-point Gauss-Legendre rule on [0, 1] as (node, weight) pairs: each root of P_n by
/// Newton's method from a Chebyshev-like first guess.
pub fn gauss_legendre(n: usize, order: Order) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    (p0, p1) = (p1, p2);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            // Half the weight on [-1, 1], 2 / ((1 - x^2) P_n'(x)^2).
            let w = 1.0 / ((1.0 - x * x) * dp * dp);
            match order {
                Order::FromOne => (0.5 * (1.0 + x), w),
                Order::FromZero => (0.5 * (1.0 - x), w),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_orders_integrate_polynomials_exactly() {
        for order in [Order::FromOne, Order::FromZero] {
            for n in [5, 20, 96] {
                let rule = gauss_legendre(n, order);
                let sum: f64 = rule.iter().map(|&(x, w)| w * x.powi(9)).sum();
                assert!((sum - 0.1).abs() < 1e-15, "{n}: {sum}");
                let weights: f64 = rule.iter().map(|&(_, w)| w).sum();
                assert!((weights - 1.0).abs() < 1e-14, "{n}: {weights}");
            }
        }
        let (up, down) = (
            gauss_legendre(20, Order::FromZero),
            gauss_legendre(20, Order::FromOne),
        );
        assert!(up[0].0 < 0.01 && down[0].0 > 0.99);
    }
}
