//! An explicit ensemble's summits stepped on a GPU with f64 shaders (`shaders/ensemble64.wgsl`,
//! the same arithmetic as [`super::add_summit`] with tables): the summits' records and the node
//! tables are uploaded once, every set of separations is summed on the device, and the contact
//! states next to a fold, which the tables leave to the exact solver, are solved here.

use super::{Asperity, Materials, Sums};
use crate::gpu::{Gpu, GpuError, SummitBuffers};
use crate::kernel::layout::SummitRec;
use crate::physics::params::Contact;
use crate::rough::lambda_table::LambdaTables;
use crate::rough::map::{TABLE_INV_H, U_S};
use crate::rough::{RoughError, Summit};
use rayon::prelude::*;
use std::f64::consts::PI;

/// An ensemble held on a GPU.
pub(super) struct OnDevice<'a> {
    gpu: &'a Gpu,
    bufs: SummitBuffers,
    d_min: f64,
    tables: &'a LambdaTables,
}

fn contact(a: &Asperity, m: &Materials) -> Result<Contact, RoughError> {
    Contact::new(a.radius_m, m.e_star_pa, m.work_of_adhesion_j_m2, m.range)
        .map_err(|e| RoughError::Scene(e.to_string().into()))
}

/// A summit's record: its scales, the approaches where it jumps and its place on the tables.
fn record(
    a: &Asperity,
    m: &Materials,
    d_min: f64,
    t: &LambdaTables,
) -> Result<SummitRec, RoughError> {
    let c = contact(a, m)?;
    let s = Summit::new(c.lambda())?;
    let st = t.stencil(s.lambda);
    let unit = c.approach_scale();
    Ok(SummitRec {
        height_m: a.height_m,
        unit,
        force: c.force_scale(),
        radius: c.radius_scale(),
        half_pi_lambda: PI * s.lambda / 2.0,
        h0: s.h0,
        c_star: s.c_star,
        c_end: s.c_end,
        delta_in: s.delta_in,
        delta_out: s.delta_out,
        delta_nc: s.delta_nc.unwrap_or(0.0),
        delta_max: (a.height_m - d_min) / unit,
        w: st.w,
        first: st.first as u32,
        has_nc: s.delta_nc.is_some() as u32,
    })
}

impl<'a> OnDevice<'a> {
    /// The ensemble on `gpu`; None where the device cannot hold it (too many summits for one
    /// binding, no f64): its summits are then stepped on the CPU.
    pub(super) fn new(
        gpu: &'a Gpu,
        asp: &[Asperity],
        m: &Materials,
        d_min: f64,
        t: &'a LambdaTables,
    ) -> Result<Option<OnDevice<'a>>, RoughError> {
        if !gpu.holds_summits(asp.len()) {
            return Ok(None);
        }
        let recs = asp
            .par_iter()
            .map(|a| record(a, m, d_min, t))
            .collect::<Result<Vec<_>, _>>()?;
        let (mut coefs, mut nodes) = (Vec::new(), Vec::new());
        for (l, ar) in t.load.iter().zip(&t.area) {
            let (lo, ao) = (coefs.len(), coefs.len() + l.coef().len());
            coefs.extend_from_slice(l.coef());
            coefs.extend_from_slice(ar.coef());
            nodes.push([lo, l.coef().len(), ao, ar.coef().len()].map(|x| x as u32));
        }
        let grading = (t.exact_below, TABLE_INV_H, 2.0 / U_S);
        match gpu.summit_buffers(&recs, &coefs, &nodes, grading) {
            Ok(bufs) => Ok(Some(OnDevice {
                gpu,
                bufs,
                d_min,
                tables: t,
            })),
            Err(GpuError::TooLarge(_) | GpuError::NoF64(_)) => Ok(None),
            Err(e) => Err(RoughError::Scene(e.to_string().into())),
        }
    }

    /// Every summit's states at `seps` summed (the retract's alone with `retract_only`), as
    /// [`super::sum_summits`] with tables gives them.
    pub(super) fn sums(
        &self,
        asp: &[Asperity],
        m: &Materials,
        seps: &[f64],
        retract_only: bool,
    ) -> Result<Sums, RoughError> {
        let r = match self.gpu.summit_sums(&self.bufs, seps, retract_only) {
            Ok(r) => r,
            // More states next to their folds than the device keeps, or sums larger than it
            // binds: the CPU steps these separations.
            Err(GpuError::TooLarge(_)) => {
                return super::sum_summits(
                    asp,
                    m,
                    seps,
                    self.d_min,
                    Some(self.tables),
                    retract_only,
                )
            }
            Err(e) => return Err(RoughError::Scene(e.to_string().into())),
        };
        let mut sums = Sums { v: r.sums };
        // The flagged states by summit (sorted: the same sums whatever the device's order).
        let mut flagged = r.flagged;
        flagged.sort_unstable();
        let mut groups: Vec<&[[u32; 2]]> = Vec::new();
        let mut rest = &flagged[..];
        while let Some(first) = rest.first() {
            let n = rest.partition_point(|f| f[0] == first[0]);
            groups.push(&rest[..n]);
            rest = &rest[n..];
        }
        let exact = |group: &[[u32; 2]]| -> Result<Vec<(usize, usize, f64, f64)>, RoughError> {
            let a = &asp[group[0][0] as usize];
            let c = contact(a, m)?;
            let s = Summit::new(c.lambda())?;
            let (unit, force, r_unit) = (c.approach_scale(), c.force_scale(), c.radius_scale());
            group
                .iter()
                .map(|&[_, kl]| {
                    let (k, leg) = ((kl & 0x7fff_ffff) as usize, 4 * (kl >> 31) as usize);
                    let d = seps[k];
                    let (p, ar) = s
                        .contact((a.height_m - d) / unit)
                        .ok_or(RoughError::Failed(d, s.lambda))?;
                    Ok((k, leg, p * force, PI * (ar * r_unit).powi(2)))
                })
                .collect()
        };
        let adds = groups
            .par_iter()
            .map(|g| exact(g))
            .collect::<Result<Vec<_>, _>>()?;
        for (k, leg, force, area) in adds.into_iter().flatten() {
            let slot = &mut sums.v[k];
            slot[leg] += force;
            slot[leg + 1] += area;
            slot[leg + 2] += 1.0;
        }
        Ok(sums)
    }
}
