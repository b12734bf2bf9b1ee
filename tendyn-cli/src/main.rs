//! The `tendyn` command line: check a mechanism, evaluate its dynamics (inverse and
//! forward), identify its parameters (`regressor`, `identify`), draw it, export it to
//! MuJoCo, generate code or its equations, run the demo, and measure error against run
//! time (`report`, through cargo).

mod draw;
mod identified;
mod mjcf;

use clap::{Parser, Subcommand};
use std::process::ExitCode;
use tendyn_codegen::report::{self, JointSpace};
use tendyn_core::base_parameters::BaseParameters;
use tendyn_core::physical_consistency::identify_consistent;
use tendyn_core::{Data, InverseDynamics, Model};

#[derive(Parser)]
#[command(
    name = "tendyn",
    version,
    about = "Dynamics of tendon-driven mechanisms (recursive Newton-Euler)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Joint positions and velocities, comma-separated, in joint order.
#[derive(clap::Args)]
struct State {
    /// Joint angles q1,...,qn (rad), comma-separated, link 1 first.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = number,
        value_name = "Q1,..."
    )]
    q: Vec<f64>,
    /// Joint velocities (rad/s), comma-separated, link 1 first.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = number,
        value_name = "QD1,..."
    )]
    qd: Vec<f64>,
}

/// Joint accelerations, comma-separated, in joint order.
#[derive(clap::Args)]
struct Acceleration {
    /// Joint accelerations (rad/s²), comma-separated, link 1 first.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = number,
        value_name = "QDD1,..."
    )]
    qdd: Vec<f64>,
}

