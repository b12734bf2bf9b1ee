//! Error against run time (`tendyn report`): for each mechanism compiled into this crate
//! (see `build.rs`) and each output its generated code provides, four evaluators are timed
//! over the same seeded random states and checked against a double-double reference:
//!
//! | evaluator | what runs |
//! |---|---|
//! | generated f64, generated f32 | the generated function of that output, generic code at that scalar |
//! | runtime f64, runtime f32 | the [`Data`] method that gives the output (`inverse_dynamics` for actuation, segment tensions, bearings and the base reaction, which only it gives); f32 on `model.cast_numeric::<f32>()` |
//!
//! **States** (the benchmark protocol of `docs/references.md`): `q ∈ [−π, π]`,
//! `q̇ ∈ [−3, 3]`, `q̈ ∈ [−10, 10]`, uniform, seeded; forward dynamics takes the reference
//! inverse dynamics' motor torques and tendon tensions (rounded to f64) at the same state.
//! f32 evaluators get the states (and those torques and tensions) rounded to f32.
//!
//! **Time**: per evaluator, a warm-up of at least [`Config::warmup`], then
//! [`Config::samples`] samples; a sample is `R` passes over all states (`R` chosen so that a
//! sample lasts at least [`Config::min_sample`]) divided by `R ×` the number of states.
//! Reported: the median and the interquartile range (25th–75th percentile) of the samples.
//!
//! **Error**: per state, the max-norm relative error `‖x − ref‖∞ / ‖ref‖∞` of the output
//! vector (every entry of the flattened output), the difference taken in double-double;
//! for forward dynamics the denominator is at least the size of the terms it sums
//! ([`forward_dynamics_term_scale`]), since balancing tensions make `q̈` a small difference
//! of large numbers. Where the reference is exactly 0 (every entry), the error at that
//! state is absolute (`‖x‖∞`), and the row says how many states that was. Reported: the
//! maximum and the median over the states. The reference is the runtime solver on
//! `model.cast_numeric::<DoubleDouble>()` (about 106 bits) at the state the evaluator got:
//! for f32 evaluators, the state rounded to f32. So an error is the evaluator's own (its
//! arithmetic and its rounded constants), not the rounding of its inputs, which would add
//! the problem's condition number times 6e-8 whatever the evaluator (near `sin q = 0`,
//! where `h` is small, that alone reaches 1e-4 relative).

#![warn(missing_docs)]

pub mod chart;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::{Duration, Instant};
use tendyn_core::output::State;
use tendyn_core::{Data, DoubleDouble, InverseDynamics, Model, Numeric};

pub use tendyn_codegen::Output;

/// One state, in f64, with everything any output takes.
#[derive(Clone, Debug, PartialEq)]
pub struct Inputs {
    /// Joint angles (rad).
    pub q: Vec<f64>,
    /// Joint rates (rad/s).
    pub qd: Vec<f64>,
    /// Joint accelerations (rad/s²).
    pub qdd: Vec<f64>,
    /// Motor torques (N·m) for forward dynamics: the reference inverse dynamics' at this
    /// state.
    pub motor_torques: Vec<f64>,
    /// Ground-level tendon tensions (N) for forward dynamics, likewise.
    pub tendon_tensions: Vec<f64>,
    /// The runtime parameters' nominal values (generated code takes them as an input).
    pub parameters: Vec<f64>,
}

/// One pass of a generated function over prepared states.
pub trait Pass {
    /// Runs `output` once per state; `false` if this mechanism's code has no such output.
    fn pass(&self, output: Output) -> bool;
}

