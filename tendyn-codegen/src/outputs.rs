//! What can be generated, and how each output is traced: the generic functions of
//! `tendyn-core` run on the symbolic scalar, so the generated code computes what the
//! runtime solver computes (the same recursion, written once). The outputs made of torques
//! about the bodies' axes run it on the regrouped model ([`Model::regrouped`]), whose
//! every such torque is the file model's: the same functions of the state, to round-off.
//!
//! All requested functions are traced into one graph, so the function that returns every
//! requested output shares their common work. Then, per function, the collected closed
//! form ([`crate::closed_form`]) replaces the traced one when it has fewer operations.

use crate::closed_form::{Collector, StateRank};
use crate::expr::{Graph, Id, OpCount, Sym};
use tendyn_core::derivatives;
use tendyn_core::distribution::Problem;
use tendyn_core::dual::Dual;
use tendyn_core::dynamics::{self, Workspace};
use tendyn_core::model::{BodyKind, Model, TensionSystem};
pub use tendyn_core::output::{Output, Param};
use tendyn_core::regressor;
use tendyn_core::{linalg, tension, Real};

/// A Rust expression over the numbers of `value` (a binding holding what the generated
/// function of `output` returns) as an iterator of `&T`, in the order of
/// [`tendyn_core::output`]: what build scripts emit to compare generated code with
/// [`Data::output`](tendyn_core::Data::output).
pub fn flattened_numbers(output: Output, value: &str) -> String {
    match output {
        Output::Actuation => {
            format!("{value}.motor_torques.iter().chain({value}.tendon_tensions.iter())")
        }
        Output::MassMatrix => format!("{value}.iter().flatten()"),
        Output::GeneralizedForcesDerivatives => format!(
            "{value}.value.iter().chain({value}.d_q.iter().flatten()).chain({value}.d_qd.iter().flatten())"
        ),
        Output::ActuationDerivatives => format!(
            "{value}.value.iter().chain({value}.d_q.iter().flatten()).chain({value}.d_qd.iter().flatten()).chain({value}.d_qdd.iter().flatten())"
        ),
        Output::Regressor => format!("{value}.y.iter().flatten().chain({value}.offset.iter())"),
        Output::ForwardDynamicsDerivatives => format!(
            "{value}.value.iter().chain({value}.d_q.iter().flatten()).chain({value}.d_qd.iter().flatten()).chain({value}.d_u.iter().flatten())"
        ),
        Output::Bearings | Output::BaseReaction => format!("{value}.iter().flatten().flatten()"),
        _ => format!("{value}.iter()"),
    }
}

/// How a function's flat list of results is shaped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Shape {
    /// `[T; n]`
    Vector(usize),
    /// `[[T; n]; n]`
    Matrix(usize),
    /// `tendyn_core::distribution::Actuation<[T; motors], [T; tendons]>`: the flat results
    /// are the torques and tensions, then what `status` needs.
    Actuation {
        /// Number of motors.
        motors: usize,
        /// Number of open-ended tendons.
        tendons: usize,
        /// How the generated code decides `status`.
        status: StatusFrom,
    },
    /// `[[[T; 3]; 2]; count]`: force and moment per entry.
    Wrenches(usize),
    /// `tendyn_core::dual::StateJacobians<[T; n], [[T; n]; n]>` (no `actuators`), or
    /// `tendyn_core::dual::ForwardJacobians<[T; n], [[T; n]; n], [[T; actuators]; n]>`:
    /// the flat results are the value, then each Jacobian row by row.
    Jacobians {
        /// Joints `n`.
        n: usize,
        /// Motors and tendons `m`, for forward dynamics' `∂q̈/∂u`.
        actuators: Option<usize>,
    },
    /// `tendyn_core::dual::ActuationJacobians<[T; actuators], [[T; n]; actuators]>`: the
    /// flat results are the value (motor torques, then tendon tensions), then its
    /// Jacobians `∂/∂q`, `∂/∂q̇`, `∂/∂q̈` row by row.
    ActuationJacobians {
        /// Joints `n`.
        n: usize,
        /// Motors and tendons.
        actuators: usize,
        /// [`StatusFrom::Exact`] where the traced values are the distributed ones (no
        /// null space, or one direction in closed form). With several directions,
        /// [`StatusFrom::Solve`]: the tendons' values and rows are the minimal-norm
        /// tensions and their derivatives, which the emitted code distributes with their
        /// derivatives (`Actuation::bounded_with_tangents`: `actuation`'s routine, which
        /// then differentiates its optimum on its active set); [`StatusFrom::SolveAtState`]
        /// adds the state's problem as `actuation` has it, then its derivative along each
        /// of the `3n` coordinates (`q`, then `q̇`, then `q̈`) in the same layout.
        distributed: StatusFrom,
    },
    /// `tendyn_core::mechanism::Regression<[[T; columns]; n], [T; n]>`: the flat results
    /// are `Y` row by row, then the offset `Q₀`.
    Regression {
        /// Joints `n`.
        n: usize,
        /// Parameters `p` (columns of `Y`).
        columns: usize,
    },
}