#[derive(Subcommand)]
enum Command {
    /// Validate a mechanism file and print what the routing implies.
    Check {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        /// Print one JSON object (docs/outputs.md §1) instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Evaluate inverse dynamics, M, h and g at a state: give it by --q, --qd and --qdd
    /// (each required, n numbers), or give many by --states.
    Eval {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        #[command(flatten)]
        state: State,
        #[command(flatten)]
        acceleration: Acceleration,
        /// A CSV file with one state per line: q..., qd..., qdd... (3n numbers).
        #[arg(long)]
        states: Option<String>,
        /// Print one JSON object per state.
        #[arg(long)]
        json: bool,
        /// With --json: add `dQ_dq` and `dQ_dqd` (n × n, arrays of rows; docs/outputs.md §3).
        #[arg(long, requires = "json")]
        derivatives: bool,
        /// With --json: add the base regressor at the state, the base parameters with the
        /// file's values and the offset of the external wrench (docs/outputs.md §6d).
        #[arg(long, requires = "json")]
        regressor: bool,
        /// With --states: print a CSV table instead of JSON lines (a header, then per
        /// state q, qd, qdd, generalized forces, motor torques and tendon tensions).
        #[arg(long, requires = "states", conflicts_with = "json")]
        csv: bool,
    },
    /// The identification regressor's parameters and the mechanism's base parameters: the
    /// combinations of masses, first moments, inertias and bearing friction that the
    /// generalized forces can tell apart, with the file's values (docs/outputs.md §6d).
    Regressor {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Estimate the base parameters from measured motion by least squares, with the
    /// standard deviation of each estimate and the residual (docs/outputs.md §6d).
    Identify {
        /// The mechanism's RON file (docs/format.md): its structure, and its values to compare.
        file: String,
        /// A CSV file with one sample per line: q..., qd..., qdd..., then the motor torques
        /// (file order) and the open-ended tendons' ground-level tensions (file order);
        /// with --forces, the n generalized forces instead. Lines starting with `#` and a
        /// first line that is not numbers (a header) are skipped.
        #[arg(long)]
        data: String,
        /// The measured columns are generalized forces, one per joint.
        #[arg(long)]
        forces: bool,
        /// Also estimate every body's mass properties, constrained to be physically
        /// consistent (positive mass, a valid inertia), and the base parameters they give.
        #[arg(long)]
        consistent: bool,
        /// With --consistent: write the mechanism's file with every body's mass properties
        /// (and friction) replaced by the estimate here, the rest as written.
        #[arg(long, requires = "consistent")]
        write: Option<String>,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Forward dynamics: joint accelerations from motor torques and tendon tensions.
    Forward {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        #[command(flatten)]
        state: State,
        /// One torque per motor (N·m), comma-separated, in the file's order of `motors`.
        #[arg(
            long,
            value_delimiter = ',',
            allow_hyphen_values = true,
            value_parser = number,
                value_name = "TAU1,..."
        )]
        torques: Vec<f64>,
        /// One ground-level tension per open-ended tendon (N), comma-separated, in the
        /// file's order of `tendons`.
        #[arg(
            long,
            value_delimiter = ',',
            allow_hyphen_values = true,
            value_parser = number,
                value_name = "T1,..."
        )]
        tensions: Vec<f64>,
        /// Print `{"mechanism": NAME, "qdd": [...], "sticking": [...], "sticking_guides":
        /// [...]}` instead of text (docs/outputs.md §5).
        #[arg(long)]
        json: bool,
        /// With --json: add `dqdd_dq`, `dqdd_dqd` (n × n) and `dqdd_du` (n × m, u the
        /// torques then the tensions), as arrays of rows (docs/outputs.md §5).
        #[arg(long, requires = "json")]
        derivatives: bool,
    },
    /// Draw the mechanism at a state as SVG: links, joints, pulleys to scale, every tendon
    /// segment in its strand's colour, exits and anchors, a scale bar and a legend.
    ///
    /// The state drawn is --q (default: all 0); --qd and --qdd (default 0) matter only with
    /// --tensions.
    Draw {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        #[command(flatten)]
        state: State,
        #[command(flatten)]
        acceleration: Acceleration,
        /// The plane it is seen in (xy: along the first joint's axis in a DH chain).
        #[arg(long, value_enum, default_value = "xy")]
        view: draw::View,
        /// Draw each segment as wide as its tension at (q, qd, qdd) (inverse dynamics).
        #[arg(long)]
        tensions: bool,
        /// The SVG file to write.
        #[arg(short = 'o', long)]
        out: String,
    },
    /// Export the mechanism to another tool's format (MuJoCo's MJCF; docs/outputs.md §6c).
    Export {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        /// Write MJCF (the only format so far).
        #[arg(long, required = true)]
        mjcf: bool,
        /// The file to write.
        #[arg(short = 'o', long)]
        out: String,
    },
    /// Generate straight-line Rust for a mechanism's dynamics.
    Generate {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        /// Comma-separated outputs: generalized_forces, actuation, mass_matrix, bias,
        /// gravity, forward_dynamics, segment_tensions, bearings, base_reaction (the
        /// default: each of these the mechanism can provide), and only when named
        /// generalized_forces_derivatives, forward_dynamics_derivatives,
        /// actuation_derivatives, regressor.
        #[arg(long, value_delimiter = ',')]
        outputs: Vec<String>,
        /// generic (over tendyn_core::Real), f64 or f32.
        #[arg(long, default_value = "generic")]
        scalar: String,
        /// Write the source here instead of to standard output.
        #[arg(short = 'o', long)]
        out: Option<String>,
    },
    /// Print the closed-form equations in readable notation (beside the paper's Eqs. 26-30,
    /// 33-35).
    Equations {
        /// The mechanism's RON file (docs/format.md).
        file: String,
        /// Comma-separated outputs (default: generalized_forces, and actuation when there
        /// are motors or tendons).
        #[arg(long, value_delimiter = ',')]
        outputs: Vec<String>,
    },
    /// Check and evaluate the paper's three built-in examples.
    Demo,
    /// Error against run time: generated code and the runtime solver, f64 and f32.
    ///
    /// For each mechanism and each output its generated code provides, times four
    /// evaluators (generated f64, generated f32, runtime solver f64, runtime solver f32) over
    /// 1,024 seeded random states (ns per call: median and interquartile range of 31
    /// samples, after a warm-up) and measures their error against the runtime solver in
    /// double-double: per state ‖x − ref‖∞ / ‖ref‖∞ of the output (forward dynamics:
    /// relative to the size of the terms it sums), max and median over the states.
    /// Prints a table (or JSON) and writes an SVG chart of error against time.
    ///
    /// The generated code must be compiled to be timed: this runs
    /// `cargo run --release -p tendyn-report` in the tendyn source tree this binary was
    /// built from, so it needs cargo and that tree. The first run compiles for a few
    /// minutes; the measurement takes about a minute for the default mechanisms (progress
    /// on stderr). Pin it to one core for steadier figures: `taskset -c 0 tendyn report`.
    Report {
        /// Mechanism files (default: the paper's three examples and Example 2 with bearing
        /// and with capstan friction).
        files: Vec<String>,
        /// Print JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// Print the table as Markdown.
        #[arg(long, conflicts_with = "json")]
        markdown: bool,
        /// Where to write the SVG chart [default: target/tendyn-report.svg in the source tree].
        #[arg(long)]
        svg: Option<String>,
        /// Random states per mechanism [default: 1024].
        #[arg(long)]
        states: Option<usize>,
        /// Timing samples per evaluator [default: 31].
        #[arg(long)]
        samples: Option<usize>,
        /// Minimum warm-up per evaluator, in ms [default: 300].
        #[arg(long)]
        warmup_ms: Option<u64>,
    },
}

