//! Generates the mechanisms the report measures into `OUT_DIR`, with every output each can
//! provide, generic over the scalar, and a glue module per mechanism (`OUT_DIR/glue.rs`).
//!
//! The mechanisms: the files named by `TENDYN_REPORT_FILES` (absolute paths separated by
//! the platform's path-list separator, `:` on Unix), or the paper's three examples and
//! Example 2 with bearing friction and with capstan friction when it is unset or empty.
//! Mechanism `k` is generated into `OUT_DIR/m{k}/STEM.rs` and wrapped in module `m{k}`, so
//! two files with the same stem do not clash.
//!
//! Per mechanism the glue has, for a scalar `T`: a fixed-size `State<T>`; `pack_*`, which
//! converts the states once and returns a [`Pass`](crate::Pass) that runs one generated
//! function over all of them (no allocation, inputs and results through
//! `std::hint::black_box`); and `eval_*`, which evaluates one output at one state into a
//! flat vector (for the errors).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use tendyn_codegen::outputs::flattened_numbers;
use tendyn_codegen::Output;

const VAR: &str = "TENDYN_REPORT_FILES";

fn main() {
    println!("cargo:rerun-if-env-changed={VAR}");
    if let Err(e) = run() {
        // A build script reports through cargo: the message, then a failing status.
        eprintln!("error: {e}");
        println!("cargo:warning={e}");
        std::process::exit(1);
    }
}

fn files() -> Result<Vec<PathBuf>, String> {
    match std::env::var_os(VAR) {
        Some(v) if !v.is_empty() => std::env::split_paths(&v)
            .filter(|p| !p.as_os_str().is_empty())
            .map(|p| {
                if p.is_absolute() {
                    Ok(p)
                } else {
                    Err(format!(
                        "{VAR}: `{}` is not an absolute path (tendyn report passes absolute paths)",
                        p.display()
                    ))
                }
            })
            .collect(),
        _ => {
            let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/mechanisms");
            Ok([
                "example1_endless",
                "example2_open_ended",
                "example3_stanford_jpl",
                "example2_friction",
                "example2_capstan",
            ]
            .iter()
            .map(|n| root.join(format!("{n}.ron")))
            .collect())
        }
    }
}

fn run() -> Result<(), String> {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);
    let files = files()?;
    let mut glue = String::new();
    let mut registry = String::from(
        "/// Every mechanism compiled into this crate (see `build.rs`), in order.\npub const MECHANISMS: &[Mechanism] = &[\n",
    );
    for (k, path) in files.iter().enumerate() {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| format!("{shown}: {e}"))?;
        let model = tendyn_core::load(path).map_err(|e| format!("{shown}: {e}"))?;
        let dir = out.join(format!("m{k}"));
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let written = tendyn_codegen::Builder::new()
            .mechanism(path)
            .out_dir(&dir)
            .generate()
            .map_err(|e| e.to_string())?;
        let generated = written
            .first()
            .and_then(|p| p.file_name())
            .and_then(|n| n.to_str())
            .ok_or_else(|| format!("{shown}: nothing was generated"))?
            .to_string();
        write_if_changed(&dir.join("mechanism.ron"), &text)?;
        let outputs = tendyn_codegen::available_outputs(&model);
        glue.push_str(&module(k, &generated, &model, &outputs));
        let variants: Vec<String> = outputs.iter().map(|o| format!("Output::{o:?}")).collect();
        writeln!(
            registry,
            "    Mechanism {{ name: {name:?}, file: {shown:?}, ron: m{k}::RON, outputs: &[{outs}], \
             pack_f64: m{k}::pack::<f64>, pack_f32: m{k}::pack::<f32>, \
             eval_f64: m{k}::eval::<f64>, eval_f32: m{k}::eval::<f32> }},",
            name = model.name(),
            outs = variants.join(", "),
        )
        .unwrap();
    }
    registry.push_str("];\n");
    write_if_changed(&out.join("glue.rs"), &format!("{glue}\n{registry}"))
}

/// The call of output `o` on state `s` (fields `q`, `qd`, `qdd`, `mt`, `tt`, `p`), with
/// `wrap` applied to every argument, and how its result is flattened into `v: Vec<f64>`.
fn call(o: Output, params: bool, wrap: &str) -> (String, String) {
    let arg = |f: &str| {
        if wrap.is_empty() {
            format!("&s.{f}")
        } else {
            format!("{wrap}(&s.{f})")
        }
    };
    let mut args: Vec<String> = match o {
        Output::MassMatrix | Output::Gravity => vec![arg("q")],
        Output::Bias => vec![arg("q"), arg("qd")],
        Output::ForwardDynamics => vec![arg("q"), arg("qd"), arg("mt"), arg("tt")],
        _ => vec![arg("q"), arg("qd"), arg("qdd")],
    };
    if params {
        args.push(arg("p"));
    }
    let flatten = format!(
        "{}.map(|x| x.to_f64()).collect()",
        flattened_numbers(o, "r")
    );
    (
        format!("code::{}::<T>({})", o.name(), args.join(", ")),
        flatten,
    )
}