/// How a generated `actuation` tells a feasible distribution from a best effort.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StatusFrom {
    /// A unique solution, or one null direction without maxima: always feasible.
    Exact,
    /// One null direction with maxima: two more results, the floors' excess over the
    /// maxima along the positive null vector and its scale
    /// (`tendyn_core::distribution::Status::of_line`).
    Line,
    /// Several null directions: the tendon results are the minimal-norm tensions, which
    /// the emitted code distributes by `tendyn_core::distribution::solve` with the
    /// constants of [`Function::distribution`].
    Solve,
    /// Several null directions that depend on the state (guides with capstan friction):
    /// the tendon results are the minimal-norm tensions, followed by the state's
    /// orthonormal null basis over the tendons (`directions` rows of one entry per
    /// tendon), the objective's optimum in its coordinates (`directions`) and each
    /// tendon's `1 / |n_k|` (one per tendon); the emitted code distributes by
    /// `tendyn_core::distribution::AtState` with the floors and maxima of
    /// [`Function::distribution`].
    SolveAtState {
        /// Null directions `d`.
        directions: usize,
    },
}

/// A traced function.
#[derive(Clone, Debug)]
pub struct Function {
    /// The output this function computes.
    pub output: Output,
    /// How its flat results are arranged in its return type.
    pub shape: Shape,
    /// Results, flattened in row-major order, in the form chosen for this function.
    pub results: Vec<Id>,
    /// The same results as traced (before any closed form), numbers gathered in products
    /// (`Graph::shared_products`).
    pub traced: Vec<Id>,
    /// Operations of the traced form.
    pub traced_ops: OpCount,
    /// Which form `results` are.
    pub form: Form,
    /// Operations of `results`.
    pub ops: OpCount,
    /// For `actuation` and `actuation_derivatives` with a null space of more than one
    /// dimension ([`StatusFrom::Solve`], [`StatusFrom::SolveAtState`]): the constants the
    /// emitted code distributes the minimal-norm tensions with.
    pub distribution: Option<Distribution>,
}

/// The form a function is emitted in: whichever has the fewest arithmetic operations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// The recursion as traced.
    Traced,
    /// Collected and expanded in the state ([`crate::closed_form`]).
    ClosedForm,
    /// Forward dynamics: `L D Lᵀ` over the best form of `M` and of the right-hand side.
    SolvedOverParts,
}

impl Form {
    /// How the generated documentation and the command line name it.
    pub fn label(self) -> &'static str {
        match self {
            Form::Traced => "traced recursion",
            Form::ClosedForm => "closed form",
            Form::SolvedOverParts => "L D Lᵀ over the best forms of M and the right-hand side",
        }
    }
}

/// The constants of the fixed-size tension distribution (see [`Function::distribution`]).
/// Where the null space depends on the state ([`StatusFrom::SolveAtState`]) only the floors
/// and maxima are constants, and `null`, `target` and `inverse_length` are empty.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution {
    /// Null-space basis restricted to the tendons: `null[d][k]`.
    pub null: Vec<Vec<f64>>,
    /// Each tendon's floor (N), in file order.
    pub floor: Vec<f64>,
    /// Each tendon's maximum (N); `f64::INFINITY` where a tendon has none.
    pub max: Vec<f64>,
    /// The objective's optimum in null-space coordinates, `λ*_d = Σₖ null[d][k] c_k`.
    pub target: Vec<f64>,
    /// `1 / |n_k|` of each tendon's row of the basis (`Problem::inverse_length`).
    pub inverse_length: Vec<f64>,
    /// The facets of the minimal-norm tensions the bounds allow, normals over the tendons
    /// and supports (`tension::facets`), where the basis is a constant; none where not.
    pub facets: Vec<(Vec<f64>, f64)>,
}

/// Why an output cannot be generated for a mechanism.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unavailable {
    /// The output refused.
    pub output: Output,
    /// Why, in words: it completes ``output `NAME` cannot be generated: ...``.
    pub reason: String,
}

/// Every requested function, traced into one graph.
pub struct Traced {
    /// The one graph every function's results are nodes of.
    pub graph: Graph,
    /// The requested functions, each once, in the order first asked for.
    pub functions: Vec<Function>,
    /// Degrees of freedom `n` (the length of `q`).
    pub dof: usize,
    /// Number of runtime parameters (inputs of every function).
    pub parameters: usize,
    /// Results of every function for `all`, in function order: each function's chosen
    /// form, or every function traced, or (beside bearings, the base reaction or the
    /// regressor) every function traced on the file's bodies: whichever shares most and so
    /// costs least.
    pub all: Vec<Id>,
    /// Operations of `all`.
    pub all_ops: OpCount,
}

