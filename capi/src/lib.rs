//! The C ABI of tabor's Maugis-Dugdale force-overlap law for particle (DEM) codes
//! ([`tabor::dem`]), dry or with a water meniscus: build a law for a pair of materials, evaluate
//! it per contact with that contact's history byte, free it. The header is `capi/include/tabor_dem.h`, generated from this
//! file by cbindgen (`cargo run -p tabor-capi-header`, which `cargo test -p tabor-capi-header`
//! checks).
//!
//! Every function takes null pointers and bad values without undefined behaviour: it returns an
//! error code (or a null law) and, where it can, a message. No panic crosses the boundary.

use std::ffi::c_char;

use tabor::dem::{Branch, Pair};
use tabor::physics::params::{effective_radius, reduced_modulus, Body, Contact, ForceRange};
use tabor::scene::humidity::HumidityInput;

/// History byte of a new contact, and branch code: apart, out of the force's reach. A history
/// byte names the stretch of the law's path a contact is on (the law's own numbering, 0 free);
/// `tabor_dem_law_branch` gives its kind.
pub const TABOR_DEM_FREE: u8 = 0;
/// Branch code: joined across a gap by a cohesive zone (the solid's, or the meniscus) alone.
pub const TABOR_DEM_NON_CONTACT: u8 = 1;
/// Branch code: in contact.
pub const TABOR_DEM_CONTACT: u8 = 2;

/// The version of this interface: 2 since a pair may have a meniscus and a history byte is the
/// law's stretch (1: a dry pair, history bytes 0, 1, 2 the branches).
pub const TABOR_DEM_ABI_VERSION: u32 = 2;

/// Return code: the force and stiffness were written.
pub const TABOR_DEM_OK: i32 = 0;
/// Return code: written, but the overlap lies beyond the table (the last cubic extrapolated):
/// build the law with a larger `overlap_max_m`.
pub const TABOR_DEM_BEYOND_TABLE: i32 = 1;
/// Return code: nothing written: a null pointer, an overlap that is not a finite number, or a
/// history byte that is not one of the law's.
pub const TABOR_DEM_INVALID: i32 = -1;

/// A pair of elastic bodies with adhesion, in SI units.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct TaborDemPair {
    /// Young's modulus of body 1 (Pa).
    pub youngs_modulus1_pa: f64,
    /// Poisson's ratio of body 1.
    pub poisson_ratio1: f64,
    /// Radius of body 1 (m).
    pub radius1_m: f64,
    /// Young's modulus of body 2 (Pa).
    pub youngs_modulus2_pa: f64,
    /// Poisson's ratio of body 2.
    pub poisson_ratio2: f64,
    /// Radius of body 2 (m); 0 for a flat wall.
    pub radius2_m: f64,
    /// The work of adhesion w (J/m^2): twice the surface energy of LAMMPS's `jkr` gamma for like
    /// bodies.
    pub work_of_adhesion_j_m2: f64,
    /// The Dugdale stress s0 (Pa); 0 to give the Lennard-Jones range instead.
    pub dugdale_stress_pa: f64,
    /// The Lennard-Jones equilibrium spacing z0 (m), used where `dugdale_stress_pa` is 0
    /// (s0 = 16 w / (9 sqrt(3) z0)).
    pub lj_range_m: f64,
    /// The largest overlap the table covers (m); beyond it an evaluation says so.
    pub overlap_max_m: f64,
    /// The relative humidity (0..1) of the air around the pair: above 0, a water meniscus (the
    /// Kelvin equation, water at 25 C) joins the solid's adhesion; 0 for a dry pair.
    pub relative_humidity: f64,
    /// Water's contact angle on the bodies (degrees, below 90 for a meniscus); used where
    /// `relative_humidity` is above 0.
    pub contact_angle_deg: f64,
}

/// What a law is: its Maugis parameter, its jumps and folds, its scales and its table.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TaborDemInfo {
    /// The Maugis parameter lambda.
    pub lambda: f64,
    /// The effective radius R* (m).
    pub radius_m: f64,
    /// The reduced modulus E* (Pa).
    pub reduced_modulus_pa: f64,
    /// The overlap where the attraction starts on the approach (m, negative: a gap of h0, or the
    /// meniscus's height).
    pub attraction_from_m: f64,
    /// The overlap where the approach enters contact (m).
    pub jump_in_m: f64,
    /// The overlap below which the retract leaves contact (the fold under rigid grips, m).
    pub jump_out_m: f64,
    /// The force there (N).
    pub jump_out_force_n: f64,
    /// Where the retract, after leaving contact across the gap, comes free (m); NaN where it
    /// comes free at the jump-out (dry, lambda above about 0.938).
    pub non_contact_end_m: f64,
    /// The pull-off force under load control (N, negative).
    pub pulloff_force_n: f64,
    /// The energy lost per slow cycle reaching contact (J).
    pub loop_energy_j: f64,
    /// The table's largest measured error, relative to max(|pull-off|, |force|).
    pub table_error: f64,
    /// The largest overlap of the table (m).
    pub overlap_max_m: f64,
    /// The meniscus's work of adhesion, 2 gamma cos(theta) (J/m^2); 0 for a dry pair (forces
    /// and energies above include it).
    pub meniscus_work_j_m2: f64,
    /// The meniscus's height, the largest gap it bridges (m); 0 for a dry pair.
    pub meniscus_range_m: f64,
    /// The number of history values: every history byte of this law is below it.
    pub histories: u32,
}