/// A mechanism compiled into this crate by `build.rs`.
#[derive(Clone, Copy)]
pub struct Mechanism {
    /// The `name` in its file.
    pub name: &'static str,
    /// The file it was generated from.
    pub file: &'static str,
    /// The file's text, as generated.
    pub ron: &'static str,
    /// Every output its generated code provides.
    pub outputs: &'static [Output],
    /// The states converted once to fixed-size `f64` arrays, ready to be timed by the
    /// generated code at `f64`; `None` if a state has the wrong sizes.
    pub pack_f64: fn(&[Inputs]) -> Option<Box<dyn Pass>>,
    /// The same at `f32` (give it states already rounded to f32).
    pub pack_f32: fn(&[Inputs]) -> Option<Box<dyn Pass>>,
    /// One output of the generated code at `f64` at one state, flattened; `None` if it is
    /// not generated here or the state has the wrong sizes.
    pub eval_f64: fn(Output, &Inputs) -> Option<Vec<f64>>,
    /// The same at `f32`, the results widened to `f64`.
    pub eval_f32: fn(Output, &Inputs) -> Option<Vec<f64>>,
}

include!(concat!(env!("OUT_DIR"), "/glue.rs"));

/// Who computes the output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Evaluator {
    /// The generated function, generic code at `f64`.
    GeneratedF64,
    /// The generated function, generic code at `f32`.
    GeneratedF32,
    /// The runtime solver on the model (`Data<f64>`).
    RuntimeF64,
    /// The runtime solver on `model.cast_numeric::<f32>()`.
    RuntimeF32,
}

impl Evaluator {
    /// The four, in the order of the table's rows.
    pub const ALL: [Evaluator; 4] = [
        Evaluator::GeneratedF64,
        Evaluator::GeneratedF32,
        Evaluator::RuntimeF64,
        Evaluator::RuntimeF32,
    ];

    /// The evaluator as the table, the chart and the JSON name it (`generated f64`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Evaluator::GeneratedF64 => "generated f64",
            Evaluator::GeneratedF32 => "generated f32",
            Evaluator::RuntimeF64 => "runtime f64",
            Evaluator::RuntimeF32 => "runtime f32",
        }
    }
}

/// How much to measure.
#[derive(Clone, Debug)]
pub struct Config {
    /// Random states per mechanism (the peers' protocol: 1,024).
    pub states: usize,
    /// Timing samples per evaluator.
    pub samples: usize,
    /// Minimum warm-up per evaluator (at least one pass is always run).
    pub warmup: Duration,
    /// Minimum duration of one sample.
    pub min_sample: Duration,
    /// Seed of the states (the same for every mechanism).
    pub seed: u64,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            states: 1024,
            samples: 31,
            warmup: Duration::from_millis(300),
            min_sample: Duration::from_millis(2),
            seed: 7,
        }
    }
}

/// Order statistics of the timing samples, ns per call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// The fastest sample.
    pub min: f64,
    /// The 25th percentile.
    pub p25: f64,
    /// The median, what the table reports.
    pub median: f64,
    /// The 75th percentile.
    pub p75: f64,
    /// The slowest sample.
    pub max: f64,
}

impl Spread {
    fn of(samples: &mut [f64]) -> Spread {
        samples.sort_by(f64::total_cmp);
        Spread {
            min: quantile(samples, 0.0),
            p25: quantile(samples, 0.25),
            median: quantile(samples, 0.5),
            p75: quantile(samples, 0.75),
            max: quantile(samples, 1.0),
        }
    }
}

/// Linear interpolation between order statistics of sorted `v` (NaN when empty).
fn quantile(v: &[f64], p: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let x = p * (v.len() - 1) as f64;
    let (i, f) = (x.floor() as usize, x - x.floor());
    if i + 1 < v.len() {
        v[i] + f * (v[i + 1] - v[i])
    } else {
        v[i]
    }
}

/// One evaluator on one output of one mechanism.
#[derive(Clone, Debug)]
pub struct Row {
    /// The `name` in its file (`name#k` when files share it, `k` its position from 1).
    pub mechanism: String,
    /// The file it was generated from ([`Mechanism::file`]).
    pub file: String,
    /// The output measured.
    pub output: Output,
    /// Who computed it.
    pub evaluator: Evaluator,
    /// ns per call.
    pub time: Spread,
    /// Max over the states of the per-state error (see the crate docs for the norm).
    pub max_error: f64,
    /// Median over the states of the per-state error.
    pub median_error: f64,
    /// States at which the evaluator returned an error (runtime solver only); the error
    /// figures are over the others.
    pub failed_states: usize,
    /// States at which the reference is exactly 0, where the error is absolute.
    pub absolute_states: usize,
}

