//! The integration tests, one binary: linking each file apart cost minutes of every test run.
//! `cargo test --release --test suite rough_wet::` runs one file's tests. tests/interrupt.rs stays a
//! binary of its own (an interrupt request is process-wide).

mod architecture;
mod atlas;
mod cli;
mod cli_refusals;
mod common;
mod cycle;
mod dem;
mod docs_examples;
mod domain;
mod extremes;
mod figures;
mod fit;
mod fit_fold;
mod fit_humidity;
mod fit_tip;
mod fit_two_zone;
mod gpu;
mod humidity;
mod law;
mod map;
mod profile;
mod properties;
mod reference;
mod reliability;
mod reliability_fit;
mod reliability_input;
mod reliability_outputs;
mod reliability_states;
mod rough;
mod rough_map;
mod rough_wet;
mod shaders;
mod tip;
mod tip_reference;
mod two_zone_cycle;
mod two_zone_profile;
mod two_zone_reference;
