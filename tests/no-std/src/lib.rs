//! The generated dynamics of the Stanford/JPL finger, and of Example 2 with bearing and
//! with capstan friction, in a `#![no_std]` crate that has no
//! `alloc`: built on its own (`cargo build -p tendyn-no-std-check`, as CI does), this
//! compiles `tendyn-core` without its `std` feature too, so anything in the generated code
//! or in `tendyn_core::Real` that needed `std` or `alloc` would fail to build here.
#![no_std]

/// The golden generated code of the paper's Example 3.
pub mod finger {
    include!("../../../tendyn-codegen/golden/example3_stanford_jpl.rs");
}

/// Example 2 with bearing friction: Coulomb friction's sign selects (`Real::sign_outside`).
pub mod bearing_friction {
    include!("../../../tendyn-codegen/golden/example2_friction.rs");
}

/// Example 2 with capstan friction on its guides: the directions' selects, `exp` of the
/// capstan factors, and the state's tension system traced.
pub mod capstan_friction {
    include!("../../../tendyn-codegen/golden/example2_capstan.rs");
}