/// Everything measured.
#[derive(Clone, Debug)]
pub struct Report {
    /// What was measured with.
    pub config: Config,
    /// One row per mechanism, output and evaluator, in that order.
    pub rows: Vec<Row>,
    /// What could not be measured, and states redrawn.
    pub notes: Vec<String>,
}

/// One state in the scalar of a runtime solver.
struct RuntimeState<T> {
    q: Vec<T>,
    qd: Vec<T>,
    qdd: Vec<T>,
    mt: Vec<T>,
    tt: Vec<T>,
}

impl<T: Numeric> RuntimeState<T> {
    fn state(&self) -> State<'_, T> {
        State {
            q: &self.q,
            qd: &self.qd,
            qdd: &self.qdd,
            motor_torques: &self.mt,
            tendon_tensions: &self.tt,
        }
    }

    fn of(s: &Inputs) -> Self {
        let c = |v: &[f64]| v.iter().map(|&x| T::from_f64(x)).collect();
        RuntimeState {
            q: c(&s.q),
            qd: c(&s.qd),
            qdd: c(&s.qdd),
            mt: c(&s.motor_torques),
            tt: c(&s.tendon_tensions),
        }
    }
}

/// `output` by the runtime solver at one state, flattened as generated code flattens it.
fn runtime<T: Numeric>(
    m: &Model<T>,
    s: &mut Data<T>,
    output: Output,
    st: &RuntimeState<T>,
) -> Result<Vec<T>, String> {
    s.output(m, output, &st.state()).map_err(|e| e.to_string())
}

/// One timed pass of the runtime solver's call for `output` over the states.
fn runtime_pass<T: Numeric>(
    m: &Model<T>,
    s: &mut Data<T>,
    output: Output,
    states: &[RuntimeState<T>],
) {
    match output {
        Output::GeneralizedForces => {
            for st in states {
                let _ = black_box(s.generalized_forces(
                    m,
                    black_box(&st.q),
                    black_box(&st.qd),
                    black_box(&st.qdd),
                ));
            }
        }
        Output::MassMatrix => {
            for st in states {
                let _ = black_box(s.mass_matrix(m, black_box(&st.q)));
            }
        }
        Output::Bias => {
            for st in states {
                let _ = black_box(s.bias(m, black_box(&st.q), black_box(&st.qd)));
            }
        }
        Output::Gravity => {
            for st in states {
                let _ = black_box(s.gravity(m, black_box(&st.q)));
            }
        }
        Output::ForwardDynamics => {
            for st in states {
                let _ = black_box(s.forward_dynamics(
                    m,
                    black_box(&st.q),
                    black_box(&st.qd),
                    black_box(&st.mt),
                    black_box(&st.tt),
                ));
            }
        }
        _ => {
            for st in states {
                let _ = black_box(s.inverse_dynamics(
                    m,
                    black_box(&st.q),
                    black_box(&st.qd),
                    black_box(&st.qdd),
                ));
            }
        }
    }
}

/// Times `pass` (one pass over `states` states): warm-up, then the samples, ns per call.
pub fn time(config: &Config, states: usize, pass: &mut dyn FnMut()) -> Spread {
    let start = Instant::now();
    let mut passes = 0u64;
    loop {
        pass();
        passes += 1;
        if start.elapsed() >= config.warmup {
            break;
        }
    }
    let per_pass = (start.elapsed().as_secs_f64() / passes as f64).max(1e-9);
    let reps = ((config.min_sample.as_secs_f64() / per_pass).ceil() as u64).max(1);
    let calls = (reps * states.max(1) as u64) as f64;
    let mut ns: Vec<f64> = (0..config.samples.max(1))
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                pass();
            }
            t.elapsed().as_secs_f64() * 1e9 / calls
        })
        .collect();
    Spread::of(&mut ns)
}

/// The size of the terms forward dynamics sums (`Data::forward_dynamics_scale`, in
/// f64; it only scales the error). Balancing tensions make `q̈` a small difference of large
/// numbers, so its error is measured against this.
pub fn forward_dynamics_term_scale(model: &Model<f64>, s: &Inputs) -> Result<f64, String> {
    Data::new(model)
        .forward_dynamics_scale(model, &s.q, &s.qd, &s.motor_torques, &s.tendon_tensions)
        .map_err(|e| e.to_string())
}