fn module(
    k: usize,
    generated: &str,
    model: &tendyn_core::Model<f64>,
    outputs: &[Output],
) -> String {
    let (n, nm, nt, np) = (
        model.dof(),
        model.motors().len(),
        model.tendons().len(),
        model.parameters().len(),
    );
    let params = np > 0;
    let mut passes = String::new();
    let mut loops = String::new();
    let mut evals = String::new();
    for &o in outputs {
        // One function per output's loop, compiled on its own (as a benchmark's closure
        // is), so that inlining the generated function does not depend on the others.
        // The states hold only what the function reads, as a benchmark's would.
        let (timed, _) = call(o, params, "black_box");
        let (ty, field) = match o {
            Output::ForwardDynamics => ("Forward", "forward"),
            _ => ("Motion", "motion"),
        };
        writeln!(
            loops,
            "    #[inline(never)]\n    fn pass_{name}<T: Numeric>(states: &[{ty}<T>]) {{\n        \
             for s in states {{\n            black_box({timed});\n        }}\n    }}\n",
            name = o.name()
        )
        .unwrap();
        writeln!(
            passes,
            "            Output::{o:?} => {{ pass_{name}(&self.{field}); true }}",
            name = o.name()
        )
        .unwrap();
        let (plain, flatten) = call(o, params, "");
        writeln!(
            evals,
            "        Output::{o:?} => {{ let r = {plain}; {flatten} }}",
        )
        .unwrap();
    }
    format!(
        r#"
/// `{name}`: generated code and glue.
#[allow(clippy::all, unreachable_patterns)]
pub mod m{k} {{
    /// The code `tendyn-codegen` generated for it: every output it can provide, generic.
    #[allow(dead_code, unused_imports, clippy::all)]
    pub mod code {{
        include!(concat!(env!("OUT_DIR"), "/m{k}/{generated}"));
    }}
    use crate::{{Inputs, Output, Pass}};
    use std::hint::black_box;
    use tendyn_core::Numeric;

    /// The mechanism file's text, as generated.
    pub const RON: &str = include_str!(concat!(env!("OUT_DIR"), "/m{k}/mechanism.ron"));

    /// One state in fixed-size arrays, as the generated functions take it.
    #[derive(Clone, Copy)]
    #[allow(dead_code)] // `p` without runtime parameters
    pub struct State<T> {{
        q: [T; {n}],
        qd: [T; {n}],
        qdd: [T; {n}],
        mt: [T; {nm}],
        tt: [T; {nt}],
        p: [T; {np}],
    }}

    fn array<T: Numeric, const L: usize>(v: &[f64]) -> Option<[T; L]> {{
        let v: &[f64; L] = v.try_into().ok()?;
        Some(v.map(T::from_f64))
    }}

    fn state<T: Numeric>(s: &Inputs) -> Option<State<T>> {{
        Some(State {{
            q: array(&s.q)?,
            qd: array(&s.qd)?,
            qdd: array(&s.qdd)?,
            mt: array(&s.motor_torques)?,
            tt: array(&s.tendon_tensions)?,
            p: array(&s.parameters)?,
        }})
    }}

    /// What every function but forward dynamics reads.
    #[allow(dead_code)]
    struct Motion<T> {{
        q: [T; {n}],
        qd: [T; {n}],
        qdd: [T; {n}],
        p: [T; {np}],
    }}

    /// What forward dynamics reads.
    #[allow(dead_code)]
    struct Forward<T> {{
        q: [T; {n}],
        qd: [T; {n}],
        mt: [T; {nm}],
        tt: [T; {nt}],
        p: [T; {np}],
    }}

    struct Packed<T> {{
        motion: Vec<Motion<T>>,
        forward: Vec<Forward<T>>,
    }}

{loops}
    impl<T: Numeric> Pass for Packed<T> {{
        #[allow(unused_variables)]
        fn pass(&self, output: Output) -> bool {{
            match output {{
{passes}            _ => false,
            }}
        }}
    }}

    /// The states in `T`, ready to be timed; `None` if a state has the wrong sizes.
    pub fn pack<T: Numeric + 'static>(states: &[Inputs]) -> Option<Box<dyn Pass>> {{
        let states: Vec<State<T>> = states.iter().map(state).collect::<Option<_>>()?;
        Some(Box::new(Packed {{
            motion: states
                .iter()
                .map(|s| Motion {{ q: s.q, qd: s.qd, qdd: s.qdd, p: s.p }})
                .collect(),
            forward: states
                .iter()
                .map(|s| Forward {{ q: s.q, qd: s.qd, mt: s.mt, tt: s.tt, p: s.p }})
                .collect(),
        }}))
    }}

    /// `output` in `T` at one state, flattened, in f64; `None` if it is not generated here
    /// or the state has the wrong sizes.
    #[allow(unused_variables)]
    pub fn eval<T: Numeric>(output: Output, s: &Inputs) -> Option<Vec<f64>> {{
        let s = state::<T>(s)?;
        Some(match output {{
{evals}        _ => return None,
        }})
    }}
}}
"#,
        name = model.name(),
    )
}

/// Rewrites a file only when its text changes, so an unchanged set of mechanisms
/// recompiles nothing.
fn write_if_changed(path: &Path, text: &str) -> Result<(), String> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}
