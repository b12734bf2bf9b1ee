//! Generates the finger's dynamics into `OUT_DIR` (firmware runs no proc macro and its
//! authors can read `target/.../out/example3_stanford_jpl.rs`). Only what the controller
//! calls is generated: the inverse dynamics with the tension distribution.

fn main() {
    tendyn_codegen::Builder::new()
        .mechanism("../mechanisms/example3_stanford_jpl.ron")
        .outputs(&["actuation"])
        .scalar(tendyn_codegen::Scalar::Generic)
        .generate()
        .unwrap_or_else(|e| panic!("{e}"));
}
