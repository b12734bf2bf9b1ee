//! The build-script way: the paper's examples generated into `OUT_DIR` by
//! `tendyn_codegen::Builder`, in f64, every output each can provide.

fn main() {
    tendyn_codegen::Builder::new()
        .mechanism("../../examples/mechanisms/example1_endless.ron")
        .mechanism("../../examples/mechanisms/example2_open_ended.ron")
        .mechanism("../../examples/mechanisms/example3_stanford_jpl.ron")
        .scalar(tendyn_codegen::Scalar::F64)
        .generate()
        .unwrap_or_else(|e| panic!("{e}"));
}
