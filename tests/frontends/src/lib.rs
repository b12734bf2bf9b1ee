//! The paper's three examples, each made available the two compile-time ways: by
//! `#[derive(TendonMechanism)]` (`derived`) and by a build script (`built`), so that
//! `tests/agreement.rs` can hold them against each other and against the runtime solver.

/// The build-script way (see `build.rs`).
pub mod built {
    pub mod example1 {
        tendyn_core::include_mechanism!("example1_endless");
    }
    pub mod example2 {
        tendyn_core::include_mechanism!("example2_open_ended");
    }
    pub mod example3 {
        tendyn_core::include_mechanism!("example3_stanford_jpl");
    }
}

/// The derive way, every output each example can provide.
pub mod derived {
    use tendyn::TendonMechanism;

    #[derive(TendonMechanism)]
    #[tendyn(file = "../../examples/mechanisms/example1_endless.ron")]
    pub struct Example1;

    #[derive(TendonMechanism)]
    #[tendyn(file = "../../examples/mechanisms/example2_open_ended.ron")]
    pub struct Example2;

    #[derive(TendonMechanism)]
    #[tendyn(file = "../../examples/mechanisms/example3_stanford_jpl.ron")]
    pub struct Example3;
}
