//! tabor: adhesive contact of elastic spheres. Exact Maugis-Dugdale (MD) states, pull-offs,
//! curves, adhesion maps (Johnson & Greenwood 1997), scenes in SI units, approach-retract cycles
//! and the pressure and gap inside the contact; the f64 solver on all cores, or the f32 WGSL
//! kernels on a GPU through [`engine::Engine`] with a cross-check.
//!
//! Units are Johnson & Greenwood's (`docs/PHYSICS.md`): lambda the Maugis parameter, load
//! `Pbar = P / (pi w R)`, approach `Dbar`, contact radius `A`. Every quantity has a domain
//! ([`physics::domain`]); outside it a state is `invalid_input`, never a number.
//!
//! # Layers
//!
//! Each uses only those before it in this list (`tests/suite/architecture.rs` checks it): [`numeric`]
//! (root finding, golden section, Gauss-Legendre) -> [`physics`] (normalisation, domain, closed
//! forms, the MD curve, fields, number types) -> [`solver`] (f64 contexts, batches, curves) ->
//! [`kernel`] (wgpu-free: the byte layout shared with WGSL, the per-lambda preparation, the CPU
//! mirror of each shader) -> [`gpu`] (device, pipelines, dispatch) -> [`engine`] (backend
//! choice, cross-check) -> [`io`], [`interrupt`] -> [`map`], [`scene`], [`mod@cycle`],
//! [`mod@profile`], [`fit`], [`rough`], [`dem`] -> [`render`] (feature `render`), [`export`] ->
//! the command line (feature `cli`). Without default features (`cargo build --lib
//! --no-default-features`) the crate is the solver, kernels, GPU host, maps, scenes, cycles,
//! profiles and fits, without the renderer or the terminal.
//!
//! The crate root re-exports what most users need ([`solve_one`], [`LambdaContext`],
//! [`Engine`], [`MapSpec`], [`solve_scene`], [`fit_curve`], [`Rough`], ...); the modules hold
//! the rest.
//!
//! # Examples
//!
//! A state at a load, and one at an approach, on the exact solver:
//!
//! ```
//! use tabor::solver::{solve_one, Control, Status};
//! let s = solve_one(1.0, 0.5, Control::Load);
//! assert_eq!(s.status, Status::Ok);
//! assert!((s.a - 1.7289400402050878).abs() < 1e-14);
//! let d = solve_one(1.0, s.approach, Control::Displacement);
//! assert!((d.a / s.a - 1.0).abs() < 1e-12);
//! // Beyond the exact solver's lambda range (1e-26..1e26) the certified closed-form limit,
//! // named by `domain::method`; outside every method a status, not a number.
//! let j = solve_one(1e30, 0.0, Control::Load);
//! assert!((j.a - 6f64.cbrt()).abs() < 1e-15);
//! assert_eq!(tabor::physics::domain::method_name(1e30), "jkr_limit");
//! assert_eq!(solve_one(1e-301, 1.0, Control::Load).status, Status::InvalidInput);
//! ```
//!
//! Pull-offs under both controls, and the whole curve of one lambda:
//!
//! ```
//! let c = tabor::solver::LambdaContext::new(10.0).unwrap();
//! assert!((c.load_pulloff.load + 1.501624860426358).abs() < 1e-12);
//! assert!(c.disp_pulloff().load > c.load_pulloff.load); // rigid grips hold on less
//! let curve = tabor::solver::curve::curve(1.0, 4.0, 5).unwrap();
//! assert_eq!(curve.points.last().unwrap().a, 0.0); // it ends at the A = 0 end
//! ```
//!
//! An adhesion map as arrays, on the CPU (or `Engine::select(Backend::Auto, None)` for a GPU):
//!
//! ```
//! use tabor::engine::Engine;
//! use tabor::map::{compute, LoadAxis, MapSpec, Region};
//! let spec = MapSpec {
//!     lambda_min: 1e-3, lambda_max: 1e3, nx: 32,
//!     load_axis: LoadAxis::Log, load_min: 1e-3, load_max: 1e3, ny: 16,
//!     tolerance: 0.05, strength_ratios: vec![],
//! };
//! let m = compute(&spec, &Engine::Cpu).unwrap();
//! // Small lambda at the largest load: Hertz; row-major, row 0 the smallest load.
//! assert_eq!(m.region_at(0, 15), Region::Hertz);
//! assert_eq!(m.len(), 32 * 16);
//! ```
//!
//! A real contact in SI units, and the work of adhesion from a pull-off force:
//!
//! ```
//! let r = tabor::scene::solve_scene(&tabor::scene::preset("afm-si").unwrap()).unwrap();
//! assert!(r.lambda > 0.1 && r.lambda < 0.12);
//! let inf = tabor::scene::infer(12.2e-9, 20e-9, 91e9, 0.3e-9).unwrap();
//! assert!(inf.w_dmt_j_m2 < inf.w_md_j_m2.unwrap() && inf.w_md_j_m2.unwrap() < inf.w_jkr_j_m2);
//! ```
//!
//! An approach-retract cycle under rigid grips, and the pressure inside a contact:
//!
//! ```
//! use tabor::cycle::{cycle, Drive};
//! let c = cycle(1.0, Drive::RigidGrips, 2.0).unwrap();
//! assert!((c.hysteresis.unwrap() - 0.4963).abs() < 2e-3);
//! let p = tabor::profile::profile(1.0, tabor::profile::Given::Load(0.0), 100).unwrap();
//! let md = &p.models[0];
//! assert!((md.energy_release_rate_over_w.unwrap() - 1.0).abs() < 1e-12); // J = w
//! ```
//!
//! An AFM force curve fitted by exact MD (here a synthetic one, 20 nm tip, 40 N/m), with its
//! 95% profile-likelihood interval and the simplest adequate model:
//!
//! ```
//! use tabor::fit::{fit_curve, synthetic::{map_curve, synthetic}, FitOptions, FitStatus};
//! let curve = synthetic(&map_curve(0, 1, 300, 40.0, 2e-11)); // E* = 2 GPa, w = 0.04 J/m^2
//! let opt = FitOptions { radius: 20e-9, spring: 40.0, ..FitOptions::default() };
//! let f = fit_curve(&curve, &opt);
//! assert_eq!(f.status, FitStatus::Ok);
//! let [lo, hi] = f.work_of_adhesion_j_m2_interval_95.unwrap();
//! assert!(lo.unwrap() < 0.04 && 0.04 < hi.unwrap());
//! assert!((f.e_star_pa.unwrap() / 2e9 - 1.0).abs() < 1e-2);
//! ```
//!
//! A rough surface of Greenwood-Williamson MD summits (lambda 2, heights of standard deviation
//! 0.5 approach units), pressed to -1 and retracted: its pull-off per summit against a smooth
//! summit's (`tabor rough --lambda 2 --sigma 0.5 --min-separation -1`):
//!
//! ```
//! let r = tabor::Rough::new(2.0, 0.5).unwrap();
//! let (_separation, pulloff) = r.pulloff_after(-1.0, 48).unwrap();
//! assert!((pulloff + 1.2081).abs() < 1e-4);
//! assert!(pulloff > r.summit.smooth_pulloff()); // roughness lowers the pull-off
//! ```

