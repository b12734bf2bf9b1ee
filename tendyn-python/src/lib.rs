//! `tendyn` for Python: a mechanism's file loaded into a [`Model`] whose methods run the
//! runtime solver of `tendyn-core` on numpy arrays, one state or a batch of states per
//! call (the loop over the batch is in Rust, without the GIL), and generate Rust code with
//! `tendyn-codegen`.
//!
//! Every array a method takes is `(n,)` for one state or `(N, n)` for `N` states; what it
//! returns has the same leading axis. Errors of the mechanism or of a state raise
//! `tendyn.TendynError` with the message the command line prints; arrays of the wrong
//! shape raise `ValueError`.

use numpy::ndarray::{Array, ArrayD, IxDyn};
use numpy::{
    AllowTypeChange, IntoPyArray, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods, PyReadonlyArrayDyn,
    PyUntypedArrayMethods,
};

/// An array argument: anything `numpy.asarray(x, dtype=float)` takes (lists, int arrays).
type Input<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use std::sync::Mutex;
use tendyn_codegen::{available_outputs, Output, Scalar};
use tendyn_core::base_parameters::BaseParameters;
use tendyn_core::{friction, Data, InverseDynamics};

create_exception!(
    tendyn,
    TendynError,
    PyException,
    "A mechanism file that cannot be read or does not validate, a state the solver cannot \
     evaluate, or code that cannot be generated; the message is the command line's (for a \
     file: the item, its line and column, and what would fix it)."
);

fn tendyn_error(e: impl std::fmt::Display) -> PyErr {
    TendynError::new_err(e.to_string())
}

/// From this many states on, a batch is spread over threads (rayon): below it, the
/// threads' start-up and buffers cost more than they save.
const PARALLEL: usize = 256;

/// Which of a state's motor torques and tendon tensions the caller gave (after `q` and
/// `qd` among its inputs), and the zeros that stand for those not given.
struct Actuators {
    given: (bool, bool),
    zeros: (Vec<f64>, Vec<f64>),
}

impl Actuators {
    /// Appends the given arrays to `named`, each with its length per state.
    fn named<'py>(
        model: &tendyn_core::Model<f64>,
        named: &mut Vec<(&'static str, Input<'py>, usize)>,
        motor_torques: Option<Input<'py>>,
        tendon_tensions: Option<Input<'py>>,
    ) -> Actuators {
        let (nm, nt) = (model.motors().len(), model.tendons().len());
        let given = (motor_torques.is_some(), tendon_tensions.is_some());
        named.extend(motor_torques.map(|a| ("motor_torques", a, nm)));
        named.extend(tendon_tensions.map(|a| ("tendon_tensions", a, nt)));
        Actuators {
            given,
            zeros: (vec![0.0; nm], vec![0.0; nt]),
        }
    }

    /// The motor torques and tendon tensions of a state whose inputs after `q` and `qd`
    /// are `rest`.
    fn of<'a>(&'a self, rest: &[&'a [f64]]) -> (&'a [f64], &'a [f64]) {
        let mut rest = rest.iter().copied();
        let mut take = |given: bool, zeros: &'a [f64]| match given {
            true => rest.next().unwrap_or(zeros),
            false => zeros,
        };
        let motors = take(self.given.0, &self.zeros.0);
        (motors, take(self.given.1, &self.zeros.1))
    }
}

/// One name, or a list of them.
#[derive(FromPyObject)]
enum Names {
    One(String),
    Many(Vec<String>),
}

impl Names {
    fn into_vec(self) -> Vec<String> {
        match self {
            Names::One(name) => vec![name],
            Names::Many(names) => names,
        }
    }
}

/// A validated mechanism and the solver's buffers for it, with the text it was validated
/// from: what pickling keeps.
#[pyclass(module = "tendyn", frozen)]
struct Model {
    model: tendyn_core::Model<f64>,
    data: Mutex<Data<f64>>,
    source: String,
}