/// Progress, for long runs: mechanism `mechanism` of `of` (from 1), and what is being
/// measured (the reference states when `output` is `None`; the errors of an output when
/// `evaluator` is `None`, then each evaluator's time).
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    /// Which mechanism, from 1.
    pub mechanism: usize,
    /// How many mechanisms there are.
    pub of: usize,
    /// The mechanism's name, as in [`Row::mechanism`].
    pub name: &'a str,
    /// The output measured; `None` while the reference states are drawn.
    pub output: Option<Output>,
    /// The evaluator timed; `None` while the errors of `output` are computed.
    pub evaluator: Option<Evaluator>,
}

/// The states of one mechanism as the f64 and the f32 evaluators get them, and the
/// reference inverse dynamics at each (states at which the reference fails are redrawn,
/// and counted).
struct States {
    f64: Vec<Inputs>,
    /// The same states rounded to f32 (the forward-dynamics inputs too), held in f64.
    f32: Vec<Inputs>,
    id_f64: Vec<InverseDynamics<DoubleDouble>>,
    id_f32: Vec<InverseDynamics<DoubleDouble>>,
    note: Option<String>,
}

fn dd(v: &[f64]) -> Vec<DoubleDouble> {
    v.iter().map(|&x| DoubleDouble::from(x)).collect()
}

fn to_f32(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| x as f32 as f64).collect()
}

fn draw_states(
    model: &Model<f64>,
    (dd_model, reference): (&Model<DoubleDouble>, &mut Data<DoubleDouble>),
    config: &Config,
) -> Result<States, String> {
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed);
    let n = model.dof();
    let parameters: Vec<f64> = model.parameters().iter().map(|p| p.value).collect();
    let mut out = States {
        f64: Vec::new(),
        f32: Vec::new(),
        id_f64: Vec::new(),
        id_f32: Vec::new(),
        note: None,
    };
    let (mut redrawn, mut first) = (0usize, None);
    let mut id = |q: &[f64], qd: &[f64], qdd: &[f64]| {
        reference
            .inverse_dynamics(dd_model, &dd(q), &dd(qd), &dd(qdd))
            .cloned()
            .map_err(|e| e.to_string())
    };
    while out.f64.len() < config.states {
        let mut v = |s: f64| {
            (0..n)
                .map(|_| rng.random_range(-s..s))
                .collect::<Vec<f64>>()
        };
        let (q, qd, qdd) = (v(std::f64::consts::PI), v(3.0), v(10.0));
        let (q32, qd32, qdd32) = (to_f32(&q), to_f32(&qd), to_f32(&qdd));
        match id(&q, &qd, &qdd).and_then(|a| Ok((a, id(&q32, &qd32, &qdd32)?))) {
            Ok((a, b)) => {
                let f = |v: &[DoubleDouble]| v.iter().map(|x| x.to_f64()).collect::<Vec<_>>();
                let (mt, tt) = (f(&a.motor_torques), f(&a.tendon_tensions));
                out.f32.push(Inputs {
                    q: q32,
                    qd: qd32,
                    qdd: qdd32,
                    motor_torques: to_f32(&mt),
                    tendon_tensions: to_f32(&tt),
                    parameters: to_f32(&parameters),
                });
                out.f64.push(Inputs {
                    q,
                    qd,
                    qdd,
                    motor_torques: mt,
                    tendon_tensions: tt,
                    parameters: parameters.clone(),
                });
                out.id_f64.push(a);
                out.id_f32.push(b);
            }
            Err(e) => {
                redrawn += 1;
                first.get_or_insert(e);
                if redrawn > 10 * config.states.max(10) {
                    return Err(format!(
                        "the reference inverse dynamics failed at {redrawn} random states \
                         (first: {})",
                        first.unwrap_or_default()
                    ));
                }
            }
        }
    }
    out.note = first.map(|e| {
        format!("{redrawn} states redrawn: the reference inverse dynamics failed (first: {e})")
    });
    Ok(out)
}

