//! Every WGSL shader is parsed and validated with naga at build time, as vello does, so a broken
//! shader fails the build on a machine without a GPU (tests/shaders.rs also checks the struct
//! layouts against the Rust side). The shaders are validated as the host builds them: after the
//! prelude of constants that `src/kernel/prelude.rs` generates from `src/physics/tolerances.rs`.

use naga::valid::{Capabilities, ValidationFlags, Validator};

/// The constants the host gives the shaders and their prelude (the same files the crate
/// compiles, at the same paths).
#[allow(dead_code)]
mod physics {
    pub mod tolerances {
        include!("src/physics/tolerances.rs");
    }
}
mod kernel {
    pub mod prelude {
        include!("src/kernel/prelude.rs");
    }
}

fn validate(name: &str, src: &str, caps: Capabilities) {
    let module = naga::front::wgsl::parse_str(src)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(src)));
    if let Err(e) = Validator::new(ValidationFlags::all(), caps).validate(&module) {
        panic!("{name}: {}", e.emit_to_string(src));
    }
}

fn main() {
    for f in [
        "shaders/md.wgsl",
        "shaders/solve.wgsl",
        "shaders/curve64.wgsl",
        "shaders/polish64.wgsl",
        "shaders/classify.wgsl",
        "shaders/ensemble64.wgsl",
        "src/physics/tolerances.rs",
        "src/kernel/prelude.rs",
    ] {
        println!("cargo:rerun-if-changed={f}");
    }
    let read = |f: &str| std::fs::read_to_string(f).unwrap_or_else(|e| panic!("{f}: {e}"));
    let prelude = kernel::prelude::wgsl_prelude();
    // The f32 kernels are one module: the shared functions, then the entry points.
    let md = prelude.clone() + &read("shaders/md.wgsl") + "\n" + &read("shaders/solve.wgsl");
    validate(
        "shaders/md.wgsl + shaders/solve.wgsl",
        &md,
        Capabilities::default(),
    );
    // A map's classification on the device.
    let classify = prelude.clone() + &read("shaders/classify.wgsl");
    validate("shaders/classify.wgsl", &classify, Capabilities::FLOAT64);
    // An explicit ensemble's stepping, in f64.
    let ensemble = prelude.clone() + &read("shaders/ensemble64.wgsl");
    validate("shaders/ensemble64.wgsl", &ensemble, Capabilities::FLOAT64);
    // The f64 refinement: the f64 curve point, then its entry point.
    let polish64 = prelude + &read("shaders/curve64.wgsl") + "\n" + &read("shaders/polish64.wgsl");
    validate(
        "shaders/curve64.wgsl + shaders/polish64.wgsl",
        &polish64,
        Capabilities::FLOAT64,
    );
}