/// A law for one pair of materials (opaque).
pub struct TaborDemLaw {
    pair: Pair,
    info: TaborDemInfo,
}

fn contact_of(p: &TaborDemPair) -> Result<Contact, String> {
    let b1 = Body {
        youngs_modulus_pa: p.youngs_modulus1_pa,
        poisson_ratio: p.poisson_ratio1,
        radius_m: Some(p.radius1_m),
    };
    let b2 = Body {
        youngs_modulus_pa: p.youngs_modulus2_pa,
        poisson_ratio: p.poisson_ratio2,
        radius_m: (p.radius2_m != 0.0).then_some(p.radius2_m),
    };
    let e = reduced_modulus(&b1, &b2).map_err(|e| e.to_string())?;
    let r = effective_radius(&b1, &b2).map_err(|e| e.to_string())?;
    let range = if p.dugdale_stress_pa != 0.0 {
        ForceRange::DugdaleStress(p.dugdale_stress_pa)
    } else {
        ForceRange::LennardJones(p.lj_range_m)
    };
    Contact::new(r, e, p.work_of_adhesion_j_m2, range).map_err(|e| e.to_string())
}

fn build(p: &TaborDemPair) -> Result<TaborDemLaw, String> {
    let contact = contact_of(p)?;
    let meniscus = if p.relative_humidity == 0.0 {
        None
    } else {
        HumidityInput::water(p.relative_humidity, p.contact_angle_deg)
            .meniscus(&contact)
            .map_err(|e| e.to_string())?
    };
    let pair =
        Pair::with_meniscus(contact, meniscus, Some(p.overlap_max_m)).map_err(|e| e.to_string())?;
    let (f, l) = (pair.force_scale, pair.length_scale);
    let law = &pair.law;
    let info = TaborDemInfo {
        lambda: law.lambda,
        radius_m: pair.contact.radius,
        reduced_modulus_pa: pair.contact.e_star,
        attraction_from_m: law.attraction_from * l,
        jump_in_m: law.delta_in * l,
        jump_out_m: law.delta_out * l,
        jump_out_force_n: law.disp_pulloff * f,
        non_contact_end_m: law.delta_nc.map_or(f64::NAN, |d| d * l),
        pulloff_force_n: law.load_pulloff * f,
        loop_energy_j: pair.loop_energy_j(p.overlap_max_m).unwrap_or(f64::NAN),
        table_error: law.error,
        overlap_max_m: law.overlap_max * l,
        meniscus_work_j_m2: meniscus.map_or(0.0, |m| m.work_of_adhesion_j_m2),
        meniscus_range_m: meniscus.map_or(0.0, |m| m.range_m),
        histories: law.stretch_count() as u32,
    };
    Ok(TaborDemLaw { pair, info })
}

/// Writes `msg` into `buf` (at most `len` bytes with the terminating zero).
fn write_message(msg: &str, buf: *mut c_char, len: usize) {
    if buf.is_null() || len == 0 {
        return;
    }
    let n = msg.len().min(len - 1);
    // SAFETY: the caller gives a buffer of `len` bytes; n + 1 <= len.
    unsafe {
        std::ptr::copy_nonoverlapping(msg.as_ptr().cast::<c_char>(), buf, n);
        *buf.add(n) = 0;
    }
}

/// Builds the law of a pair (tabulating every stretch of its path: about half a millisecond
/// dry, half a second with a meniscus). Returns NULL where the pair is refused or the table
/// misses its 1e-6 target, with the reason in `error` (`error_len` bytes, may be NULL).
///
/// # Safety
/// `pair` is NULL or points to a `TaborDemPair`; `error` is NULL or points to `error_len`
/// writable bytes.
#[no_mangle]
pub unsafe extern "C" fn tabor_dem_law_new(
    pair: *const TaborDemPair,
    error: *mut c_char,
    error_len: usize,
) -> *mut TaborDemLaw {
    if pair.is_null() {
        write_message("tabor_dem_law_new: pair is NULL", error, error_len);
        return std::ptr::null_mut();
    }
    // SAFETY: non-null, and the caller promises a TaborDemPair.
    let p = unsafe { *pair };
    match std::panic::catch_unwind(|| build(&p)) {
        Ok(Ok(law)) => Box::into_raw(Box::new(law)),
        Ok(Err(msg)) => {
            write_message(&msg, error, error_len);
            std::ptr::null_mut()
        }
        Err(_) => {
            write_message("tabor_dem_law_new: internal error", error, error_len);
            std::ptr::null_mut()
        }
    }
}

