//! Generates the benchmarked outputs of the scale mechanisms (`mechanisms/*.ron`) into
//! `OUT_DIR`, in `f64`: what `benches/scale.rs` times beside the runtime solver.

fn main() {
    let mut builder = tendyn_codegen::Builder::new()
        .outputs(&[
            "generalized_forces",
            "mass_matrix",
            "forward_dynamics",
            "actuation",
        ])
        .scalar(tendyn_codegen::Scalar::F64);
    for name in ["finger4", "arm6", "chain8", "chain12"] {
        builder = builder.mechanism(format!("mechanisms/{name}.ron"));
    }
    builder.generate().unwrap_or_else(|e| panic!("{e}"));
}
