//! Every shader parses and validates with naga (no GPU needed), and the Rust structs match the
//! WGSL layouts byte for byte.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use tabor::kernel::layout::{
    Branch, ClassifyParams, EnsembleParams, GpuLambda, Lambda64, Out, Out64, Params, Point64,
    SummitRec,
};

fn parse(src: &str) -> naga::Module {
    naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{}", e.emit_to_string(src)))
}

fn module() -> naga::Module {
    parse(&tabor::kernel::shader_source())
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

/// An f64 module (its own: the f32 one must build where f64 does not exist), parsed: it
/// validates with the FLOAT64 capability and not without it.
fn f64_module(source: &str) -> naga::Module {
    let m = parse(source);
    Validator::new(ValidationFlags::all(), Capabilities::FLOAT64)
        .validate(&m)
        .unwrap_or_else(|e| panic!("{e:?}"));
    assert!(
        Validator::new(ValidationFlags::all(), Capabilities::default())
            .validate(&m)
            .is_err()
    );
    m
}

/// The f64 refinement's module validates as an f64 module, and its structs match the Rust ones.
#[test]
fn f64_module_validates_and_matches_rust_layout() {
    let m = f64_module(&tabor::kernel::polish64_source());
    let size_of = |name: &str| wgsl_size(&m, name);
    assert_eq!(size_of("Lambda64"), std::mem::size_of::<Lambda64>());
    assert_eq!(size_of("Point64"), std::mem::size_of::<Point64>());
    assert_eq!(size_of("Out64"), std::mem::size_of::<Out64>());
    assert_eq!(size_of("Params"), std::mem::size_of::<Params>());
}

/// The map's classification validates, and its parameters match the Rust struct.
#[test]
fn classify_module_validates_and_matches_rust_layout() {
    let m = parse(&tabor::kernel::classify_source());
    Validator::new(ValidationFlags::all(), Capabilities::FLOAT64)
        .validate(&m)
        .unwrap_or_else(|e| panic!("{e:?}"));
    assert_eq!(
        wgsl_size(&m, "Params"),
        std::mem::size_of::<ClassifyParams>()
    );
}

/// An ensemble's stepping validates as an f64 module, and its structs match the Rust ones.
#[test]
fn ensemble_module_validates_and_matches_rust_layout() {
    let m = f64_module(&tabor::kernel::ensemble64_source());
    assert_eq!(wgsl_size(&m, "Summit"), std::mem::size_of::<SummitRec>());
    assert_eq!(
        wgsl_size(&m, "Params"),
        std::mem::size_of::<EnsembleParams>()
    );
    let entries: Vec<_> = m.entry_points.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(entries, ["sum_chunks", "reduce"]);
}

/// The value of a named WGSL `const` of `m` (a scalar literal).
fn wgsl_const(m: &naga::Module, name: &str) -> f64 {
    let (_, c) = m
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no const {name}"));
    match m.global_expressions[c.init] {
        naga::Expression::Literal(naga::Literal::F32(v)) => v as f64,
        naga::Expression::Literal(naga::Literal::F64(v)) => v,
        naga::Expression::Literal(naga::Literal::U32(v)) => v as f64,
        ref e => panic!("const {name} is not a scalar literal: {e:?}"),
    }
}

/// The shader and its CPU mirror use the same thresholds, and every kernel the host's
/// workgroup size: read from the WGSL through naga, so neither side can drift.
#[test]
fn shader_constants_match_the_host() {
    use tabor::kernel::cpu::md;
    let m = module();
    for (name, v) in [
        ("F_NOISE", md::F_NOISE as f64),
        ("BRACKET_CLOSED", md::BRACKET_CLOSED as f64),
        ("SUB_ULP_STEP", md::SUB_ULP_STEP as f64),
        ("BRACKET_BELOW", md::BRACKET_BELOW as f64),
        ("BRACKET_ABOVE", md::BRACKET_ABOVE as f64),
        ("MAX_ITER", md::MAX_ITER as f64),
        ("TABLE_NODES", tabor::solver::context::TABLE_NODES as f64),
    ] {
        assert_eq!(wgsl_const(&m, name), v, "{name}");
    }
    let size = tabor::kernel::prelude::WORKGROUP_SIZE as u32;
    let p64 = parse(&tabor::kernel::polish64_source());
    for module in [&m, &p64] {
        for e in &module.entry_points {
            assert_eq!(e.workgroup_size, [size, 1, 1], "{}", e.name);
        }
    }
}
