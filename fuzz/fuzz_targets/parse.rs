//! Bytes → UTF-8 text → `tendyn_core::parse`. Invariant: no panic (any text gives a model
//! or an `Error`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = tendyn_core::parse(text);
    }
});