/// Loads and validates a mechanism file. The error starts with the file's path once: a
/// file that cannot be read names it already.
fn load(file: &str) -> Result<Model<f64>, String> {
    tendyn_core::load(file).map_err(|e| load_error(file, e))
}

fn load_error(file: &str, e: tendyn_core::Error) -> String {
    match e {
        tendyn_core::Error::Io { .. } => e.to_string(),
        _ => format!("{file}: {e}"),
    }
}

/// One number of a comma-separated list such as `--q`. Spaces around it are allowed, as
/// in `--states` files (`--q "0.1, 0.2"`).
fn number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    t.parse()
        .map_err(|_| format!("`{t}` is not a number (expected e.g. 0.25, -1e-3)"))
}

/// The arguments with every one that ends in a comma joined to the next, unless that is a
/// flag: unquoted, the shell makes `--q 0.1, 0.2` two arguments, `0.1,` and `0.2`, which
/// are one list. Nothing after a `--` is touched.
fn join_continued(args: impl Iterator<Item = std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let mut out: Vec<std::ffi::OsString> = Vec::new();
    let (mut continued, mut verbatim) = (false, false);
    for a in args {
        let text = a.to_str().unwrap_or("");
        // A long flag, or a short one (`-o`); a negative number is no flag.
        let short = text.len() == 2
            && text.starts_with('-')
            && text[1..].chars().all(|c| c.is_ascii_alphabetic());
        let flag = text.starts_with("--") || short;
        match out.last_mut() {
            Some(last) if continued && !flag => last.push(&a),
            Some(last) if continued => {
                // A list that ends in a comma before a flag ends there.
                if let Some(ended) = last.to_str().map(|t| t.trim_end_matches(',').to_owned()) {
                    *last = ended.into();
                }
                out.push(a.clone());
            }
            _ => out.push(a.clone()),
        }
        verbatim |= text == "--";
        continued = !verbatim && text.ends_with(',');
    }
    out
}