impl Traced {
    /// The inputs of `o`'s function: its state inputs, then the runtime parameters if the
    /// mechanism has any.
    pub fn params(&self, o: Output) -> Vec<Param> {
        let mut p = o.params().to_vec();
        if self.parameters > 0 {
            p.push(Param::Parameters);
        }
        p
    }
}

/// Inputs of the traced functions, created once so that every function shares them.
struct Inputs {
    q: Vec<Sym>,
    qd: Vec<Sym>,
    qdd: Vec<Sym>,
    motor_torques: Vec<Sym>,
    tendon_tensions: Vec<Sym>,
}

pub(crate) fn array(name: &str, n: usize) -> Vec<Sym> {
    (0..n).map(|i| Sym::input(format!("{name}[{i}]"))).collect()
}

/// The order in which generated code eliminates a state's tension system where guides
/// have capstan friction: the first of `Elimination::candidates` that holds at every
/// direction of sliding validation checks, if one does.
fn elimination(model: &Model<f64>) -> Option<tension::Elimination> {
    tension::Elimination::candidates(model)
        .into_iter()
        .find(|order| order.holds_while_sliding(model))
}

/// A state's tension system with capstan friction as generated code solves it: by the
/// fixed order of elimination (`check` refuses such a mechanism without one).
fn traced_system<T: Real>(
    order: &Option<tension::Elimination>,
    model: &Model<T>,
    matrix: Vec<Vec<T>>,
) -> tendyn_core::Result<TensionSystem<T>> {
    let order =
        (order.as_ref()).expect("`check` refuses capstan friction without an elimination order");
    Ok(tension::system_traced(model, matrix, order))
}

/// The state's problem of several null directions as the emitted
/// `tendyn_core::distribution::AtState` takes it: its orthonormal null basis over the
/// tendons row by row, the objective's optimum in its coordinates, each tendon's
/// `1 / |n_k|`.
fn problem_at_state<T: Real>(model: &Model<T>, system: &TensionSystem<T>) -> Vec<T> {
    let (d, k) = (system.null_space.len(), model.tendons().len());
    let p = tension::bounds(model, system);
    (0..d)
        .flat_map(|i| (0..k).map(move |j| (i, j)))
        .map(|(i, j)| p.null(i, j))
        .chain((0..d).map(|i| p.target(i)))
        .chain((0..k).map(|j| p.inverse_length(j)))
        .collect()
}

/// Checks that every requested output can be generated for `model`.
pub fn check(model: &Model<f64>, outputs: &[Output]) -> Result<(), Unavailable> {
    check_with(model, outputs, &capstan_elimination(model, outputs))
}

/// Of `candidates`, those [`check`] lets through for `model` (the order of elimination
/// searched once for all of them).
pub fn available(model: &Model<f64>, candidates: &[Output]) -> Vec<Output> {
    let elimination = capstan_elimination(model, candidates);
    (candidates.iter().copied())
        .filter(|o| check_with(model, &[*o], &elimination).is_ok())
        .collect()
}

/// Whether generated code solves the state's tension system for output `o`: where guides
/// have capstan friction, only with an order of elimination.
fn solves_tension_system(o: Output) -> bool {
    matches!(
        o,
        Output::Actuation
            | Output::ActuationDerivatives
            | Output::SegmentTensions
            | Output::Bearings
            | Output::BaseReaction
    )
}

/// The order of elimination of a model whose guides have capstan friction, where one of
/// `outputs` needs it (`None` otherwise, or where no order holds): searched once per
/// generation, for `check` and the trace alike, since each candidate is checked at every
/// direction of sliding.
fn capstan_elimination(model: &Model<f64>, outputs: &[Output]) -> Option<tension::Elimination> {
    let needed = model.has_capstan() && outputs.iter().any(|&o| solves_tension_system(o));
    needed.then(|| elimination(model)).flatten()
}