/// Loads and validates the mechanism file at `path` (a `str` or any path-like object).
#[pyfunction]
fn load(path: std::path::PathBuf) -> PyResult<Model> {
    let text = std::fs::read_to_string(&path).map_err(|e| {
        tendyn_error(tendyn_core::Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    })?;
    loads(&text, &path.display().to_string())
}

/// Validates the mechanism in `text` (RON); `name` stands for the file in messages.
#[pyfunction]
#[pyo3(signature = (text, name = "<string>"))]
fn loads(text: &str, name: &str) -> PyResult<Model> {
    let model = tendyn_core::parse(text).map_err(|e| tendyn_error(format!("{name}: {e}")))?;
    Ok(Model::new(model, text))
}

/// States of one input: `(n,)` (one state) or `(N, n)`, as `count` rows of `width`
/// numbers laid end to end.
struct Batch {
    values: Vec<f64>,
    width: usize,
    count: usize,
    batched: bool,
}

/// The numbers of `array` in logical (row-major) order: one copy when they already lie so
/// in memory, aligned, as numpy's arrays usually do. Any other array of float64 (a view
/// into a record array, a misaligned buffer, broadcast or strided views) is first made
/// so by `numpy.require(a, float64, ["C", "A"])`: a view of it would read the wrong
/// numbers (strides that are no multiple of 8) or misaligned memory. Where that copy
/// cannot be made (a broadcast view of more numbers than memory holds), numpy raises
/// `MemoryError`.
fn numbers(array: &PyReadonlyArrayDyn<'_, f64>) -> PyResult<Vec<f64>> {
    let aligned = (array.data() as usize).is_multiple_of(std::mem::align_of::<f64>());
    if aligned && array.is_c_contiguous() {
        if let Some(values) = array.as_array().as_slice() {
            return Ok(values.to_vec());
        }
    }
    let py = array.py();
    let copy = py
        .import("numpy")?
        .call_method1("require", (array.as_any(), "float64", vec!["C", "A"]))?;
    let copy: PyReadonlyArrayDyn<'_, f64> = copy.extract()?;
    let view = copy.as_array();
    Ok(match view.as_slice() {
        Some(values) => values.to_vec(),
        None => view.iter().copied().collect(),
    })
}

impl Batch {
    /// State `k`'s numbers.
    fn row(&self, k: usize) -> &[f64] {
        &self.values[k * self.width..(k + 1) * self.width]
    }

    fn of(what: &str, array: &PyReadonlyArrayDyn<'_, f64>, n: usize) -> PyResult<Batch> {
        // The shape first: a view is made only of one of the two shapes taken.
        let shape = array.shape().to_vec();
        match shape.as_slice() {
            [k] if *k == n => Ok(Batch {
                values: numbers(array)?,
                width: n,
                count: 1,
                batched: false,
            }),
            [count, k] if *k == n => Ok(Batch {
                values: numbers(array)?,
                width: n,
                count: *count,
                batched: true,
            }),
            _ => {
                let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
                let shown = match dims.len() {
                    1 => format!("({},)", dims[0]),
                    _ => format!("({})", dims.join(", ")),
                };
                Err(PyValueError::new_err(format!(
                    "`{what}` has shape {shown}; expected ({n},) for one state or (N, {n}) \
                     for N states"
                )))
            }
        }
    }

    /// The batches of several inputs, which must agree on batching and on `N`.
    fn all(inputs: Vec<(&str, Batch)>) -> PyResult<(Vec<Batch>, bool, usize)> {
        let batched = inputs[0].1.batched;
        let count = inputs[0].1.count;
        if let Some((what, b)) = inputs
            .iter()
            .find(|(_, b)| b.batched != batched || b.count != count)
        {
            let first = inputs[0].0;
            return Err(PyValueError::new_err(if b.batched != batched {
                format!(
                    "`{what}` and `{first}` mix one state (n,) and a batch (N, n): give both \
                     the same way"
                )
            } else {
                format!("`{what}` has another number of states than `{first}`")
            }));
        }
        Ok((inputs.into_iter().map(|(_, b)| b).collect(), batched, count))
    }
}

/// `values` (each of `shape`) as one array, with an axis over them first when `batched`.
fn stacked<'py>(
    py: Python<'py>,
    values: Vec<Vec<f64>>,
    shape: &[usize],
    batched: bool,
) -> Bound<'py, PyArrayDyn<f64>> {
    let count = values.len();
    stacked_flat(py, values.concat(), count, shape, batched)
}

/// [`stacked`] from the `count` results laid end to end in `flat`, which the array takes
/// over without a copy.
fn stacked_flat<'py>(
    py: Python<'py>,
    flat: Vec<f64>,
    count: usize,
    shape: &[usize],
    batched: bool,
) -> Bound<'py, PyArrayDyn<f64>> {
    let batch = batched.then_some(count);
    let dims: Vec<usize> = batch.into_iter().chain(shape.iter().copied()).collect();
    let array: ArrayD<f64> =
        Array::from_shape_vec(IxDyn(&dims), flat).expect("each state's result has the shape");
    array.into_pyarray(py)
}

/// Appends a state's values of an inverse-dynamics result to `fields[0]`, the field it
/// reads ([`read_guides`]: to the five fields from there).
type Reader = fn(&tendyn_core::Model<f64>, [&[f64]; 3], &InverseDynamics<f64>, &mut [Vec<f64>]);

/// The keys of each guide's quantities in `inverse_dynamics`'s dict, in the order
/// [`read_guides`] writes them; `guide_sticking` is boolean.
const GUIDE_KEYS: [&str; 5] = [
    "guide_wrap_angles",
    "guide_sliding_speeds",
    "guide_directions",
    "guide_sticking",
    "guide_dissipated_powers",
];

