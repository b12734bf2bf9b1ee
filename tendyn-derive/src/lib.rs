//! `#[derive(TendonMechanism)]`: generated dynamics from a RON file at compile time.
//!
//! Empty for now: the derive is built on top of `tendyn-codegen` (issue 5).
