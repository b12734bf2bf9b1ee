//! The paper's three example mechanisms, as shipped in `examples/mechanisms/`.

use tendyn_core::Model;

/// File names (without `.ron`) of the paper's examples, in paper order.
pub const NAMES: [&str; 3] = [
    "example1_endless",
    "example2_open_ended",
    "example3_stanford_jpl",
];

/// The RON text of example `name`.
pub fn text(name: &str) -> String {
    let path = format!(
        "{}/../examples/mechanisms/{name}.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The three examples, validated.
pub fn all() -> Vec<Model<f64>> {
    NAMES
        .iter()
        .map(|n| tendyn_core::parse(&text(n)).unwrap_or_else(|e| panic!("{n}: {e}")))
        .collect()
}