/// [`check`] with the order of elimination already searched.
fn check_with(
    model: &Model<f64>,
    outputs: &[Output],
    elimination: &Option<tension::Elimination>,
) -> Result<(), Unavailable> {
    for &o in outputs {
        let reason = match o {
            o if solves_tension_system(o) && model.has_capstan() && elimination.is_none() => Some(
                "a guide has capstan friction (`mu > 0`), which makes the tension system \
                     depend on the state, and the order of elimination chosen from its `E` \
                     either leaves a motor or loop side free or meets a zero pivot for some \
                     direction of sliding (the routing is close to uncontrollable) — use the \
                     runtime solver (`tendyn eval`)"
                    .to_string(),
            ),
            // Segment tensions and bearings need the distributed tensions; the base
            // reaction does not (it comes from the tension-free pass), so it stays available.
            Output::SegmentTensions | Output::Bearings if model.system().null_space.len() > 1 => {
                Some(format!(
                    "the tension system has a {}-dimensional null space: generated code \
                     distributes the ground-level tensions (actuation) through a numeric routine, \
                     and does not carry them on to segments and bearings — use the runtime solver",
                    model.system().null_space.len()
                ))
            }
            Output::Actuation | Output::ActuationDerivatives
                if model.motors().is_empty() && model.tendons().is_empty() =>
            {
                Some("the mechanism has neither motors nor tendons".to_string())
            }
            Output::ForwardDynamics | Output::ForwardDynamicsDerivatives
                if model.motors().is_empty() && model.tendons().is_empty() =>
            {
                Some("the mechanism has neither motors nor tendons to drive it".to_string())
            }
            Output::SegmentTensions if model.strands().is_empty() => {
                Some("the mechanism has no tendon segments (no routed tendon or loop)".to_string())
            }
            Output::SegmentTensions | Output::Bearings | Output::BaseReaction
                if model.routing_incomplete() =>
            {
                Some(
                    "the routing is incomplete (an explicit coupling or structure column): where \
                 those transmissions act is unknown"
                        .to_string(),
                )
            }
            _ => None,
        };
        if let Some(reason) = reason {
            return Err(Unavailable { output: o, reason });
        }
    }
    Ok(())
}

/// Traces the requested outputs of `model` (see [`check`] for which are available).
pub fn trace(model: &Model<f64>, outputs: &[Output]) -> Result<Traced, Unavailable> {
    trace_with(model, outputs, Regroup::Yes, |model, params| {
        Ok(model.symbolic(|k| params[k]))
    })
}

/// Whether the outputs made of torques about the bodies' axes alone are traced on the
/// regrouped model ([`Model::regrouped`]: each body's mass that moves with its carrier
/// moved onto it), which gives them exactly for less work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Regroup {
    /// Generated code.
    Yes,
    /// `tendyn equations`, whose lengths are symbols the moved masses' places would not
    /// follow, and whose equations read as the file's bodies.
    No,
}

/// Whether output `o` is made of torques about the bodies' axes alone (the regrouped model
/// gives it exactly), not of bearing forces, the base reaction or per-body parameters.
fn axial(o: Output) -> bool {
    !matches!(
        o,
        Output::Bearings | Output::BaseReaction | Output::Regressor
    )
}

/// The symbolic models an output is traced on.
struct Models<'a> {
    /// The file's bodies.
    full: &'a Model<Sym>,
    /// The regrouped one, where it differs.
    regrouped: Option<&'a Model<Sym>>,
}

impl Models<'_> {
    /// The model `o` is traced on, and whether it is the regrouped one.
    fn of(&self, o: Output) -> (&Model<Sym>, bool) {
        match self.regrouped {
            Some(r) if axial(o) => (r, true),
            _ => (self.full, false),
        }
    }
}