/// The bodies whose bearing has friction, in body order (joints, then pulleys): the
/// entries of `bearing_friction` and `sticking`.
fn friction_bodies(model: &tendyn_core::Model<f64>) -> impl Iterator<Item = usize> + '_ {
    (0..model.bodies().len()).filter(|&b| model.bodies()[b].friction.is_some())
}

/// Each guide's quantities at a state, in the fields of [`GUIDE_KEYS`] from `fields[0]`
/// on (a placeholder NaN for the power where there are no segment tensions; the dict then
/// says `None`).
fn read_guides(
    model: &tendyn_core::Model<f64>,
    state: [&[f64]; 3],
    r: &InverseDynamics<f64>,
    fields: &mut [Vec<f64>],
) {
    let guides = friction::guide_states(model, state, r.segment_tensions.as_deref());
    let flag = |b: bool| if b { 1.0 } else { 0.0 };
    fields[0].extend(guides.iter().map(|g| g.wrap_angle));
    fields[1].extend(guides.iter().map(|g| g.sliding_speed));
    fields[2].extend(guides.iter().map(|g| g.direction));
    fields[3].extend(guides.iter().map(|g| flag(g.sticking)));
    fields[4].extend(
        guides
            .iter()
            .map(|g| g.dissipated_power.unwrap_or(f64::NAN)),
    );
}

/// Appends `output` of `r`, which a complete routing always attributes (the only case in
/// which [`inverse_fields`] reads it).
fn attributed(r: &InverseDynamics<f64>, output: Output, field: &mut Vec<f64>) {
    let given = r.extend_flattened(output, field);
    debug_assert!(given, "a complete routing attributes {output:?}");
}