/// `output` by the double-double reference at every state; `Err` names the first state at
/// which it fails.
fn reference_at(
    (dd_model, reference): (&Model<DoubleDouble>, &mut Data<DoubleDouble>),
    output: Output,
    states: &[Inputs],
    ids: &[InverseDynamics<DoubleDouble>],
) -> Result<Vec<Vec<DoubleDouble>>, String> {
    states
        .iter()
        .zip(ids)
        .enumerate()
        .map(|(i, (s, id))| {
            match output.evaluator() {
                "inverse_dynamics" => id
                    .flattened(output)
                    .ok_or_else(|| format!("{} is not available", output.name())),
                _ => runtime(dd_model, reference, output, &RuntimeState::of(s)),
            }
            .map_err(|e| format!("state {i} (q = {:?}): {e}", s.q))
        })
        .collect()
}

/// Per-state errors of one evaluator against the reference.
#[derive(Default)]
struct Errors {
    values: Vec<f64>,
    failed: usize,
    absolute: usize,
}

impl Errors {
    fn add(&mut self, got: Result<Vec<f64>, String>, want: &[DoubleDouble], floor: f64) {
        let got = match got {
            Ok(g) => g,
            Err(_) => {
                self.failed += 1;
                return;
            }
        };
        if got.len() != want.len() {
            self.values.push(f64::INFINITY);
            return;
        }
        let diff = got
            .iter()
            .zip(want)
            .map(|(&x, &r)| {
                let d = (DoubleDouble::from(x) - r).abs().to_f64();
                if d.is_nan() {
                    f64::INFINITY
                } else {
                    d
                }
            })
            .fold(0.0f64, f64::max);
        let scale = want
            .iter()
            .map(|r| r.abs().to_f64())
            .fold(0.0f64, f64::max)
            .max(floor);
        if scale == 0.0 {
            self.absolute += 1;
            self.values.push(diff);
        } else {
            self.values.push(diff / scale);
        }
    }

    fn max_median(&mut self) -> (f64, f64) {
        self.values.sort_by(f64::total_cmp);
        (
            self.values.last().copied().unwrap_or(f64::NAN),
            quantile(&self.values, 0.5),
        )
    }
}