/// The force (N, positive repulsive) and the stiffness dF/d(overlap) (N/m) at `overlap_m` (m,
/// positive interpenetrating) for a contact whose history byte is `*history` (updated: start a
/// new contact with `TABOR_DEM_FREE`). Returns `TABOR_DEM_OK`, `TABOR_DEM_BEYOND_TABLE`
/// (written, extrapolated) or `TABOR_DEM_INVALID` (nothing written). The stiffness is infinite
/// at a fold itself, where the branch is vertical (the jump out of contact above lambda 0.94),
/// and large next to one; where a branch ends without a fold it is its finite slope. No
/// allocation; safe from any number of threads on one law.
///
/// # Safety
/// `law` is NULL or a law from `tabor_dem_law_new` not yet freed; the other pointers are NULL or
/// point to writable values of their types.
#[no_mangle]
pub unsafe extern "C" fn tabor_dem_law_eval(
    law: *const TaborDemLaw,
    overlap_m: f64,
    history: *mut u8,
    force_n: *mut f64,
    stiffness_n_m: *mut f64,
) -> i32 {
    if law.is_null() || history.is_null() || force_n.is_null() || stiffness_n_m.is_null() {
        return TABOR_DEM_INVALID;
    }
    // SAFETY: non-null and valid by the caller's promise.
    let (law, h) = unsafe { (&*law, &mut *history) };
    let Some(mut hist) = law.pair.law.history(*h) else {
        return TABOR_DEM_INVALID;
    };
    if !overlap_m.is_finite() {
        return TABOR_DEM_INVALID;
    }
    let e = law.pair.eval(overlap_m, &mut hist);
    *h = hist.code();
    // SAFETY: as above.
    unsafe {
        *force_n = e.force_n;
        *stiffness_n_m = e.stiffness_n_m;
    }
    if e.beyond_table {
        TABOR_DEM_BEYOND_TABLE
    } else {
        TABOR_DEM_OK
    }
}

/// The branch a history byte is on: `TABOR_DEM_FREE`, `TABOR_DEM_NON_CONTACT` or
/// `TABOR_DEM_CONTACT`; `TABOR_DEM_INVALID` for a NULL law or a byte that is no history of it.
///
/// # Safety
/// `law` is NULL or a live law.
#[no_mangle]
pub unsafe extern "C" fn tabor_dem_law_branch(law: *const TaborDemLaw, history: u8) -> i32 {
    if law.is_null() {
        return TABOR_DEM_INVALID;
    }
    // SAFETY: non-null and valid by the caller's promise.
    let law = unsafe { &*law };
    match law
        .pair
        .law
        .history(history)
        .map(|h| law.pair.law.branch(h))
    {
        Some(Branch::Free) => TABOR_DEM_FREE as i32,
        Some(Branch::NonContact) => TABOR_DEM_NON_CONTACT as i32,
        Some(Branch::Contact) => TABOR_DEM_CONTACT as i32,
        None => TABOR_DEM_INVALID,
    }
}

/// Copies the law's description into `*info`. Returns `TABOR_DEM_OK` or `TABOR_DEM_INVALID`.
///
/// # Safety
/// `law` is NULL or a live law; `info` is NULL or points to a writable `TaborDemInfo`.
#[no_mangle]
pub unsafe extern "C" fn tabor_dem_law_info(
    law: *const TaborDemLaw,
    info: *mut TaborDemInfo,
) -> i32 {
    if law.is_null() || info.is_null() {
        return TABOR_DEM_INVALID;
    }
    // SAFETY: non-null and valid by the caller's promise.
    unsafe { *info = (*law).info };
    TABOR_DEM_OK
}

/// The energy lost (J) in one slow cycle from apart to `overlap_max_m` and back: the area of the
/// force-overlap loop. NaN for a NULL law or where it could not be computed.
///
/// # Safety
/// `law` is NULL or a live law.
#[no_mangle]
pub unsafe extern "C" fn tabor_dem_law_loop_energy(
    law: *const TaborDemLaw,
    overlap_max_m: f64,
) -> f64 {
    if law.is_null() || overlap_max_m.is_nan() {
        return f64::NAN;
    }
    // SAFETY: non-null and valid by the caller's promise.
    let law = unsafe { &*law };
    std::panic::catch_unwind(|| law.pair.loop_energy_j(overlap_max_m))
        .ok()
        .flatten()
        .unwrap_or(f64::NAN)
}

/// Frees a law (NULL is ignored).
///
/// # Safety
/// `law` is NULL or a law from `tabor_dem_law_new`, freed once.
#[no_mangle]
pub unsafe extern "C" fn tabor_dem_law_free(law: *mut TaborDemLaw) {
    if !law.is_null() {
        // SAFETY: from Box::into_raw in tabor_dem_law_new, freed once by the caller's promise.
        drop(unsafe { Box::from_raw(law) });
    }
}