/// A field of [`Model::inverse_dynamics`]'s dict: its key, its shape per state, and its
/// reader (`None` for the guide fields after the first, which [`read_guides`] writes).
type Field = (&'static str, Vec<usize>, Option<Reader>);

/// The fields of [`Model::inverse_dynamics`]'s dict. Segment tensions, bearings and the
/// base reaction only where the routing attributes them (`None` in the dict otherwise).
fn inverse_fields(model: &tendyn_core::Model<f64>) -> Vec<Field> {
    let (n, tendons) = (model.dof(), model.tendons().len());
    let frictional = friction_bodies(model).count();
    let mut fields: Vec<Field> = vec![
        (
            "generalized_forces",
            vec![n],
            Some(|_, _, r, f| f[0].extend(&r.generalized_forces)),
        ),
        (
            "motor_torques",
            vec![model.motors().len()],
            Some(|_, _, r, f| f[0].extend(&r.motor_torques)),
        ),
        (
            "tendon_tensions",
            vec![tendons],
            Some(|_, _, r, f| f[0].extend(&r.tendon_tensions)),
        ),
        (
            "minimal_norm_tensions",
            vec![tendons],
            Some(|_, _, r, f| f[0].extend(&r.minimal_norm_tensions)),
        ),
        (
            "null_space_tensions",
            vec![tendons],
            Some(|_, _, r, f| f[0].extend(&r.null_space_tensions)),
        ),
        (
            "loop_sides",
            vec![model.loops().len(), 2],
            Some(|_, _, r, f| f[0].extend(r.loop_sides.iter().flatten())),
        ),
        (
            "pulley_moments",
            vec![model.bodies().len() - n],
            Some(|_, _, r, f| f[0].extend(r.pulley_demands.iter().map(|(_, m)| m))),
        ),
        (
            "bearing_friction",
            vec![frictional],
            Some(|_, _, r, f| f[0].extend(r.bearing_friction.iter().map(|(_, t)| t))),
        ),
        (
            "sticking",
            vec![frictional],
            Some(|m, _, r, f| {
                let at_rest = |b: usize| if r.sticking.contains(&b) { 1.0 } else { 0.0 };
                f[0].extend(friction_bodies(m).map(at_rest))
            }),
        ),
    ];
    let guides = model.guides().count();
    fields.extend(GUIDE_KEYS.iter().enumerate().map(|(i, &key)| {
        let read: Option<Reader> = (i == 0).then_some(read_guides);
        (key, vec![guides], read)
    }));
    if !model.routing_incomplete() {
        let segments = model.strands().iter().map(|s| s.segments.len()).sum();
        fields.extend([
            (
                "segment_tensions",
                vec![segments],
                Some((|_, _, r, f| attributed(r, Output::SegmentTensions, &mut f[0])) as Reader),
            ),
            (
                "bearings",
                vec![model.bodies().len(), 2, 3],
                Some(|_, _, r, f| attributed(r, Output::Bearings, &mut f[0])),
            ),
            (
                "base_reaction",
                vec![2, 3],
                Some(|_, _, r, f| attributed(r, Output::BaseReaction, &mut f[0])),
            ),
        ]);
    }
    fields
}

impl Model {
    fn new(model: tendyn_core::Model<f64>, source: &str) -> Model {
        let data = Mutex::new(Data::new(&model));
        Model {
            model,
            data,
            source: source.to_string(),
        }
    }

    /// One array per field of `shapes` (each a state's shape), from `evaluate` on the
    /// states of `named`, which appends a state's values to each field's. Without the GIL:
    /// on this model's buffers in order, or, from [`PARALLEL`] states on and where rayon
    /// has more than one thread, one run of consecutive states per thread, each with
    /// buffers of its own (each state's result is the same either way). The arrays take
    /// over the values without a copy where one run made them; several runs' are copied
    /// into the first's. The first failing state raises `TendynError`, naming its row
    /// (`batch row k:`) when the call has more than one state.
    fn fill<'py>(
        &self,
        py: Python<'py>,
        named: Vec<(&str, Input<'_>, usize)>,
        shapes: &[Vec<usize>],
        evaluate: impl Fn(&mut Data<f64>, &[&[f64]], &mut [Vec<f64>]) -> tendyn_core::Result<()>
            + Send
            + Sync,
    ) -> PyResult<Vec<Bound<'py, PyArrayDyn<f64>>>> {
        let (inputs, batched, count) = self.states(named)?;
        // At most four inputs (forward dynamics'), taken without allocation and passed as
        // exactly as many slices as there are inputs.
        assert!(
            inputs.len() <= 4,
            "a method takes at most four state inputs"
        );
        let state = |k: usize| -> [&[f64]; 4] {
            std::array::from_fn(|i| inputs.get(i).map_or(&[][..], |b| b.row(k)))
        };
        let sizes: Vec<usize> = shapes.iter().map(|s| s.iter().product()).collect();
        let threads = match count >= PARALLEL {
            true => rayon::current_num_threads().max(1),
            false => 1,
        };
        let chunk = count.div_ceil(threads).max(1);
        // The values of every field over the run of states from `first`, or its first
        // failing state.
        let run = |data: &mut Data<f64>, first: usize| {
            let states = first..(first + chunk).min(count);
            // Fallibly: a batch whose results exceed memory is an error, not an abort.
            let mut fields: Vec<Vec<f64>> = Vec::new();
            for size in &sizes {
                let mut field = Vec::new();
                let room = size.checked_mul(states.len()).ok_or(());
                room.and_then(|r| field.try_reserve_exact(r).map_err(|_| ()))
                    .map_err(|()| {
                        let e = tendyn_core::Error::State(format!(
                            "the results of {} states need more memory than there is: \
                             give fewer states per call",
                            states.len()
                        ));
                        (first, e)
                    })?;
                fields.push(field);
            }
            for k in states {
                evaluate(data, &state(k)[..inputs.len()], &mut fields).map_err(|e| (k, e))?;
                debug_assert!(
                    (fields.iter().zip(&sizes)).all(|(f, s)| f.len() == (k + 1 - first) * s),
                    "a state's values fill each field's shape"
                );
            }
            Ok(fields)
        };
        let firsts: Vec<usize> = (0..count).step_by(chunk).collect();
        let runs: Vec<Result<Vec<Vec<f64>>, _>> = py.detach(|| {
            if threads > 1 {
                (firsts.par_iter())
                    .map(|&first| run(&mut Data::new(&self.model), first))
                    .collect()
            } else {
                let mut data = self.data.lock().unwrap_or_else(|p| p.into_inner());
                firsts.iter().map(|&first| run(&mut data, first)).collect()
            }
        });
        // Runs are in order of their states, and each stops at its first failure.
        let mut runs: Vec<Vec<Vec<f64>>> = (runs.into_iter())
            .collect::<Result<_, (usize, tendyn_core::Error)>>()
            .map_err(|(k, e)| match count {
                1 => tendyn_error(e),
                _ => tendyn_error(format!("batch row {k}: {e}")),
            })?;
        // Each field's values: the first run's, with the later runs' appended (each run's
        // freed as soon as it is copied).
        Ok((shapes.iter().enumerate())
            .map(|(f, shape)| {
                let mut values = (runs.first_mut())
                    .map(|run| std::mem::take(&mut run[f]))
                    .unwrap_or_default();
                values.reserve((count * sizes[f]).saturating_sub(values.len()));
                for run in runs.iter_mut().skip(1) {
                    values.extend_from_slice(&std::mem::take(&mut run[f]));
                }
                stacked_flat(py, values, count, shape, batched)
            })
            .collect())
    }

    /// [`fill`](Model::fill) for one field of `shape`.
    fn per_state<'py>(
        &self,
        py: Python<'py>,
        named: Vec<(&str, Input<'_>, usize)>,
        shape: &[usize],
        evaluate: impl Fn(&mut Data<f64>, &[&[f64]], &mut Vec<f64>) -> tendyn_core::Result<()>
            + Send
            + Sync,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let evaluate = |data: &mut Data<f64>, s: &[&[f64]], fields: &mut [Vec<f64>]| {
            evaluate(data, s, &mut fields[0])
        };
        let mut arrays = self.fill(py, named, &[shape.to_vec()], evaluate)?;
        Ok(arrays.remove(0))
    }

    fn states(&self, named: Vec<(&str, Input<'_>, usize)>) -> PyResult<(Vec<Batch>, bool, usize)> {
        let batches = named
            .iter()
            .map(|(what, a, n)| Ok((*what, Batch::of(what, a, *n)?)))
            .collect::<PyResult<Vec<_>>>()?;
        Batch::all(batches)
    }
}

#[pymethods]
impl Model {
    /// For `bench/inverse_dynamics_batch.py`: the Rust solver alone on the same states in
    /// this process, `Data::inverse_dynamics` in a loop on one thread with no Python and no
    /// copies, best of `repeats` passes; nanoseconds per state. What a batched
    /// `inverse_dynamics` call is measured against (issue 12's speed goal).
    fn _rust_loop_ns(
        &self,
        py: Python<'_>,
        q: Input<'_>,
        qd: Input<'_>,
        qdd: Input<'_>,
        repeats: usize,
    ) -> PyResult<f64> {
        let n = self.model.dof();
        let (inputs, _, count) = self.states(vec![("q", q, n), ("qd", qd, n), ("qdd", qdd, n)])?;
        let model = &self.model;
        let best = py.detach(|| {
            let mut data = Data::new(model);
            // Warm buffers, as the batch's (the model's own) are after its first call.
            if count > 0 {
                let (q, qd, qdd) = (inputs[0].row(0), inputs[1].row(0), inputs[2].row(0));
                data.inverse_dynamics(model, q, qd, qdd)
                    .map_err(tendyn_error)?;
            }
            let mut best = f64::INFINITY;
            for _ in 0..repeats.max(1) {
                let start = std::time::Instant::now();
                for k in 0..count {
                    let (q, qd, qdd) = (inputs[0].row(k), inputs[1].row(k), inputs[2].row(k));
                    let r = data
                        .inverse_dynamics(model, q, qd, qdd)
                        .map_err(tendyn_error)?;
                    std::hint::black_box(r);
                }
                best = best.min(start.elapsed().as_nanos() as f64);
            }
            Ok::<f64, PyErr>(best)
        })?;
        Ok(best / count.max(1) as f64)
    }

    /// Pickling (and `copy.deepcopy`, and sending a model to another process) keeps the
    /// mechanism's text: unpickling validates it again, with buffers of its own.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let loads = py.import("tendyn")?.getattr("loads")?;
        Ok((loads, (self.source.clone(),)))
    }

    /// The mechanism's name.
    #[getter]
    fn name(&self) -> &str {
        self.model.name()
    }

    /// Number of joint coordinates `n`.
    #[getter]
    fn dof(&self) -> usize {
        self.model.dof()
    }

    /// The joints' (links') names, in joint order.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.model.joint_names().map(String::from).collect()
    }

    /// The open-ended tendons' names, in file order (the columns of `structure_matrix`).
    #[getter]
    fn tendon_names(&self) -> Vec<String> {
        self.model
            .tendons()
            .iter()
            .map(|t| t.name.clone())
            .collect()
    }

    /// The pulleys' names, in file order: the rows of `pulley_moments` and, after the
    /// joints, of `bearings`.
    #[getter]
    fn pulley_names(&self) -> Vec<String> {
        let n = self.model.dof();
        self.model.bodies()[n..]
            .iter()
            .map(|b| b.name.clone())
            .collect()
    }

    /// The bodies whose bearing has friction, in body order (joints, then pulleys): the
    /// entries of `inverse_dynamics`'s `bearing_friction` and `sticking`.
    #[getter]
    fn friction_bodies(&self) -> Vec<String> {
        friction_bodies(&self.model)
            .map(|b| self.model.bodies()[b].name.clone())
            .collect()
    }

    /// Each guide's pulley and tendon, strand by strand in route order: the entries of
    /// `inverse_dynamics`'s `guide_…` arrays.
    #[getter]
    fn guides(&self) -> Vec<(String, String)> {
        (self.model.guides())
            .map(|(s, _, body, _)| {
                let pulley = self.model.bodies()[body].name.clone();
                (pulley, self.model.strands()[s].name.clone())
            })
            .collect()
    }

    /// Each strand's name and number of segments, in order (`segment_tensions` runs
    /// through them; a loop has two strands, `LOOP/ccw` and `LOOP/cw`).
    #[getter]
    fn strands(&self) -> Vec<(String, usize)> {
        self.model
            .strands()
            .iter()
            .map(|s| (s.name.clone(), s.segments.len()))
            .collect()
    }

    /// The loops' names, in file order: the rows of `inverse_dynamics`'s `loop_sides`.
    #[getter]
    fn loop_names(&self) -> Vec<String> {
        self.model.loops().iter().map(|l| l.name.clone()).collect()
    }

    /// The motors' names, in file order.
    #[getter]
    fn motor_names(&self) -> Vec<String> {
        self.model.motors().iter().map(|m| m.name.clone()).collect()
    }

    /// The structure matrix `A` (m), `(n, tendons)`: the tendons' part of `Q` is `A T`
    /// (paper Eqs. 33, 35). The frictionless, constant matrix: where tendons slide over
    /// guides with capstan friction the solver uses the state's `A(σ, q)` instead.
    #[getter]
    fn structure_matrix<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let (n, k) = (self.model.dof(), self.model.tendons().len());
        debug_assert_eq!(self.model.structure_matrix().len(), n);
        stacked(py, self.model.structure_matrix(), &[k], true)
    }

    /// Each pulley's coupling to the joints: name → `(n,)` row, its angle relative to its
    /// carrier per joint angle (paper Eqs. 9-10).
    #[getter]
    fn couplings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for b in &self.model.bodies()[self.model.dof()..] {
            out.set_item(&b.name, b.coupling.clone().into_pyarray(py))?;
        }
        Ok(out)
    }

    /// Inverse dynamics at `(q, qd, qdd)`: a dict of arrays, each with the batch axis first
    /// when the states are batched — `generalized_forces` `(n,)`, `motor_torques`,
    /// `tendon_tensions`, `minimal_norm_tensions` and `null_space_tensions` (file order),
    /// `loop_sides` `(loops, 2)` (`loop_names` order; ccw, cw side at the driving pulley;
    /// a loop is slack where either is negative), `pulley_moments`
    /// (`pulley_names` order), `segment_tensions` (every segment of every strand, `strands`
    /// order), `bearings` `(bodies, 2, 3)` (force, moment; joints then pulleys),
    /// `base_reaction` `(2, 3)`; the last three `None` where the routing cannot attribute
    /// them; `bearing_friction` and `sticking` (bool), one entry per `friction_bodies`;
    /// `guide_wrap_angles`, `guide_sliding_speeds`, `guide_directions`, `guide_sticking`
    /// (bool) and `guide_dissipated_powers` (`None` where the routing cannot attribute
    /// them to guides it has), one entry per `guides` of the model. Units and frames as
    /// docs/outputs.md §3.
    fn inverse_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
        qdd: Input<'py>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (model, n) = (&self.model, self.model.dof());
        let fields = inverse_fields(model);
        let shapes: Vec<Vec<usize>> = fields.iter().map(|(_, shape, _)| shape.clone()).collect();
        // The readers of fields with values (a reader of an empty field reads nothing, and
        // the look-ups of friction's and the guides' cost as much as their output).
        let readers: Vec<(usize, Reader)> = (fields.iter().enumerate())
            .filter(|(_, (_, shape, _))| shape.iter().product::<usize>() > 0)
            .filter_map(|(f, (_, _, read))| read.map(|read| (f, read)))
            .collect();
        let named = vec![("q", q, n), ("qd", qd, n), ("qdd", qdd, n)];
        let arrays = self.fill(py, named, &shapes, |data, s, values| {
            let r = data.inverse_dynamics(model, s[0], s[1], s[2])?;
            for &(f, read) in &readers {
                read(model, [s[0], s[1], s[2]], r, &mut values[f..]);
            }
            Ok(())
        })?;
        let out = PyDict::new(py);
        // Without guides there is nothing to attribute: an empty array, as the command
        // line's `"guides": []`.
        let has_guides = model.guides().next().is_some();
        for ((key, _, _), array) in fields.iter().zip(arrays) {
            match *key {
                "sticking" | "guide_sticking" => {
                    out.set_item(key, array.call_method1("astype", ("bool",))?)?
                }
                "guide_dissipated_powers" if model.routing_incomplete() && has_guides => {
                    out.set_item(key, py.None())?
                }
                _ => out.set_item(key, array)?,
            }
        }
        for key in ["segment_tensions", "bearings", "base_reaction"] {
            if !out.contains(key)? {
                out.set_item(key, py.None())?;
            }
        }
        Ok(out)
    }

    /// The joint-space mass matrix `M(q)` (kg·m²), `(n, n)` per state.
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (model, n) = (&self.model, self.model.dof());
        self.per_state(py, vec![("q", q, n)], &[n, n], |data, s, row| {
            row.extend(data.mass_matrix(model, s[0])?.iter().flatten());
            Ok(())
        })
    }

    /// Coriolis and centrifugal generalized forces `h(q, q̇)` (N·m).
    fn bias<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (model, n) = (&self.model, self.model.dof());
        self.per_state(
            py,
            vec![("q", q, n), ("qd", qd, n)],
            &[n],
            |data, s, row| {
                row.extend(data.bias(model, s[0], s[1])?);
                Ok(())
            },
        )
    }

    /// Gravity generalized forces `g(q)` (N·m).
    fn gravity<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (model, n) = (&self.model, self.model.dof());
        self.per_state(py, vec![("q", q, n)], &[n], |data, s, row| {
            row.extend(data.gravity(model, s[0])?);
            Ok(())
        })
    }

    /// Joint accelerations `q̈` (rad/s²) from motor torques and ground-level tendon
    /// tensions (file order; zeros where not given).
    #[pyo3(signature = (q, qd, motor_torques = None, tendon_tensions = None))]
    fn forward_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
        motor_torques: Option<Input<'py>>,
        tendon_tensions: Option<Input<'py>>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let n = self.model.dof();
        let mut named = vec![("q", q, n), ("qd", qd, n)];
        let actuators = Actuators::named(&self.model, &mut named, motor_torques, tendon_tensions);
        let model = &self.model;
        self.per_state(py, named, &[n], |data, s, row| {
            let (mt, tt) = actuators.of(&s[2..]);
            row.extend(data.forward_dynamics(model, s[0], s[1], mt, tt)?);
            Ok(())
        })
    }

    /// Where `forward_dynamics` is not exact: the bearings with Coulomb friction and the
    /// guides with friction touching their tendon that it takes without friction at `(q,
    /// q̇)`, within the band of rest, where only `q̈` (which it does not know) would direct
    /// them. `{"sticking": (…, friction bodies), "guide_sticking": (…, guides)}` of
    /// booleans, in `friction_bodies` and `guides` order; all false with
    /// `friction_smoothing`.
    fn forward_at_rest<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (model, n) = (&self.model, self.model.dof());
        let shapes = [
            vec![friction_bodies(model).count()],
            vec![model.guides().count()],
        ];
        let flag = |at_rest: bool| if at_rest { 1.0 } else { 0.0 };
        let named = vec![("q", q, n), ("qd", qd, n)];
        let arrays = self.fill(py, named, &shapes, |_, s, values| {
            let (bodies, guides) = tendyn_core::friction::forward_at_rest(model, s[0], s[1]);
            values[0].extend(friction_bodies(model).map(|b| flag(bodies.contains(&b))));
            let guide = |(g, k, _, _): (usize, usize, usize, _)| flag(guides.contains(&(g, k)));
            values[1].extend(model.guides().map(guide));
            Ok(())
        })?;
        let out = PyDict::new(py);
        for (key, array) in ["sticking", "guide_sticking"].into_iter().zip(arrays) {
            out.set_item(key, array.call_method1("astype", ("bool",))?)?;
        }
        Ok(out)
    }

    /// `∂Q/∂q` and `∂Q/∂q̇`, exact (dual numbers through the recursion): `(2, n, n)` per
    /// state, `[0][i][k] = ∂Q_i/∂q_k`, `[1][i][k] = ∂Q_i/∂q̇_k` (`∂Q/∂q̈` is `mass_matrix`).
    fn generalized_forces_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
        qdd: Input<'py>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (model, n) = (&self.model, self.model.dof());
        let named = vec![("q", q, n), ("qd", qd, n), ("qdd", qdd, n)];
        self.per_state(py, named, &[2, n, n], |data, s, row| {
            let d = data.generalized_forces_derivatives(model, s[0], s[1], s[2])?;
            row.extend(d.d_q.iter().chain(&d.d_qd));
            Ok(())
        })
    }

    /// `∂q̈/∂q`, `∂q̈/∂q̇` and `∂q̈/∂u` of forward dynamics side by side, exact: `(n, 2n + m)`
    /// per state, columns `q`, then `q̇`, then `u` (the motor torques, then the tendon
    /// tensions, file order); actuators not given are zero, as in `forward_dynamics`.
    #[pyo3(signature = (q, qd, motor_torques = None, tendon_tensions = None))]
    fn forward_dynamics_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
        motor_torques: Option<Input<'py>>,
        tendon_tensions: Option<Input<'py>>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let n = self.model.dof();
        let (nm, nt) = (self.model.motors().len(), self.model.tendons().len());
        let mut named = vec![("q", q, n), ("qd", qd, n)];
        let actuators = Actuators::named(&self.model, &mut named, motor_torques, tendon_tensions);
        let model = &self.model;
        self.per_state(py, named, &[n, 2 * n + nm + nt], |data, s, row| {
            let (mt, tt) = actuators.of(&s[2..]);
            let d = data.forward_dynamics_derivatives(model, s[0], s[1], mt, tt)?;
            let (cq, cu) = (n, nm + nt);
            for i in 0..n {
                row.extend(&d.d_q[i * cq..(i + 1) * cq]);
                row.extend(&d.d_qd[i * cq..(i + 1) * cq]);
                row.extend(&d.d_u[i * cu..(i + 1) * cu]);
            }
            Ok(())
        })
    }

    /// The identification regressor `Y(q, q̇, q̈)`: `(n, p)` per state, one column per
    /// name of `parameter_names` (`Q = Y π + offset`, `offset` the external wrench's part:
    /// `regressor_offset`).
    fn regressor<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
        qd: Input<'py>,
        qdd: Input<'py>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (model, n) = (&self.model, self.model.dof());
        let p = tendyn_core::regressor::count(model);
        let named = vec![("q", q, n), ("qd", qd, n), ("qdd", qdd, n)];
        self.per_state(py, named, &[n, p], |data, s, row| {
            row.extend(&data.regressor(model, s[0], s[1], s[2])?.y);
            Ok(())
        })
    }

    /// The regressor's offset `Q₀` (N·m), the external wrench's part (zeros without one).
    fn regressor_offset<'py>(
        &self,
        py: Python<'py>,
        q: Input<'py>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (model, n) = (&self.model, self.model.dof());
        self.per_state(py, vec![("q", q, n)], &[n], |data, s, row| {
            let zeros = vec![0.0; n];
            row.extend(&data.regressor(model, s[0], &zeros, &zeros)?.known);
            Ok(())
        })
    }

    /// The regressor's parameters, in its column order (`BODY.m`, `BODY.mx`, …, `BODY.zz`
    /// about the body-frame origin, `BODY.coulomb`, `BODY.viscous`).
    #[getter]
    fn parameter_names(&self) -> Vec<String> {
        let model = &self.model;
        tendyn_core::regressor::parameters(model)
            .iter()
            .map(|p| p.name(model))
            .collect()
    }

    /// The model's own parameter values `π`, in `parameter_names` order.
    fn parameter_values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let values = tendyn_core::regressor::values(&self.model);
        stacked(
            py,
            vec![values],
            &[tendyn_core::regressor::count(&self.model)],
            false,
        )
    }

    /// The base parameters as `tendyn regressor --json` lists them: a list of dicts with
    /// `name`, `value` (the file's), `kept` and `merged`; the base regressor is
    /// `regressor(...)[..., columns]` with `columns = [parameter_names.index(b["kept"])
    /// for b in base_parameters()]`.
    fn base_parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let base = BaseParameters::of(&self.model).map_err(tendyn_error)?;
        let text = tendyn_codegen::report::base_parameters_json(&self.model, &base).to_string();
        py.import("json")?.call_method1("loads", (text,))
    }

    /// The generated Rust source of `outputs` (a name or a list of names as `tendyn
    /// generate --outputs`; the default outputs the mechanism provides when `None`), in
    /// `scalar` `"generic"`, `"f64"` or `"f32"`.
    #[pyo3(signature = (outputs = None, scalar = "generic"))]
    fn generate(&self, outputs: Option<Names>, scalar: &str) -> PyResult<String> {
        let scalar = Scalar::parse(scalar).ok_or_else(|| {
            PyValueError::new_err(format!(
                "unknown scalar `{scalar}`; use generic, f64 or f32"
            ))
        })?;
        let outputs = match outputs {
            None => available_outputs(&self.model),
            Some(names) => (names.into_vec().iter())
                .map(|name| {
                    Output::parse(name).ok_or_else(|| {
                        let all: Vec<&str> = Output::ALL.iter().map(|o| o.name()).collect();
                        PyValueError::new_err(format!(
                            "unknown output `{name}`; the outputs are {}",
                            all.join(", ")
                        ))
                    })
                })
                .collect::<PyResult<Vec<Output>>>()?,
        };
        let generated = tendyn_codegen::generate(&self.model, &outputs, scalar, "python")
            .map_err(tendyn_error)?;
        Ok(generated.source())
    }

    /// The `tendyn check --json` report as a dict: joints, tendons, motors, couplings, the
    /// tension system and its condition, the static torque ranges.
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = tendyn_codegen::report::check_json(&self.model).to_string();
        py.import("json")?.call_method1("loads", (text,))
    }

    fn __repr__(&self) -> String {
        format!(
            "<tendyn.Model {:?}: {} joints, {} tendons, {} motors>",
            self.model.name(),
            self.model.dof(),
            self.model.tendons().len(),
            self.model.motors().len()
        )
    }
}

/// Dynamics of tendon-driven robotic mechanisms (recursive Newton-Euler) from a RON file.
#[pymodule]
fn tendyn(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(loads, m)?)?;
    m.add_class::<Model>()?;
    m.add("TendynError", m.py().get_type::<TendynError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
