//! Compile-time behaviour of `#[derive(TendonMechanism)]`, through trybuild: every paper
//! example and parameters-as-fields compile and run (`ui/pass`), and every problem the
//! runtime validation reports is a compile error at the attribute that names what is wrong
//! (`ui/fail`, with the expected messages in the `.stderr` files).
//!
//! trybuild compiles the cases in a scratch crate, so relative mechanism paths are resolved
//! against this crate's directory through `TENDYN_MANIFEST_DIR`.

#[test]
fn derive_compiles_good_mechanisms_and_rejects_bad_ones_with_located_errors() {
    std::env::set_var("TENDYN_MANIFEST_DIR", env!("CARGO_MANIFEST_DIR"));
    let t = trybuild::TestCases::new();
    t.pass("tests/ui/pass/*.rs");
    t.compile_fail("tests/ui/fail/*.rs");
}