/// A line to standard error: what was written where, or why nothing was. Where no one
/// reads it any more (`2>&1 | head -1`), it is dropped: the work is done either way, and
/// the exit status still says how it went (`eprintln!` would panic).
macro_rules! note {
    ($($t:tt)*) => {{
        use std::io::Write;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}

/// Writes to stdout. A reader that went away (`tendyn demo | head`) ends the program
/// quietly, with success; any other failure (a full disk behind `> out.rs`) is an error,
/// exit status 1, so that a script does not take a partial output for a whole one.
fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        note!("error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

macro_rules! say {
    ($($t:tt)*) => { emit(&format!("{}\n", format!($($t)*))) };
}

fn main() -> ExitCode {
    match run(Cli::parse_from(join_continued(std::env::args_os()))) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            note!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Check { file, json } => {
            // A routing that fails its checks is shown as far as it was derived.
            let m = tendyn_core::load(&file).map_err(|e| {
                if let (Some(system), false) = (e.implied(), json) {
                    emit(&report::implied_text(system));
                }
                load_error(&file, e)
            })?;
            if json {
                say!("{}", report::check_json(&m));
            } else {
                emit(&report::check_text(&m));
            }
            Ok(())
        }
        Command::Demo => {
            for (file, text) in tendyn_codegen::report::BUILT_IN {
                let m = tendyn_core::parse(text).map_err(|e| format!("{file}: {e}"))?;
                emit(&report::check_text(&m));
                let n = m.dof();
                let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
                let qd: Vec<f64> = (0..n).map(|i| 1.0 - 0.5 * i as f64).collect();
                let qdd: Vec<f64> = (0..n).map(|i| 2.0 + i as f64).collect();
                say!("inverse dynamics at q = {q:?}, qd = {qd:?}, qdd = {qdd:?}:");
                emit(&eval_text(&m, &q, &qd, &qdd)?);
                say!("");
            }
            Ok(())
        }
        Command::Eval {
            file,
            state: State { q, qd },
            acceleration: Acceleration { qdd },
            states,
            json,
            derivatives,
            regressor,
            csv,
        } => {
            let m = load(&file)?;
            let n = m.dof();
            let mut solver = Data::new(&m);
            let base = match regressor {
                true => Some(BaseParameters::of(&m).map_err(|e| e.to_string())?),
                false => None,
            };
            let eval_json = |q: &[f64], qd: &[f64], qdd: &[f64]| -> Result<_, String> {
                let mut out = eval_json(&m, q, qd, qdd)?;
                if derivatives {
                    let d = Data::new(&m)
                        .generalized_forces_derivatives(&m, q, qd, qdd)
                        .map_err(|e| e.to_string())?;
                    out["dQ_dq"] = rows(&d.d_q, n);
                    out["dQ_dqd"] = rows(&d.d_qd, n);
                }
                if let Some(base) = &base {
                    let r = Data::new(&m)
                        .regressor(&m, q, qd, qdd)
                        .map_err(|e| e.to_string())?
                        .clone();
                    let extra = report::regressor_at_json(&m, base, &r);
                    let (o, extra) = (out.as_object_mut(), extra.as_object());
                    if let (Some(o), Some(extra)) = (o, extra) {
                        o.extend(extra.clone());
                    }
                }
                Ok(out)
            };
            match states {
                None => {
                    if json {
                        say!("{}", eval_json(&q, &qd, &qdd)?);
                    } else {
                        emit(&eval_text(&m, &q, &qd, &qdd)?);
                    }
                }
                Some(path) => {
                    if !(q.is_empty() && qd.is_empty() && qdd.is_empty()) {
                        return Err("give either --states or --q/--qd/--qdd, not both".into());
                    }
                    // Every line is read and checked before anything is printed.
                    let rows = csv_rows(&path, 3 * n, "q, qd, qdd")?;
                    if csv {
                        say!("{}", report::inverse_csv_header(&m));
                    }
                    for (line, vals) in rows {
                        let (q, qd, qdd) = (&vals[..n], &vals[n..2 * n], &vals[2 * n..]);
                        let at = |e: String| format!("{path}:{line}: {e}");
                        if csv {
                            let r = solver
                                .inverse_dynamics(&m, q, qd, qdd)
                                .map_err(|e| at(e.to_string()))?;
                            say!("{}", report::inverse_csv_row(q, qd, qdd, r));
                        } else {
                            say!("{}", eval_json(q, qd, qdd).map_err(at)?);
                        }
                    }
                }
            }
            Ok(())
        }
        Command::Regressor { file, json } => {
            let m = load(&file)?;
            let base = BaseParameters::of(&m).map_err(|e| e.to_string())?;
            if json {
                say!("{}", report::regressor_json(&m, &base));
            } else {
                emit(&report::regressor_text(&m, &base));
            }
            Ok(())
        }
        Command::Identify {
            file,
            data,
            forces,
            consistent,
            write,
            json,
        } => {
            let m = load(&file)?;
            let samples = identification_samples(&m, &data, forces)?;
            let base = BaseParameters::of(&m).map_err(|e| e.to_string())?;
            if consistent {
                let c =
                    identify_consistent(&m, &base, &samples).map_err(|e| format!("{data}: {e}"))?;
                if let Some(out) = &write {
                    let text =
                        std::fs::read_to_string(&file).map_err(|e| format!("{file}: {e}"))?;
                    let identified = identified::with_estimate(&text, &m, &c)
                        .map_err(|e| format!("{out}: {e}"))?;
                    tendyn_codegen::builder::write_atomically(out.as_ref(), &identified)
                        .map_err(|e| format!("{out}: {e}"))?;
                    note!(
                        "wrote `{}` with the identified mass properties to {out}",
                        m.name()
                    );
                }
                if json {
                    say!("{}", report::consistent_json(&m, &base, &c));
                } else {
                    emit(&report::consistent_text(&m, &base, &c));
                }
                return Ok(());
            }
            let id = tendyn_core::identification::identify(&m, &base, &samples)
                .map_err(|e| format!("{data}: {e}"))?;
            if json {
                say!("{}", report::identification_json(&m, &base, &id));
            } else {
                emit(&report::identification_text(&m, &base, &id));
            }
            Ok(())
        }
        Command::Draw {
            file,
            state: State { q, qd },
            acceleration: Acceleration { qdd },
            view,
            tensions,
            out,
        } => {
            let m = load(&file)?;
            let zeros = |v: Vec<f64>| if v.is_empty() { vec![0.0; m.dof()] } else { v };
            let (q, qd, qdd) = (zeros(q), zeros(qd), zeros(qdd));
            for (what, v) in [("q", &q), ("qd", &qd), ("qdd", &qdd)] {
                m.check_state(what, v).map_err(|e| e.to_string())?;
            }
            let segment_tensions = if tensions {
                let mut data = Data::new(&m);
                let r = data
                    .inverse_dynamics(&m, &q, &qd, &qdd)
                    .map_err(|e| e.to_string())?;
                Some(r.segment_tensions.clone().ok_or(
                    "--tensions: the routing is incomplete (an explicit coupling or structure \
                     column), so segment tensions are unknown",
                )?)
            } else {
                None
            };
            let scene = draw::scene(&m, &q, segment_tensions.as_deref());
            let svg = draw::svg(&m, &scene, view)?;
            tendyn_codegen::builder::write_atomically(out.as_ref(), &svg)
                .map_err(|e| format!("{out}: {e}"))?;
            note!("drew `{}` ({}) to {out}", m.name(), view.name());
            Ok(())
        }
        Command::Export { file, mjcf: _, out } => {
            let m = load(&file)?;
            let xml = mjcf::mjcf(&m)?;
            tendyn_codegen::builder::write_atomically(out.as_ref(), &xml)
                .map_err(|e| format!("{out}: {e}"))?;
            note!("exported `{}` as MJCF to {out}", m.name());
            Ok(())
        }
        Command::Generate {
            file,
            outputs,
            scalar,
            out,
        } => {
            let m = load(&file)?;
            let outputs: Vec<tendyn_codegen::Output> = if outputs.is_empty() {
                tendyn_codegen::available_outputs(&m)
            } else {
                outputs
                    .iter()
                    .map(|o| {
                        tendyn_codegen::Output::parse(o).ok_or_else(|| {
                            let names: Vec<&str> = tendyn_codegen::Output::ALL
                                .iter()
                                .map(|o| o.name())
                                .collect();
                            format!("unknown output `{o}`; the outputs are {}", names.join(", "))
                        })
                    })
                    .collect::<Result<_, _>>()?
            };
            let scalar = tendyn_codegen::Scalar::parse(&scalar)
                .ok_or_else(|| format!("unknown scalar `{scalar}`; use generic, f64 or f32"))?;
            let source = std::path::Path::new(&file)
                .file_name()
                .map_or(file.clone(), |n| n.to_string_lossy().into_owned());
            let start = std::time::Instant::now();
            let g = tendyn_codegen::generate(&m, &outputs, scalar, &source)
                .map_err(|e| format!("{file}: {e}"))?;
            let text = g.source();
            let elapsed = start.elapsed();
            match out {
                Some(path) => tendyn_codegen::builder::write_atomically(path.as_ref(), &text)
                    .map_err(|e| format!("{path}: {e}"))?,
                None => emit(&text),
            }
            note!(
                "generated {} functions for `{}` in {:.2} ms:",
                g.functions.len(),
                m.name(),
                elapsed.as_secs_f64() * 1e3
            );
            for (o, ops, form) in &g.functions {
                note!("  {:<20} {} ({})", o.name(), ops, form.label());
            }
            note!("  {:<20} {}", "all", g.all);
            Ok(())
        }
        Command::Equations { file, outputs } => {
            let m = load(&file)?;
            let outputs: Vec<tendyn_codegen::Output> = if outputs.is_empty() {
                tendyn_codegen::outputs::available(
                    &m,
                    &[
                        tendyn_codegen::Output::GeneralizedForces,
                        tendyn_codegen::Output::Actuation,
                    ],
                )
            } else {
                outputs
                    .iter()
                    .map(|o| {
                        tendyn_codegen::Output::parse(o).ok_or_else(|| {
                            tendyn_codegen::Error::UnknownOutput(o.clone()).to_string()
                        })
                    })
                    .collect::<Result<_, _>>()?
            };
            emit(
                &tendyn_codegen::equations::equations(&m, &outputs)
                    .map_err(|e| format!("{file}: {e}"))?,
            );
            Ok(())
        }
        Command::Report {
            files,
            json,
            markdown,
            svg,
            states,
            samples,
            warmup_ms,
        } => {
            let mut args: Vec<std::ffi::OsString> = Vec::new();
            if json {
                args.push("--json".into());
            }
            if markdown {
                args.push("--markdown".into());
            }
            if let Some(svg) = svg {
                // The report runs in the source tree: a relative path is made absolute here.
                let path = std::path::absolute(&svg).map_err(|e| format!("{svg}: {e}"))?;
                args.extend(["--svg".into(), path.into_os_string()]);
            }
            for (flag, value) in [
                ("--states", states.map(|v| v as u64)),
                ("--samples", samples.map(|v| v as u64)),
                ("--warmup-ms", warmup_ms),
            ] {
                if let Some(v) = value {
                    args.extend([flag.into(), v.to_string().into()]);
                }
            }
            let code = report_command(&files, &args)?;
            if code != 0 {
                // tendyn-report (or cargo) has said why; every failure is status 1, as
                // for every other subcommand (cargo's own would be 101).
                std::process::exit(1);
            }
            Ok(())
        }
        Command::Forward {
            file,
            state: State { q, qd },
            torques,
            tensions,
            json,
            derivatives,
        } => {
            let m = load(&file)?;
            for (flag, given, items, what) in [
                (
                    "--torques",
                    torques.len(),
                    m.motors()
                        .iter()
                        .map(|x| x.name.as_str())
                        .collect::<Vec<_>>(),
                    "motor torque (N·m)",
                ),
                (
                    "--tensions",
                    tensions.len(),
                    m.tendons().iter().map(|x| x.name.as_str()).collect(),
                    "ground-level tendon tension (N)",
                ),
            ] {
                if given != items.len() {
                    return Err(format!(
                        "{flag} has {given} numbers but `{}` needs {}: one {what} for each of {}, in file order",
                        m.name(),
                        items.len(),
                        if items.is_empty() { "none (leave the flag out)".to_string() } else { items.join(", ") }
                    ));
                }
            }
            let mut s = Data::new(&m);
            let qdd = s
                .forward_dynamics(&m, &q, &qd, &torques, &tensions)
                .map_err(|e| e.to_string())?
                .to_vec();
            // Within the band of rest, forward dynamics takes no friction (it does not know
            // q̈, which would give the impending motion's direction): flag those elements.
            let (bearings, guides) = tendyn_core::friction::forward_at_rest(&m, &q, &qd);
            let bearings: Vec<&str> = (bearings.into_iter())
                .map(|b| m.bodies()[b].name.as_str())
                .collect();
            let guides: Vec<(&str, &str)> = (guides.into_iter())
                .map(|(s, k)| {
                    let strand = &m.strands()[s];
                    let pulley = &m.bodies()[strand.idlers[k].body].name;
                    (strand.name.as_str(), pulley.as_str())
                })
                .collect();
            if json {
                let mut out = serde_json::json!({
                    "mechanism": m.name(),
                    "qdd": qdd,
                    "sticking": bearings,
                    "sticking_guides": guides
                        .iter()
                        .map(|(t, p)| serde_json::json!({"tendon": t, "pulley": p}))
                        .collect::<Vec<_>>(),
                });
                if derivatives {
                    let d = s
                        .forward_dynamics_derivatives(&m, &q, &qd, &torques, &tensions)
                        .map_err(|e| e.to_string())?;
                    out["dqdd_dq"] = rows(&d.d_q, m.dof());
                    out["dqdd_dqd"] = rows(&d.d_qd, m.dof());
                    out["dqdd_du"] = rows(&d.d_u, m.dof());
                }
                say!("{out}");
            } else {
                say!("qdd = {qdd:?}");
                let resting: Vec<String> = (bearings.iter())
                    .map(|b| format!("`{b}`'s bearing"))
                    .chain(guides.iter().map(|(t, p)| format!("`{t}` over `{p}`")))
                    .collect();
                if !resting.is_empty() {
                    say!(
                        "at rest, without friction (exact only away from rest): {}",
                        resting.join(", ")
                    );
                }
            }
            Ok(())
        }
    }
}

/// `tendyn report`: validates every file (so bad input fails here, located, before any
/// build), then runs `cargo run --release -p tendyn-report -- ARGS` in the source tree this
/// binary was built from, with the files' absolute paths in `TENDYN_REPORT_FILES`.
/// Returns the exit status of cargo (and so of the report).
fn report_command(files: &[String], args: &[std::ffi::OsString]) -> Result<i32, String> {
    let mut paths = Vec::new();
    for file in files {
        load(file)?;
        paths.push(std::fs::canonicalize(file).map_err(|e| format!("{file}: {e}"))?);
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(std::path::Path::to_path_buf)
        .unwrap_or_default();
    if !root.join("tendyn-report").join("Cargo.toml").is_file() {
        return Err(format!(
            "tendyn report compiles the generated code with cargo in the tendyn source tree, \
             and that tree is not at {} (where this binary was built); run it from a checkout: \
             cargo run --release --bin tendyn -- report",
            root.display()
        ));
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = std::process::Command::new(&cargo);
    command
        .args(["run", "--release", "-p", "tendyn-report", "--"])
        .args(args)
        .current_dir(&root);
    if paths.is_empty() {
        command.env_remove("TENDYN_REPORT_FILES");
    } else {
        let joined = std::env::join_paths(&paths).map_err(|e| {
            format!("cannot pass the files to the report (a path contains the separator): {e}")
        })?;
        command.env("TENDYN_REPORT_FILES", joined);
    }
    let status = command.status().map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            format!(
                "cargo was not found (`{}`): tendyn report compiles the generated code with \
                 cargo; install Rust or put cargo on PATH",
                std::path::Path::new(&cargo).display()
            )
        } else {
            format!(
                "cannot run `{}`: {e}",
                std::path::Path::new(&cargo).display()
            )
        }
    })?;
    Ok(status.code().unwrap_or(1))
}

/// Inverse dynamics and the joint-space terms at one state.
fn evaluate(
    m: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<(InverseDynamics<f64>, JointSpace), String> {
    let mut s = Data::new(m);
    let e = |e: tendyn_core::Error| e.to_string();
    let r = s.inverse_dynamics(m, q, qd, qdd).map_err(e)?.clone();
    let js = JointSpace {
        mass: s.mass_matrix(m, q).map_err(e)?.to_vec(),
        bias: s.bias(m, q, qd).map_err(e)?.to_vec(),
        gravity: s.gravity(m, q).map_err(e)?.to_vec(),
    };
    Ok((r, js))
}

/// The numbers of a CSV file, `columns` per line, with each line's number (from 1): blank
/// lines and lines starting with `#` are skipped, and so is a first line that is not
/// numbers (a header, as `eval --states --csv` prints). A wrong count or a word elsewhere
/// is an error naming the line and what it should hold (`what`).
fn csv_rows(path: &str, columns: usize, what: &str) -> Result<Vec<(usize, Vec<f64>)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut rows = Vec::new();
    let mut first = true;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let parsed: Result<Vec<f64>, String> = line
            .split(',')
            .map(|x| x.trim().parse().map_err(|e| format!("`{}`: {e}", x.trim())))
            .collect();
        // A first line none of whose fields is a number is a header; one with a number
        // and a typo is a data line with an error, never silently dropped.
        let header = std::mem::replace(&mut first, false)
            && line.split(',').all(|x| x.trim().parse::<f64>().is_err());
        let vals = match parsed {
            Ok(v) => v,
            Err(_) if header => continue,
            Err(e) => return Err(format!("{path}:{}: {e}", i + 1)),
        };
        if vals.len() != columns {
            return Err(format!(
                "{path}:{}: expected {columns} numbers ({what}), got {}",
                i + 1,
                vals.len()
            ));
        }
        rows.push((i + 1, vals));
    }
    Ok(rows)
}

