//! Scale benchmarks of tendyn (issue 16): `cargo bench -p tendyn-bench`. The mechanisms are
//! in `mechanisms/`; the build script generates their `generalized_forces`, `mass_matrix`,
//! `forward_dynamics` and `actuation` in `f64`, and `benches/scale.rs` times them and the
//! runtime solver's evaluators over the same 1,024 seeded states (the protocol of
//! `docs/references.md`). The generated modules are included by the benchmark alone, so
//! that tests do not compile them.