/// [`trace`] of the symbolic model `symbolic` makes of `model` and its parameters' symbols
/// (`tendyn equations` makes lengths and radii symbols too), within the graph's scope.
pub(crate) fn trace_with<E: From<Unavailable>>(
    model: &Model<f64>,
    outputs: &[Output],
    regroup: Regroup,
    mut symbolic: impl FnMut(&Model<f64>, &[Sym]) -> Result<Model<Sym>, E>,
) -> Result<Traced, E> {
    let elimination = capstan_elimination(model, outputs);
    check_with(model, outputs, &elimination)?;
    // Each output once, in the order asked for.
    let mut unique: Vec<Output> = Vec::new();
    for &o in outputs {
        if !unique.contains(&o) {
            unique.push(o);
        }
    }
    let outputs = &unique[..];
    let n = model.dof();
    let (mut graph, results) = Graph::default().scope(|| -> Result<_, E> {
        // Runtime parameters stay symbols: inputs of every function.
        let params = array("params", model.parameters().len());
        let m = symbolic(model, &params)?;
        let regrouped = match (regroup == Regroup::Yes)
            .then(|| model.regrouped())
            .flatten()
        {
            Some(r) => Some(symbolic(&r, &params)?),
            None => None,
        };
        let models = Models {
            full: &m,
            regrouped: regrouped.as_ref(),
        };
        let inputs = Inputs {
            q: array("q", n),
            qd: array("qd", n),
            qdd: array("qdd", n),
            motor_torques: array("motor_torques", m.motors().len()),
            tendon_tensions: array("tendon_tensions", m.tendons().len()),
        };
        let mut ws = Workspace::new(&m);
        let mut shared = Shared {
            elimination: elimination.clone(),
            ..Shared::default()
        };
        let results = outputs
            .iter()
            .map(|&o| (o, trace_one(&models, o, &inputs, &mut ws, &mut shared)))
            .collect::<Vec<_>>();
        // Where bearings, the base reaction or the regressor walk the file's bodies beside
        // outputs that walk the regrouped ones, `all` may share more with every output on
        // the file's bodies: those are traced too, as a third way to share work.
        let mixed = outputs.iter().any(|&o| axial(o)) && outputs.iter().any(|&o| !axial(o));
        let unregrouped = if models.regrouped.is_some() && mixed {
            let full = Models {
                full: &m,
                regrouped: None,
            };
            // The file model's inverse dynamics (bearings', already traced) is kept; the
            // mass matrix and the dual model were the regrouped model's.
            let mut shared = Shared {
                elimination,
                inverse: [shared.inverse[0].take(), None],
                ..Shared::default()
            };
            let roots = outputs
                .iter()
                .flat_map(|&o| trace_one(&full, o, &inputs, &mut ws, &mut shared).1)
                .map(|s| s.0)
                .collect();
            Some(roots)
        } else {
            None
        };
        Ok((results, shared.forward_parts, unregrouped))
    });
    let (results, forward_parts, unregrouped): (_, _, Option<Vec<Id>>) = results?;
    let mut functions = Vec::new();
    let traced: Vec<(Output, Shape, Vec<Id>)> = results
        .into_iter()
        .map(|(o, (shape, r))| (o, shape, r.iter().map(|s| s.0).collect()))
        .collect();
    // The traced form with its numbers gathered, over every function at once so that what
    // they share stays shared (`all`); the closed form expands the roots as traced (see
    // `Graph::shared_products`).
    // Forward dynamics' parts (`M` and the right-hand side) too: solved over, they join
    // the others in `all`.
    let parts: Vec<Id> = forward_parts
        .iter()
        .flat_map(|(mass, rhs)| mass.iter().chain(rhs).copied())
        .collect();
    let every: Vec<Id> = traced
        .iter()
        .flat_map(|t| t.2.iter().copied())
        .chain(parts)
        .chain(unregrouped.iter().flatten().copied())
        .collect();
    let gathered = graph.shared_products(&every);
    let mut gathered = graph.merged_like_terms(&gathered).into_iter();
    /// One function as traced: its roots, and those with numbers gathered with their count.
    struct Trace {
        output: Output,
        shape: Shape,
        roots: Vec<Id>,
        gathered: Vec<Id>,
        ops: OpCount,
    }
    let traced: Vec<Trace> = traced
        .into_iter()
        .map(|(output, shape, roots)| {
            let gathered: Vec<Id> = gathered.by_ref().take(roots.len()).collect();
            let ops = graph.count(&gathered);
            Trace {
                output,
                shape,
                roots,
                gathered,
                ops,
            }
        })
        .collect();
    // One collector for all functions, so that shared subexpressions are expanded once;
    // its limit is the largest function's budget.
    let budget_of = |ops: OpCount| ops.arithmetic() + 32;
    let largest = traced.iter().map(|t| budget_of(t.ops)).max().unwrap_or(0);
    let mut collector = Collector::new(largest);
    // A closed form with more terms than the trace has operations cannot win.
    let mut choose = |graph: &mut Graph, roots: &[Id], traced: &[Id], traced_ops: OpCount| {
        let closed = collector.collect(graph, roots, &StateRank, budget_of(traced_ops));
        match closed.map(|c| (graph.count(&c), c)) {
            Some((ops, c)) if ops.arithmetic() < traced_ops.arithmetic() => {
                (c, Form::ClosedForm, ops)
            }
            _ => (traced.to_vec(), Form::Traced, traced_ops),
        }
    };
    for t in traced {
        let (results, form, ops) = choose(&mut graph, &t.roots, &t.gathered, t.ops);
        let (output, traced_ops) = (t.output, t.ops);
        functions.push(Function {
            output,
            shape: t.shape,
            results,
            traced: t.gathered,
            traced_ops,
            form,
            ops,
            distribution: (matches!(output, Output::Actuation | Output::ActuationDerivatives)
                && model.system().null_space.len() > 1)
                .then(|| distribution_constants(model, !model.has_capstan())),
        });
    }
    // Forward dynamics is `L D Lᵀ` over `M` and the right-hand side: solved over each
    // part's own best form, it can beat both its trace and its closed form as a whole
    // (whose divisions stop the expansion at the solve).
    if let Some((mass, rhs)) = forward_parts {
        let gathered_mass: Vec<Id> = gathered.by_ref().take(mass.len()).collect();
        let gathered_rhs: Vec<Id> = gathered.by_ref().take(rhs.len()).collect();
        let ops = graph.count(&gathered_mass);
        let (mass, ..) = choose(&mut graph, &mass, &gathered_mass, ops);
        let ops = graph.count(&gathered_rhs);
        let (rhs, ..) = choose(&mut graph, &rhs, &gathered_rhs, ops);
        let (g, composed) = graph.scope(|| {
            let mut m: Vec<Sym> = mass.into_iter().map(Sym).collect();
            let mut x: Vec<Sym> = rhs.into_iter().map(Sym).collect();
            linalg::ldlt_solve(&mut m, &mut x);
            x.into_iter().map(|s| s.0).collect::<Vec<Id>>()
        });
        graph = g;
        let f = functions
            .iter_mut()
            .find(|f| f.output == Output::ForwardDynamics)
            .expect("forward dynamics was traced");
        let ops = graph.count(&composed);
        if ops.arithmetic() < f.ops.arithmetic() {
            (f.results, f.form, f.ops) = (composed, Form::SolvedOverParts, ops);
        }
    }
    let chosen: Vec<Id> = functions
        .iter()
        .flat_map(|f| f.results.iter().copied())
        .collect();
    let traced: Vec<Id> = functions
        .iter()
        .flat_map(|f| f.traced.iter().copied())
        .collect();
    let (chosen_ops, traced_ops) = (graph.count(&chosen), graph.count(&traced));
    let (mut all, mut all_ops) = if traced_ops.arithmetic() < chosen_ops.arithmetic() {
        (traced, traced_ops)
    } else {
        (chosen, chosen_ops)
    };
    if unregrouped.is_some() {
        let unregrouped: Vec<Id> = gathered.collect();
        let ops = graph.count(&unregrouped);
        if ops.arithmetic() < all_ops.arithmetic() {
            (all, all_ops) = (unregrouped, ops);
        }
    }
    Ok(Traced {
        graph,
        functions,
        dof: n,
        parameters: model.parameters().len(),
        all,
        all_ops,
    })
}