/// Measures every output of every mechanism: times and errors of the four evaluators.
/// Errors name the mechanism's file and what went wrong.
pub fn run(
    mechanisms: &[Mechanism],
    config: &Config,
    progress: &mut dyn FnMut(Progress),
) -> Result<Report, String> {
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for (k, mech) in mechanisms.iter().enumerate() {
        let at = |e: String| format!("{}: {e}", mech.file);
        // Two files may give the same name: then the rows say which (by position, from 1).
        let name = if mechanisms.iter().filter(|m| m.name == mech.name).count() > 1 {
            format!("{}#{}", mech.name, k + 1)
        } else {
            mech.name.to_string()
        };
        let say = |output, evaluator, progress: &mut dyn FnMut(Progress)| {
            progress(Progress {
                mechanism: k + 1,
                of: mechanisms.len(),
                name: &name,
                output,
                evaluator,
            })
        };
        say(None, None, progress);
        let model = tendyn_core::parse(mech.ron).map_err(|e| at(e.to_string()))?;
        let dd_model = model.cast_numeric::<DoubleDouble>();
        let f32_model = model.cast_numeric::<f32>();
        let mut reference = Data::new(&dd_model);
        let states = draw_states(&model, (&dd_model, &mut reference), config).map_err(at)?;
        notes.extend(states.note.as_ref().map(|n| format!("{name}: {n}")));
        let f64_states: Vec<RuntimeState<f64>> = states.f64.iter().map(RuntimeState::of).collect();
        let f32_states: Vec<RuntimeState<f32>> = states.f32.iter().map(RuntimeState::of).collect();
        let internal = |what: &str| at(format!("internal: the generated {what} does not match"));
        let packed_f64 = (mech.pack_f64)(&states.f64).ok_or_else(|| internal("state sizes"))?;
        let packed_f32 = (mech.pack_f32)(&states.f32).ok_or_else(|| internal("state sizes"))?;
        let mut solver_f64 = Data::new(&model);
        let mut solver_f32 = Data::new(&f32_model);
        for &output in mech.outputs {
            say(Some(output), None, progress);
            // The reference at every state, as each scalar's evaluators get it.
            let want = reference_at(
                (&dd_model, &mut reference),
                output,
                &states.f64,
                &states.id_f64,
            )
            .and_then(|a| {
                Ok((
                    a,
                    reference_at(
                        (&dd_model, &mut reference),
                        output,
                        &states.f32,
                        &states.id_f32,
                    )?,
                ))
            });
            let (want_f64, want_f32) = match want {
                Ok(w) => w,
                Err(e) => {
                    notes.push(format!(
                        "{name}: {} not measured: the reference failed at {e}",
                        output.name()
                    ));
                    continue;
                }
            };
            // Errors.
            let mut errors: [Errors; 4] = Default::default();
            for (i, (s64, s32)) in states.f64.iter().zip(&states.f32).enumerate() {
                let floor = |s: &Inputs| {
                    if output == Output::ForwardDynamics {
                        forward_dynamics_term_scale(&model, s).unwrap_or(0.0)
                    } else {
                        0.0
                    }
                };
                let to64 = |v: Vec<f32>| v.into_iter().map(f64::from).collect::<Vec<f64>>();
                let generated = |eval: fn(Output, &Inputs) -> Option<Vec<f64>>, s| {
                    // Generated code cannot fail; a missing output is a bug of the glue.
                    eval(output, s).ok_or_else(|| internal(output.name()))
                };
                let (floor64, floor32) = (floor(s64), floor(s32));
                errors[0].add(Ok(generated(mech.eval_f64, s64)?), &want_f64[i], floor64);
                errors[1].add(Ok(generated(mech.eval_f32, s32)?), &want_f32[i], floor32);
                errors[2].add(
                    runtime(&model, &mut solver_f64, output, &f64_states[i]),
                    &want_f64[i],
                    floor64,
                );
                errors[3].add(
                    runtime(&f32_model, &mut solver_f32, output, &f32_states[i]).map(to64),
                    &want_f32[i],
                    floor32,
                );
            }
            // Times.
            let n = states.f64.len();
            for (j, e) in Evaluator::ALL.iter().enumerate() {
                say(Some(output), Some(*e), progress);
                let mut ran = true;
                let t = match e {
                    Evaluator::GeneratedF64 => {
                        time(config, n, &mut || ran &= packed_f64.pass(output))
                    }
                    Evaluator::GeneratedF32 => {
                        time(config, n, &mut || ran &= packed_f32.pass(output))
                    }
                    Evaluator::RuntimeF64 => time(config, n, &mut || {
                        runtime_pass(&model, &mut solver_f64, output, &f64_states)
                    }),
                    Evaluator::RuntimeF32 => time(config, n, &mut || {
                        runtime_pass(&f32_model, &mut solver_f32, output, &f32_states)
                    }),
                };
                if !ran {
                    return Err(internal(output.name()));
                }
                let (max_error, median_error) = errors[j].max_median();
                rows.push(Row {
                    mechanism: name.clone(),
                    file: mech.file.to_string(),
                    output,
                    evaluator: *e,
                    time: t,
                    max_error,
                    median_error,
                    failed_states: errors[j].failed,
                    absolute_states: errors[j].absolute,
                });
            }
        }
    }
    Ok(Report {
        config: config.clone(),
        rows,
        notes,
    })
}