// `!(x <= tol)` and the like are deliberate: a NaN must land on the failure side.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Every public item is documented.
#![warn(missing_docs)]

// Messages on stderr that never panic: std's `eprintln!` panics when stderr is a closed pipe
// (`tabor ... 2>&1 | head -1`). Like stdout, a message nobody can read is dropped. Defined
// before the modules so that every `eprintln!`/`eprint!` in the crate is this one.
macro_rules! eprintln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}
#[allow(unused_macros)]
macro_rules! eprint {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($t)*);
    }};
}

// The speed-against-accuracy workload of `tabor bench` and the data behind the gallery's line
// figures: public for the command line's and the tests' use, not part of the library's API.
#[doc(hidden)]
pub mod bench;
#[cfg(feature = "cli")]
pub mod cli;
pub mod cycle;
pub mod dem;
pub mod engine;
pub mod error;
pub mod export;
#[doc(hidden)]
pub mod figure_data;
pub mod fit;
pub mod gpu;
pub mod interrupt;
pub mod io;
// The WGSL kernels' sources, buffer layouts and CPU mirrors: documented, as `gpu` takes and
// returns their types; most users solve through `engine`, `map` or `solver`.
pub mod kernel;
pub mod law;
pub mod map;
pub mod numeric;
pub mod physics;
pub mod profile;
pub(crate) mod progress;
#[cfg(feature = "render")]
pub mod render;
pub mod rough;
pub mod scene;
pub mod solver;

// What a user of the library needs most, at the crate root; the modules hold the rest.
pub use cycle::{cycle, Cycle, CycleSpec, Drive};
pub use engine::{Backend, Engine, Precision};
pub use fit::{fit_curve, Curve, CurveFit, FitOptions};
pub use law::ContactLaw;
pub use map::{compute as compute_map, MapData, MapSpec, Region};
pub use physics::model::ContactModel;
pub use physics::params::{Contact, ForceRange};
pub use profile::{profile, Given, Profile};
pub use rough::ensemble::{Asperity, EnsembleCycle, EnsembleSpec, SummitSolver};
pub use rough::map::{RoughMap, RoughMapSpec};
pub use rough::{Rough, RoughCycle, Summit};
pub use scene::{infer, preset, solve_scene, SceneInput, SceneResult};
pub use solver::{solve_one, Control, LambdaContext, State, Status};