/// The constants of a many-dimensional distribution, from the model's bounds: with its
/// null space where that is `constant`, the floors and maxima alone where it is not.
fn distribution_constants(model: &Model<f64>, constant: bool) -> Distribution {
    let problem = tension::bounds(model, model.system());
    let (k, d) = (problem.tendons(), problem.directions());
    let d = if constant { d } else { 0 };
    Distribution {
        null: (0..d)
            .map(|i| (0..k).map(|j| problem.null(i, j)).collect())
            .collect(),
        floor: (0..k).map(|j| problem.floor(j)).collect(),
        max: (0..k).map(|j| problem.max(j)).collect(),
        target: (0..d).map(|i| problem.target(i)).collect(),
        inverse_length: if constant {
            (0..k).map(|j| problem.inverse_length(j)).collect()
        } else {
            Vec::new()
        },
        facets: if constant {
            tension::facets(&problem)
        } else {
            Vec::new()
        },
    }
}

/// Recursions several outputs share, traced once: inverse dynamics (behind actuation,
/// segment tensions, bearings and the base reaction) and the mass matrix (behind itself and
/// forward dynamics). Hash-consing would merge the nodes anyway; this saves the tracing work.
#[derive(Default)]
struct Shared {
    /// How a state's tension system is solved where guides have friction (chosen from
    /// the numeric model; `None` only where `check` refuses capstan friction).
    elimination: Option<tension::Elimination>,
    /// On the file's model, and on the regrouped one.
    inverse: [Option<InverseTrace>; 2],
    /// Read by axial outputs only, so on the regrouped model where there is one.
    mass: Option<Vec<Vec<Sym>>>,
    /// Forward dynamics' mass matrix (flat) and right-hand side, to solve again over each
    /// one's best form.
    forward_parts: Option<(Vec<Id>, Vec<Id>)>,
    /// The model on dual numbers and its workspace, for the derivatives (axial outputs
    /// only, like `mass`).
    dual: Option<DualModel>,
}

/// Inverse dynamics as traced, with what `actuation`'s status needs from its distribution.
struct InverseTrace {
    result: dynamics::InverseDynamics<Sym>,
    /// The one-direction distribution's excess and scale, where maxima make it needed.
    line_excess: Option<(Sym, Sym)>,
    /// A state's many-dimensional distribution problem (guides with capstan friction):
    /// its null basis row by row, target and inverse lengths ([`StatusFrom::SolveAtState`]).
    state_problem: Option<(usize, Vec<Sym>)>,
}

/// The model on dual numbers and a workspace for it (the derivatives' trace).
type DualModel = (Model<Dual<Sym>>, Workspace<Dual<Sym>>);

