//! The CPU mirror of `shaders/ensemble64.wgsl`: each (chunk of summits, separation) summed in
//! the kernel's order, then the chunks added in order, with the same f64 arithmetic. Read it
//! side by side with the shader.

use crate::kernel::layout::{EnsembleParams, SummitRec};

fn spline_at(coefs: &[[f64; 4]], first: u32, intervals: u32, x: f64) -> f64 {
    let last = intervals - 1;
    let xk = x.min(last as f64).max(0.0);
    let k = xk as u32;
    let s = x - k as f64;
    let c = coefs[(first + k) as usize];
    ((c[3] * s + c[2]) * s + c[1]) * s + c[0]
}

/// The shader's `add_state`: one leg's state (0 approach, 1 retract; branch 0 free, 1
/// non-contact, 2 contact) into `acc`, or a flag.
#[allow(clippy::too_many_arguments)]
fn add_state(
    acc: &mut [f64; 8],
    flags: &mut Vec<[u32; 2]>,
    (s, i, k): (&SummitRec, u32, u32),
    leg: u32,
    delta: f64,
    branch: u32,
    (coefs, nodes, p): (&[[f64; 4]], &[[u32; 4]], &EnsembleParams),
) {
    let o = 4 * leg as usize;
    if branch == 1 {
        let root = (s.c_star * s.c_star + 2.0 * (delta + s.h0)).max(0.0);
        let c = (s.c_star + root.sqrt()).min(s.c_end);
        acc[o] += -(s.half_pi_lambda * c * c) * s.force;
        acc[o + 3] += 1.0;
    } else if branch == 2 {
        let u = (delta - s.delta_out).max(0.0).sqrt();
        let v = 2.0 * u / (1.0 + (1.0 + u * p.two_over_us).sqrt());
        if v < p.exact_below {
            flags.push([i, k | (leg << 31)]);
            return;
        }
        let x = v * p.inv_h;
        let (mut load, mut area) = (0.0, 0.0);
        for j in 0..4 {
            let n = nodes[(s.first + j as u32) as usize];
            load += s.w[j] * spline_at(coefs, n[0], n[1], x);
            area += s.w[j] * spline_at(coefs, n[2], n[3], x);
        }
        let ar = area * s.radius;
        acc[o] += load * s.force;
        acc[o + 1] += (std::f64::consts::PI * ar) * ar;
        acc[o + 2] += 1.0;
    }
}

/// The kernel's sums at `seps` (per separation: the approach's force, area, contacts and
/// non-contacts, then the retract's) and its flagged states, for the parameters `p` it ran with.
pub fn sums(
    recs: &[SummitRec],
    coefs: &[[f64; 4]],
    nodes: &[[u32; 4]],
    p: &EnsembleParams,
    seps: &[f64],
) -> (Vec<[f64; 8]>, Vec<[u32; 2]>) {
    let (ns, chunks) = (p.seps as usize, p.chunks as usize);
    let mut partials = vec![[0.0; 8]; chunks * ns];
    let mut flags = Vec::new();
    for c in 0..chunks {
        for (k, &d) in seps.iter().enumerate() {
            let acc = &mut partials[c * ns + k];
            let end = ((c + 1) * p.chunk as usize).min(p.summits as usize);
            for i in c * p.chunk as usize..end {
                let s = &recs[i];
                let delta = (s.height_m - d) / s.unit;
                let at = (s, i as u32, k as u32);
                let tables = (coefs, nodes, p);
                if p.retract_only == 0 {
                    let b = if delta >= s.delta_in {
                        2
                    } else if delta >= -s.h0 {
                        1
                    } else {
                        0
                    };
                    add_state(acc, &mut flags, at, 0, delta, b, tables);
                }
                let r = if s.delta_max >= s.delta_in && delta >= s.delta_out {
                    2
                } else if s.has_nc == 1 && s.delta_max >= -s.h0 && delta >= s.delta_nc {
                    1
                } else {
                    0
                };
                add_state(acc, &mut flags, at, 1, delta, r, tables);
            }
        }
    }
    let sums = (0..ns)
        .map(|k| {
            let mut t = [0.0; 8];
            for (q, tq) in t.iter_mut().enumerate() {
                for c in 0..chunks {
                    *tq += partials[c * ns + k][q];
                }
            }
            t
        })
        .collect();
    (sums, flags)
}