/// A row-major matrix of `n` rows as a JSON array of rows.
fn rows(flat: &[f64], n: usize) -> serde_json::Value {
    let columns = flat.len() / n.max(1);
    serde_json::json!((0..n)
        .map(|i| &flat[i * columns..(i + 1) * columns])
        .collect::<Vec<_>>())
}

/// The samples of `tendyn identify --data`: per line the state, then what was measured
/// (actuators, or with `forces` the generalized forces), turned into generalized forces.
fn identification_samples(
    m: &Model<f64>,
    path: &str,
    forces: bool,
) -> Result<Vec<tendyn_core::identification::Sample>, String> {
    let n = m.dof();
    let (motors, tendons) = (m.motors().len(), m.tendons().len());
    let measured = if forces { n } else { motors + tendons };
    let what = if forces {
        format!("q, qd, qdd: {n} each, then {n} generalized forces")
    } else {
        format!("q, qd, qdd: {n} each, then {motors} motor torques and {tendons} tendon tensions")
    };
    let mut data = Data::new(m);
    let mut samples = Vec::new();
    for (line, vals) in csv_rows(path, 3 * n + measured, &what)? {
        let at = |e: String| format!("{path}:{line}: {e}");
        let (q, qd, qdd) = (&vals[..n], &vals[n..2 * n], &vals[2 * n..3 * n]);
        let rest = &vals[3 * n..];
        let delivered = if forces {
            rest.to_vec()
        } else {
            let (torques, tensions) = rest.split_at(motors);
            data.actuator_forces(m, q, qd, torques, tensions)
                .map_err(|e| at(e.to_string()))?
        };
        samples.push(tendyn_core::identification::Sample {
            q: q.to_vec(),
            qd: qd.to_vec(),
            qdd: qdd.to_vec(),
            forces: delivered,
        });
    }
    Ok(samples)
}

fn eval_text(m: &Model<f64>, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<String, String> {
    let (r, js) = evaluate(m, q, qd, qdd)?;
    Ok(report::inverse_text(m, [q, qd, qdd], &r, &js))
}

fn eval_json(
    m: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<serde_json::Value, String> {
    let (r, js) = evaluate(m, q, qd, qdd)?;
    Ok(report::inverse_json(m, q, qd, qdd, &r, &js))
}