impl Shared {
    fn inverse(
        &mut self,
        (m, regrouped): (&Model<Sym>, bool),
        i: &Inputs,
        ws: &mut Workspace<Sym>,
    ) -> &InverseTrace {
        let elimination = &self.elimination;
        self.inverse[usize::from(regrouped)].get_or_insert_with(|| {
            let (mut line_excess, mut state_problem) = (None, None);
            let (excess, problem) = (&mut line_excess, &mut state_problem);
            // One-dimensional null spaces: the closed form (`max`es), traced; larger ones
            // are distributed by the emitted call (see `Function::distribution`). With
            // guides with friction `E` depends on the state: its solution is traced too,
            // and for several null directions the state's basis is handed to the call.
            let at_state = |model: &Model<Sym>, matrix| traced_system(elimination, model, matrix);
            let distribute = |model: &Model<Sym>, system: &TensionSystem<Sym>, x: &mut [Sym]| {
                let (k, d) = (model.tendons().len(), system.null_space.len());
                if d == 1 && k > 0 {
                    *excess = tension::along_line(model, system, x).excess;
                } else if d > 1 && k > 0 && system.eliminated.is_some() {
                    tension::minimal_norm(model, system, x);
                    *problem = Some((d, problem_at_state(model, system)));
                }
                Ok(())
            };
            let mut result = dynamics::InverseDynamics::empty();
            dynamics::inverse_dynamics(
                m,
                &i.q,
                &i.qd,
                &i.qdd,
                ws,
                at_state,
                distribute,
                &mut result,
            )
            .expect("tracing the distribution cannot fail");
            InverseTrace {
                result,
                line_excess,
                state_problem,
            }
        })
    }

    /// The model on dual numbers (every number a constant) and a workspace for it.
    fn dual(&mut self, m: &Model<Sym>) -> (&Model<Dual<Sym>>, &mut Workspace<Dual<Sym>>) {
        let (model, ws) = self.dual.get_or_insert_with(|| {
            let dual = m.dual();
            let ws = Workspace::new(&dual);
            (dual, ws)
        });
        (model, ws)
    }

    fn mass(&mut self, m: &Model<Sym>, i: &Inputs, ws: &mut Workspace<Sym>) -> Vec<Vec<Sym>> {
        self.mass
            .get_or_insert_with(|| dynamics::mass_matrix(m, &i.q, ws))
            .clone()
    }
}

