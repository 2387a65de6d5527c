//! Golden-section search for a minimum. One iteration for every caller; the stop rule, the tie
//! rule and the iteration limit are parameters because each caller's numbers were tuned with
//! its own (and must not change).

/// When the search's bracket `[a, b]` is narrow enough (tested before each step).
#[derive(Clone, Copy, Debug)]
pub enum Width {
    /// `b - a < tol`.
    Absolute(f64),
    /// `b - a <= tol (1 + max(|a|, |b|))`.
    Relative(f64),
}

/// Which inner probe a tie of their values keeps (and which one is the best at the end).
#[derive(Clone, Copy, Debug)]
pub enum Ties {
    /// The left probe: the bracket shrinks from the right while `f(left) <= f(right)`.
    Left,
    /// The right probe: the bracket shrinks from the right only while `f(left) < f(right)`.
    Right,
}

/// The rules of a golden-section search.
#[derive(Clone, Copy, Debug)]
pub struct Golden {
    /// The stop rule.
    pub width: Width,
    /// The tie rule.
    pub ties: Ties,
    /// The most steps (each one evaluation).
    pub max_iter: usize,
}

/// The two inner probes `(x, f(x))` where a search stopped, left first.
#[derive(Clone, Copy, Debug)]
pub struct Probes {
    /// The left probe.
    pub left: (f64, f64),
    /// The right probe.
    pub right: (f64, f64),
    ties: Ties,
}

impl Probes {
    /// The probe with the lesser value (a tie by the search's rule).
    pub fn best(&self) -> (f64, f64) {
        if keeps_left(self.ties, self.left.1, self.right.1) {
            self.left
        } else {
            self.right
        }
    }
}

fn keeps_left(ties: Ties, f_left: f64, f_right: f64) -> bool {
    match ties {
        Ties::Left => f_left <= f_right,
        Ties::Right => f_left < f_right,
    }
}

impl Golden {
    /// Searches `[a, b]` for a minimum of `f`; the first error of `f` ends the search.
    pub fn search<E>(
        &self,
        mut f: impl FnMut(f64) -> Result<f64, E>,
        mut a: f64,
        mut b: f64,
    ) -> Result<Probes, E> {
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut c, mut e) = (b - g * (b - a), a + g * (b - a));
        let (mut fc, mut fe) = (f(c)?, f(e)?);
        for _ in 0..self.max_iter {
            let narrow = match self.width {
                Width::Absolute(tol) => b - a < tol,
                Width::Relative(tol) => (b - a) <= tol * (1.0 + a.abs().max(b.abs())),
            };
            if narrow {
                break;
            }
            if keeps_left(self.ties, fc, fe) {
                (b, e, fe) = (e, c, fc);
                c = b - g * (b - a);
                fc = f(c)?;
            } else {
                (a, c, fc) = (c, e, fe);
                e = a + g * (b - a);
                fe = f(e)?;
            }
        }
        Ok(Probes {
            left: (c, fc),
            right: (e, fe),
            ties: self.ties,
        })
    }

    /// The argument of the minimum of `f` on `[a, b]`.
    pub fn argmin(&self, mut f: impl FnMut(f64) -> f64, a: f64, b: f64) -> f64 {
        match self.search(|x| Ok::<f64, std::convert::Infallible>(f(x)), a, b) {
            Ok(p) => p.best().0,
            Err(never) => match never {},
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_parabolas_vertex_under_both_rules() {
        let f = |x: f64| (x - 0.3) * (x - 0.3) + 1.0;
        for width in [Width::Absolute(1e-13), Width::Relative(1e-15)] {
            for ties in [Ties::Left, Ties::Right] {
                let rule = Golden {
                    width,
                    ties,
                    max_iter: 200,
                };
                assert!((rule.argmin(f, -1.0, 2.0) - 0.3).abs() < 1e-7);
            }
        }
    }

    #[test]
    fn an_error_ends_the_search() {
        let rule = Golden {
            width: Width::Relative(1e-15),
            ties: Ties::Right,
            max_iter: 200,
        };
        let mut calls = 0;
        let r = rule.search(
            |x| {
                calls += 1;
                if calls > 5 {
                    Err("stop")
                } else {
                    Ok(x * x)
                }
            },
            -1.0,
            1.0,
        );
        assert_eq!(r.unwrap_err(), "stop");
        assert_eq!(calls, 6);
    }
}
