//! `tendyn-codegen`: turns a validated mechanism into specialised straight-line Rust.
//!
//! The symbolic engine arrives with issue 4; for now this crate hosts the `tendyn` CLI
//! (`src/bin/tendyn.rs`) and its report formatting ([`report`]).

pub mod closed_form;
pub mod expr;
pub mod report;