fn trace_one(
    models: &Models,
    o: Output,
    i: &Inputs,
    ws: &mut Workspace<Sym>,
    shared: &mut Shared,
) -> (Shape, Vec<Sym>) {
    let (m, regrouped) = models.of(o);
    let n = m.dof();
    let zeros = vec![Sym::zero(); n];
    match o {
        Output::GeneralizedForces => {
            let mut out = zeros.clone();
            dynamics::generalized_forces(m, &i.q, &i.qd, &i.qdd, ws, &mut out);
            (Shape::Vector(n), out)
        }
        Output::MassMatrix => {
            let mm = shared.mass(m, i, ws);
            (Shape::Matrix(n), mm.into_iter().flatten().collect())
        }
        Output::Bias => (Shape::Vector(n), dynamics::bias(m, &i.q, &i.qd, ws)),
        Output::Gravity => (Shape::Vector(n), dynamics::gravity(m, &i.q, ws)),
        Output::ForwardDynamics => {
            let rhs = dynamics::forward_dynamics_rhs(
                m,
                &i.q,
                &i.qd,
                &i.motor_torques,
                &i.tendon_tensions,
                ws,
            );
            let mut mm: Vec<Sym> = shared.mass(m, i, ws).into_iter().flatten().collect();
            let behind = dynamics::idlers_behind_capstan(m, &i.q, &i.qd, ws);
            let mut x = rhs;
            if behind.is_empty() {
                shared.forward_parts = Some((
                    mm.iter().map(|s| s.0).collect(),
                    x.iter().map(|s| s.0).collect(),
                ));
                linalg::ldlt_solve(&mut mm, &mut x);
            } else {
                // Idlers behind guides with friction: Woodbury on `M`'s factor, as at run
                // time (`dynamics::accelerations`).
                linalg::ldlt_factor(&mut mm, n);
                dynamics::accelerations(&behind, |b| linalg::ldlt_substitute(&mm, b), &mut x);
            }
            (Shape::Vector(n), x)
        }
        Output::ActuationDerivatives => {
            let order = shared.elimination.clone();
            let (dual, dual_ws) = shared.dual(m);
            // As `Shared::inverse` traces `actuation`: the state's system (capstan
            // friction) by the fixed order of elimination, one null direction in closed
            // form; several: the minimal-norm tensions (and the state's problem, one per
            // seeded coordinate), distributed by the emitted code.
            let (tendons, directions) = (m.tendons().len(), m.system().null_space.len());
            let problems = core::cell::RefCell::new(Vec::new());
            let at_state = |model: &Model<Dual<Sym>>, matrix| traced_system(&order, model, matrix);
            let distribute = |model: &Model<Dual<Sym>>,
                              system: &TensionSystem<Dual<Sym>>,
                              x: &mut [Dual<Sym>]| {
                if tendons > 0 && directions == 1 {
                    tension::along_line(model, system, x);
                } else if tendons > 0 && directions > 1 {
                    tension::minimal_norm(model, system, x);
                    if system.eliminated.is_some() {
                        problems.borrow_mut().push(problem_at_state(model, system));
                    }
                }
                Ok(())
            };
            let d = derivatives::actuation_derivatives(
                dual,
                [&i.q, &i.qd, &i.qdd],
                dual_ws,
                at_state,
                distribute,
            )
            .expect("tracing the distribution cannot fail");
            let problems = problems.into_inner();
            let distributed = match (tendons > 0 && directions > 1, problems.first()) {
                (false, _) => StatusFrom::Exact,
                (true, None) => StatusFrom::Solve,
                (true, Some(_)) => StatusFrom::SolveAtState { directions },
            };
            // The state's problem: its values (the same in every seeded pass), then its
            // derivative along each coordinate.
            let values = problems.first().into_iter().flatten().map(|p| p.value);
            let tangents = problems.iter().flatten().map(|p| p.tangent);
            let actuators = m.motors().len() + tendons;
            let shape = Shape::ActuationJacobians {
                n,
                actuators,
                distributed,
            };
            (
                shape,
                d.flattened()
                    .into_iter()
                    .chain(values)
                    .chain(tangents)
                    .collect(),
            )
        }
        Output::GeneralizedForcesDerivatives => {
            let (dual, dual_ws) = shared.dual(m);
            let d = derivatives::generalized_forces_derivatives(dual, &i.q, &i.qd, &i.qdd, dual_ws);
            (Shape::Jacobians { n, actuators: None }, d.flattened())
        }
        Output::ForwardDynamicsDerivatives => {
            let (dual, dual_ws) = shared.dual(m);
            let d = derivatives::forward_dynamics_derivatives(
                m,
                dual,
                &i.q,
                &i.qd,
                &i.motor_torques,
                &i.tendon_tensions,
                ws,
                dual_ws,
            );
            let actuators = Some(i.motor_torques.len() + i.tendon_tensions.len());
            (Shape::Jacobians { n, actuators }, d.flattened())
        }
        Output::Regressor => {
            let columns = regressor::count(m);
            let mut work = regressor::Work::new(m);
            let (mut y, mut offset) = (vec![Sym::zero(); n * columns], zeros.clone());
            regressor::regressor(m, &i.q, &i.qd, &i.qdd, &mut work, &mut y, &mut offset);
            y.extend(offset);
            (Shape::Regression { n, columns }, y)
        }
        Output::Actuation | Output::SegmentTensions | Output::Bearings | Output::BaseReaction => {
            let r = shared.inverse((m, regrouped), i, ws);
            // Availability was checked before tracing (`check`).
            let flat = r
                .result
                .flattened(o)
                .expect("an output inverse dynamics gives");
            let shape = match o {
                Output::Actuation => {
                    let status = match (&r.state_problem, r.line_excess) {
                        (Some((directions, _)), _) => StatusFrom::SolveAtState {
                            directions: *directions,
                        },
                        _ if m.system().null_space.len() > 1 && !m.tendons().is_empty() => {
                            StatusFrom::Solve
                        }
                        (_, Some(_)) => StatusFrom::Line,
                        _ => StatusFrom::Exact,
                    };
                    Shape::Actuation {
                        motors: m.motors().len(),
                        tendons: m.tendons().len(),
                        status,
                    }
                }
                Output::SegmentTensions => Shape::Vector(flat.len()),
                Output::Bearings => Shape::Wrenches(flat.len() / 6),
                _ => Shape::Wrenches(1),
            };
            // After the torques and tensions, what `status` needs: a one-dimensional
            // distribution's excess and scale, or the state's problem of several directions.
            let actuation = o == Output::Actuation;
            let excess = r.line_excess.filter(|_| actuation);
            let problem = (r.state_problem.as_ref()).filter(|_| actuation);
            let results = flat
                .into_iter()
                .chain(excess.into_iter().flat_map(|(e, s)| [e, s]))
                .chain(problem.into_iter().flat_map(|(_, v)| v.iter().copied()))
                .collect();
            (shape, results)
        }
    }
}

/// Names of what each result of a function is, for documentation (`segment_tensions`:
/// `strand#k`, `bearings`: body names).
pub fn result_labels(model: &Model<f64>, o: Output) -> Vec<String> {
    match o {
        Output::SegmentTensions => model
            .strands()
            .iter()
            .flat_map(|s| (0..s.segments.len()).map(move |k| format!("{}#{k}", s.name)))
            .collect(),
        Output::Bearings => model.bodies().iter().map(|b| b.name.clone()).collect(),
        Output::Actuation => model
            .motors()
            .iter()
            .map(|m| format!("motor {}", m.name))
            .chain(model.tendons().iter().map(|t| format!("tendon {}", t.name)))
            .collect(),
        Output::BaseReaction => vec![
            "force".to_string(),
            "moment about the base origin".to_string(),
        ],
        _ => model.bodies()[..model.dof()]
            .iter()
            .map(|b| b.name.clone())
            .collect(),
    }
}

/// Whether body `b` is a pulley (for documentation of bearings frames).
pub fn is_pulley(model: &Model<f64>, b: usize) -> bool {
    matches!(model.bodies()[b].kind, BodyKind::Pulley { .. })
}