/// The error norm, the timing and the runtime calls, in words (under the table, in JSON).
pub fn method(config: &Config) -> Vec<String> {
    vec![
        format!(
            "states: {} per mechanism, seed {}, q in [-pi, pi], qd in [-3, 3], qdd in [-10, 10]; \
             forward dynamics takes the reference inverse dynamics' torques and tensions",
            config.states, config.seed
        ),
        format!(
            "time: ns per call, median and IQR (25th-75th percentile) of {} samples, each >= {} ms \
             of whole passes over the states, after >= {} ms of warm-up",
            config.samples,
            config.min_sample.as_secs_f64() * 1e3,
            config.warmup.as_secs_f64() * 1e3
        ),
        "error: per state ||x - ref||_inf / ||ref||_inf over the flattened output (forward \
         dynamics: / max(||ref||_inf, size of the terms it sums)), max and median over the \
         states; ref = runtime solver in double-double at the state the evaluator got (for \
         f32, the state rounded to f32)"
            .to_string(),
        "runtime actuation, segment_tensions, bearings, base_reaction: the time of the whole \
         inverse_dynamics call, which gives them all"
            .to_string(),
    ]
}

fn sci(x: f64) -> String {
    if x.is_nan() {
        "-".to_string()
    } else if x.is_infinite() {
        "inf".to_string()
    } else if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x:.1e}")
    }
}

fn ns(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else {
        format!("{x:.1}")
    }
}

impl Row {
    /// What the error columns need said: failures and absolute errors.
    fn remark(&self) -> String {
        let mut r = Vec::new();
        if self.failed_states > 0 {
            r.push(format!("failed at {} states", self.failed_states));
        }
        if self.absolute_states > 0 {
            r.push(format!(
                "absolute: reference 0 at {} states",
                self.absolute_states
            ));
        }
        r.join("; ")
    }
}

impl Report {
    /// The table, aligned for a terminal, with the method and the notes under it.
    pub fn table(&self) -> String {
        let head = [
            "mechanism",
            "output",
            "evaluator",
            "ns/call",
            "IQR (ns)",
            "max rel err",
            "median rel err",
            "",
        ];
        let cells: Vec<[String; 8]> = self
            .rows
            .iter()
            .map(|r| {
                [
                    r.mechanism.clone(),
                    r.output.name().to_string(),
                    r.evaluator.name().to_string(),
                    ns(r.time.median),
                    format!("{}-{}", ns(r.time.p25), ns(r.time.p75)),
                    sci(r.max_error),
                    sci(r.median_error),
                    r.remark(),
                ]
            })
            .collect();
        let mut width = head.map(|h| h.chars().count());
        for c in &cells {
            for (w, x) in width.iter_mut().zip(c) {
                *w = (*w).max(x.chars().count());
            }
        }
        let line = |c: &[String]| {
            let mut s = String::new();
            for (i, (x, w)) in c.iter().zip(width).enumerate() {
                let pad = " ".repeat(w - x.chars().count());
                // Text left, numbers right.
                if (3..7).contains(&i) {
                    s.push_str(&format!("{pad}{x}  "));
                } else {
                    s.push_str(&format!("{x}{pad}  "));
                }
            }
            s.trim_end().to_string() + "\n"
        };
        let mut out = line(&head.map(String::from));
        for c in &cells {
            out.push_str(&line(c));
        }
        out.push('\n');
        for m in method(&self.config).iter().chain(&self.notes) {
            out.push_str(&format!("{m}\n"));
        }
        out
    }

    /// The table as Markdown (what the README shows).
    pub fn markdown(&self) -> String {
        let mut out = String::from(
            "| mechanism | output | evaluator | ns/call | IQR (ns) | max rel. error | median rel. error |\n\
             |---|---|---|---:|---:|---:|---:|\n",
        );
        for r in &self.rows {
            let remark = r.remark();
            out.push_str(&format!(
                "| {} | {} | {} | {} | {}–{} | {}{} | {} |\n",
                r.mechanism,
                r.output.name(),
                r.evaluator.name(),
                ns(r.time.median),
                ns(r.time.p25),
                ns(r.time.p75),
                sci(r.max_error),
                if remark.is_empty() {
                    String::new()
                } else {
                    format!(" ({remark})")
                },
                sci(r.median_error),
            ));
        }
        out
    }

