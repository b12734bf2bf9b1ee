//! A mechanism and a state: the input is RON text, then (after its first NUL byte, if any) a
//! tail of bytes that gives the numbers. If the text validates, every public entry point of
//! `tendyn_core::Data` runs at that state (and `Model::with_parameters` first, if the
//! file declares runtime parameters).
//!
//! Invariants: no panic, and every `Ok` holds only finite numbers (the project's rule: a
//! bad input gives an error, never a non-finite result).
//!
//! The tail's first byte picks how the numbers are read (byte % 3):
//! 0. raw `f64` bit patterns, 8 bytes each (little-endian): huge, tiny, NaN, ±∞;
//! 1. `i16 / 1000`, 2 bytes each (moderate values, |x| < 33);
//! 2. `(i16 / 32768) · 10^(e % 64 − 32)`, 3 bytes each (a wide range, finite).
//!
//! Numbers are taken in the order: parameters, q, qd, qdd, motor torques, tendon tensions;
//! once the tail runs out every further number is 0.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tendyn_core::{Data, InverseDynamics};

/// Models with more bodies are skipped (the runtime solver is cheap, but not free).
const MAX_BODIES: usize = 32;

struct Numbers<'a> {
    mode: u8,
    bytes: &'a [u8],
}

impl Numbers<'_> {
    fn next(&mut self) -> f64 {
        let width = [8, 2, 3][self.mode as usize];
        if self.bytes.len() < width {
            self.bytes = &[];
            return 0.0;
        }
        let (b, rest) = self.bytes.split_at(width);
        self.bytes = rest;
        match self.mode {
            0 => f64::from_le_bytes(b.try_into().unwrap()),
            1 => f64::from(i16::from_le_bytes([b[0], b[1]])) / 1000.0,
            _ => {
                let m = f64::from(i16::from_le_bytes([b[0], b[1]])) / 32768.0;
                m * 10f64.powi(i32::from(b[2] % 64) - 32)
            }
        }
    }

    fn take(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next()).collect()
    }
}

struct State<'a> {
    q: &'a [f64],
    qd: &'a [f64],
    qdd: &'a [f64],
    tau: &'a [f64],
    tensions: &'a [f64],
}

fn assert_finite<'a>(what: &str, values: impl IntoIterator<Item = &'a f64>, s: &State) {
    let values: Vec<f64> = values.into_iter().copied().collect();
    if values.iter().any(|x| !x.is_finite()) {
        panic!(
            "Ok({what}) holds a non-finite number: {values:?} at q {:?}, qd {:?}, qdd {:?}, \
             motor torques {:?}, tendon tensions {:?}",
            s.q, s.qd, s.qdd, s.tau, s.tensions
        );
    }
}

fn check_inverse(r: &InverseDynamics<f64>, state: &State) {
    let v = |(a, b): &(
        tendyn_core::spatial::Vec3<f64>,
        tendyn_core::spatial::Vec3<f64>,
    )| { a.to_array().into_iter().chain(b.to_array()) };
    let c = |what, x: &[f64]| assert_finite(what, x, state);
    c("inverse_dynamics.generalized_forces", &r.generalized_forces);
    c("inverse_dynamics.motor_torques", &r.motor_torques);
    c("inverse_dynamics.tendon_tensions", &r.tendon_tensions);
    c(
        "inverse_dynamics.minimal_norm_tensions",
        &r.minimal_norm_tensions,
    );
    c(
        "inverse_dynamics.null_space_tensions",
        &r.null_space_tensions,
    );
    c(
        "inverse_dynamics.loop_sides",
        &r.loop_sides.iter().flatten().copied().collect::<Vec<_>>(),
    );
    if let Some(s) = &r.segment_tensions {
        c(
            "inverse_dynamics.segment_tensions",
            &s.iter().flatten().copied().collect::<Vec<_>>(),
        );
    }
    c(
        "inverse_dynamics.pulley_demands",
        &r.pulley_demands.iter().map(|p| p.1).collect::<Vec<_>>(),
    );
    if let Some(b) = &r.bearings {
        c(
            "inverse_dynamics.bearings",
            &b.iter().flat_map(v).collect::<Vec<_>>(),
        );
    }
    if let Some(b) = &r.base_reaction {
        c("inverse_dynamics.base_reaction", &v(b).collect::<Vec<_>>());
    }
    c(
        "inverse_dynamics.bearing_friction",
        &r.bearing_friction.iter().map(|p| p.1).collect::<Vec<_>>(),
    );
    c("inverse_dynamics.unknowns", &r.unknowns);
    let _ = r.slack_loops();
}

fuzz_target!(|data: &[u8]| {
    let (text, tail) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    let Ok(text) = std::str::from_utf8(text) else {
        return;
    };
    let Ok(file_model) = tendyn_core::parse(text) else {
        return;
    };
    if file_model.bodies().len() > MAX_BODIES {
        return;
    }
    let mut numbers = match tail.split_first() {
        Some((&m, rest)) => Numbers {
            mode: m % 3,
            bytes: rest,
        },
        None => Numbers {
            mode: 0,
            bytes: &[],
        },
    };

    let with_params;
    let model = if file_model.parameters().is_empty() {
        &file_model
    } else {
        let p = numbers.take(file_model.parameters().len());
        match file_model.with_parameters(&p) {
            Ok(m) => {
                with_params = m;
                &with_params
            }
            // Refused: the file's own values.
            Err(_) => &file_model,
        }
    };

    let n = model.dof();
    let q = numbers.take(n);
    let qd = numbers.take(n);
    let qdd = numbers.take(n);
    let tau = numbers.take(model.motors().len());
    let tensions = numbers.take(model.tendons().len());
    let state = &State {
        q: &q,
        qd: &qd,
        qdd: &qdd,
        tau: &tau,
        tensions: &tensions,
    };

    // Properties of the model alone: no panic (NaN endpoints are documented).
    let _ = tendyn_core::torque_range::static_torque_ranges(model);

    let mut s = Data::new(model);
    if let Ok(r) = s.inverse_dynamics(model, &q, &qd, &qdd) {
        check_inverse(r, state);
        let _ = s.balance_rows(model, &q, &qd, &qdd);
    }
    if let Ok(x) = s.generalized_forces(model, &q, &qd, &qdd) {
        assert_finite("generalized_forces", x, state);
    }
    if let Ok(m) = s.mass_matrix(model, &q) {
        assert_finite("mass_matrix", m.iter().flatten(), state);
    }
    if let Ok(h) = s.bias(model, &q, &qd) {
        assert_finite("bias", h, state);
    }
    if let Ok(g) = s.gravity(model, &q) {
        assert_finite("gravity", g, state);
    }
    if let Ok(a) = s.forward_dynamics(model, &q, &qd, &tau, &tensions) {
        assert_finite("forward_dynamics", a, state);
    }
    if let Ok(x) = s.forward_dynamics_scale(model, &q, &qd, &tau, &tensions) {
        assert_finite("forward_dynamics_scale", [&x], state);
    }
});
