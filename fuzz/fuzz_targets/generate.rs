//! Text → validation → generated code of every output the model offers, for the `f64` and
//! `f32` scalars (and the request of every output, which must refuse the unavailable ones
//! with an error). Invariant: no panic. Models of more than `MAX_BODIES` bodies are
//! skipped, so that a run keeps making progress.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tendyn_codegen::{available_outputs, generate_with, Options, Output, Scalar};

const MAX_BODIES: usize = 12;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(model) = tendyn_core::parse(text) else {
        return;
    };
    if model.bodies().len() > MAX_BODIES {
        return;
    }
    let outputs = available_outputs(&model);
    for scalar in [Scalar::F64, Scalar::F32] {
        let _ = generate_with(&model, &outputs, &Options::new(scalar, "fuzz.ron"));
    }
    if outputs.len() != Output::DEFAULT.len() {
        // Refused by the availability check before any tracing: cheap.
        let r = generate_with(&model, Output::DEFAULT, &Options::new(Scalar::F64, "fuzz.ron"));
        assert!(
            r.is_err(),
            "every default output generated although available_outputs offers only {outputs:?}"
        );
    }
});