    /// Everything, as JSON: the method, the rows, the notes.
    pub fn json(&self) -> serde_json::Value {
        let num = |x: f64| {
            if x.is_finite() {
                serde_json::json!(x)
            } else {
                serde_json::Value::Null
            }
        };
        serde_json::json!({
            "config": {
                "states": self.config.states,
                "samples": self.config.samples,
                "warmup_ms": self.config.warmup.as_secs_f64() * 1e3,
                "min_sample_ms": self.config.min_sample.as_secs_f64() * 1e3,
                "seed": self.config.seed,
            },
            "method": method(&self.config),
            "error_norm": "max over states of ||x - ref||_inf / ||ref||_inf (forward_dynamics: \
                           denominator at least the size of the terms it sums)",
            "rows": self.rows.iter().map(|r| serde_json::json!({
                "mechanism": r.mechanism,
                "file": r.file,
                "output": r.output.name(),
                "evaluator": r.evaluator.name(),
                "runtime_call": match r.evaluator {
                    Evaluator::RuntimeF64 | Evaluator::RuntimeF32 => Some(r.output.evaluator()),
                    _ => None,
                },
                "ns_per_call": {
                    "min": num(r.time.min),
                    "p25": num(r.time.p25),
                    "median": num(r.time.median),
                    "p75": num(r.time.p75),
                    "max": num(r.time.max),
                },
                "max_rel_error": num(r.max_error),
                "median_rel_error": num(r.median_error),
                "failed_states": r.failed_states,
                "absolute_error_states": r.absolute_states,
            })).collect::<Vec<_>>(),
            "notes": self.notes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let mut v = [4.0, 1.0, 3.0, 2.0, 5.0];
        let s = Spread::of(&mut v);
        assert_eq!(
            (s.min, s.p25, s.median, s.p75, s.max),
            (1.0, 2.0, 3.0, 4.0, 5.0)
        );
        assert_eq!(quantile(&[1.0, 2.0], 0.5), 1.5);
        assert!(quantile(&[], 0.5).is_nan());
    }

    #[test]
    fn the_error_is_max_norm_relative_in_double_double_and_absolute_against_zero() {
        let dd = |v: &[f64]| v.iter().map(|&x| DoubleDouble::from(x)).collect::<Vec<_>>();
        let mut e = Errors::default();
        // ‖(1e-3, 0)‖∞ / ‖(−4, 2)‖∞.
        e.add(Ok(vec![-4.001, 2.0]), &dd(&[-4.0, 2.0]), 0.0);
        // Below one ulp of the reference's f64 rounding: seen because the difference is
        // taken in double-double.
        let r = DoubleDouble::from_parts(1.0, 1e-20);
        e.add(Ok(vec![1.0]), &[r], 0.0);
        // A floor (forward dynamics' term scale) above the result's norm.
        e.add(Ok(vec![1.5]), &dd(&[1.0]), 10.0);
        // Against an exact 0: absolute.
        e.add(Ok(vec![0.0, 2e-20]), &dd(&[0.0, 0.0]), 0.0);
        // A failure, and a NaN.
        e.add(Err("singular".into()), &dd(&[1.0]), 0.0);
        e.add(Ok(vec![f64::NAN]), &dd(&[1.0]), 0.0);
        assert_eq!((e.failed, e.absolute), (1, 1));
        let v = &e.values;
        assert!((v[0] - 0.001 / 4.0).abs() < 1e-15, "{}", v[0]);
        assert!((v[1] - 1e-20).abs() < 1e-30, "{}", v[1]);
        assert_eq!(v[2], 0.05);
        assert_eq!(v[3], 2e-20);
        assert_eq!(v[4], f64::INFINITY);
        let first = v[0];
        let (max, median) = e.max_median();
        assert_eq!(max, f64::INFINITY);
        assert_eq!(median, first);
    }

    #[test]
    fn timing_gives_ordered_positive_figures_per_call() {
        let config = Config {
            samples: 5,
            warmup: Duration::ZERO,
            min_sample: Duration::from_micros(200),
            ..Config::default()
        };
        let mut x = 0u64;
        let s = time(&config, 100, &mut || {
            for i in 0..100u64 {
                x = black_box(x.wrapping_mul(31).wrapping_add(i));
            }
        });
        assert!(0.0 < s.min && s.min <= s.p25 && s.p25 <= s.median);
        assert!(s.median <= s.p75 && s.p75 <= s.max && s.max.is_finite());
    }
}
