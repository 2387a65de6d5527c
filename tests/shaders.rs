//! Every shader parses and validates with naga (no GPU needed), and the Rust structs match the
//! WGSL layouts byte for byte.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use tabor::gpu::layout::{Branch, GpuLambda, Lambda64, Out, Out64, Params, Point64};

fn parse(src: &str) -> naga::Module {
    naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{}", e.emit_to_string(src)))
}

fn module() -> naga::Module {
    parse(&tabor::gpu::shader_source())
}

/// The size naga lays out for the WGSL struct `name` of `m`.
fn wgsl_size(m: &naga::Module, name: &str) -> usize {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(m.to_ctx()).unwrap();
    let (h, _) = m
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"));
    layouter[h].size as usize
}

#[test]
fn shaders_parse_and_validate() {
    let m = module();
    Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&m)
        .unwrap_or_else(|e| panic!("{e:?}"));
    let entries: Vec<_> = m.entry_points.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(entries, ["grid", "points", "probe"]);
}

#[test]
fn rust_structs_match_wgsl_layout() {
    let m = module();
    let size_of = |name: &str| wgsl_size(&m, name);
    assert_eq!(size_of("Branch"), std::mem::size_of::<Branch>());
    assert_eq!(size_of("Lambda"), std::mem::size_of::<GpuLambda>());
    assert_eq!(size_of("Params"), std::mem::size_of::<Params>());
    assert_eq!(size_of("Out"), std::mem::size_of::<Out>());
    // Member offsets of the nested branches.
    let (_, lam) = m
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Lambda"))
        .unwrap();
    if let naga::TypeInner::Struct { members, .. } = &lam.inner {
        let off = |n: &str| {
            members
                .iter()
                .find(|mm| mm.name.as_deref() == Some(n))
                .unwrap()
                .offset as usize
        };
        assert_eq!(off("load"), std::mem::offset_of!(GpuLambda, load));
        assert_eq!(off("disp"), std::mem::offset_of!(GpuLambda, disp));
        assert_eq!(off("end_load"), std::mem::offset_of!(GpuLambda, end_load));
    } else {
        panic!("Lambda is not a struct");
    }
}

/// The f64 refinement is its own module; it validates with the FLOAT64 capability, and its
/// structs match the Rust ones.
#[test]
fn f64_module_validates_and_matches_rust_layout() {
    let m = parse(include_str!("../shaders/polish64.wgsl"));
    Validator::new(ValidationFlags::all(), Capabilities::FLOAT64)
        .validate(&m)
        .unwrap_or_else(|e| panic!("{e:?}"));
    // Without FLOAT64 it must not validate: it could not be part of the f32 module.
    assert!(
        Validator::new(ValidationFlags::all(), Capabilities::default())
            .validate(&m)
            .is_err()
    );
    let size_of = |name: &str| wgsl_size(&m, name);
    assert_eq!(size_of("Lambda64"), std::mem::size_of::<Lambda64>());
    assert_eq!(size_of("Point64"), std::mem::size_of::<Point64>());
    assert_eq!(size_of("Out64"), std::mem::size_of::<Out64>());
    assert_eq!(size_of("Params"), std::mem::size_of::<Params>());
}
