//! samplab's integration tests as one binary, each file a module (one link where there were
//! twelve). Binaries of their own: `allocation.rs` (a global allocator), `memory.rs` (the
//! process-wide memory limit) and `discrepancy.rs`, whose stops are judged in CPU seconds
//! after the flag (beside the heavier tests of the others a 4 x 10^6-point sort ran past
//! its bound once in two runs).
#[path = "architecture.rs"]
mod architecture;
#[path = "conform.rs"]
mod conform;
#[path = "conformance.rs"]
mod conformance;
#[path = "constructions.rs"]
mod constructions;
#[path = "cubature.rs"]
mod cubature;
#[path = "expr.rs"]
mod expr;
#[path = "integrands_d.rs"]
mod integrands_d;
#[path = "integration.rs"]
mod integration;
#[path = "nets.rs"]
mod nets;
#[path = "pixels.rs"]
mod pixels;
#[path = "predict.rs"]
mod predict;
#[path = "spatial.rs"]
mod spatial;
#[path = "spectrum.rs"]
mod spectrum;
#[path = "structure.rs"]
mod structure;
