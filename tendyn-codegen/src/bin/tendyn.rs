//! The `tendyn` command line: check a mechanism, evaluate its dynamics, run the demo.

use clap::{Parser, Subcommand};
use std::process::ExitCode;
use tendyn_codegen::report::{self, JointSpace};
use tendyn_core::{InverseDynamics, Model, Solver};

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
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    q: Vec<f64>,
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    qd: Vec<f64>,
}

#[derive(Subcommand)]
enum Command {
    /// Validate a mechanism file and print what the routing implies.
    Check { file: String },
    /// Evaluate inverse dynamics, M, h and g at a state.
    Eval {
        file: String,
        #[command(flatten)]
        state: State,
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        qdd: Vec<f64>,
        /// A CSV file with one state per line: q..., qd..., qdd... (3n numbers).
        #[arg(long)]
        states: Option<String>,
        /// Print one JSON object per state.
        #[arg(long)]
        json: bool,
    },
    /// Forward dynamics: joint accelerations from motor torques and tendon tensions.
    Forward {
        file: String,
        #[command(flatten)]
        state: State,
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        torques: Vec<f64>,
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        tensions: Vec<f64>,
        #[arg(long)]
        json: bool,
    },
    /// Generate straight-line Rust for a mechanism's dynamics.
    Generate {
        file: String,
        /// Comma-separated outputs (default: every output the mechanism can provide):
        /// generalized_forces, actuation, mass_matrix, bias, gravity, forward_dynamics,
        /// segment_tensions, bearings, base_reaction.
        #[arg(long, value_delimiter = ',')]
        outputs: Vec<String>,
        /// generic (over tendyn_core::Real), f64 or f32.
        #[arg(long, default_value = "generic")]
        scalar: String,
        /// Write the source here instead of to standard output.
        #[arg(short = 'o', long)]
        out: Option<String>,
    },
    /// Print the closed-form equations in readable notation (beside the paper's Eqs. 28-35).
    Equations {
        file: String,
        /// Comma-separated outputs (default: generalized_forces and actuation).
        #[arg(long, value_delimiter = ',')]
        outputs: Vec<String>,
    },
    /// Check and evaluate the paper's three built-in examples.
    Demo,
}

/// Writes to stdout; a reader that went away (`tendyn demo | head`) ends the program quietly.
fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if out
        .write_all(text.as_bytes())
        .and_then(|_| out.flush())
        .is_err()
    {
        std::process::exit(0);
    }
}

macro_rules! say {
    ($($t:tt)*) => { emit(&format!("{}\n", format!($($t)*))) };
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Check { file } => {
            let m = tendyn_core::load(&file).map_err(|e| format!("{file}: {e}"))?;
            emit(&report::check_text(&m));
            Ok(())
        }
        Command::Demo => {
            for (file, text) in tendyn_codegen::report::BUILT_IN {
                let m = tendyn_core::parse(text).map_err(|e| format!("{file}: {e}"))?;
                emit(&report::check_text(&m));
                let n = m.dof;
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
            qdd,
            states,
            json,
        } => {
            let m = tendyn_core::load(&file).map_err(|e| format!("{file}: {e}"))?;
            let n = m.dof;
            match states {
                None => {
                    if json {
                        say!("{}", eval_json(&m, &q, &qd, &qdd)?);
                    } else {
                        emit(&eval_text(&m, &q, &qd, &qdd)?);
                    }
                }
                Some(path) => {
                    if !(q.is_empty() && qd.is_empty() && qdd.is_empty()) {
                        return Err("give either --states or --q/--qd/--qdd, not both".into());
                    }
                    let text =
                        std::fs::read_to_string(&path).map_err(|e| format!("{path}: {e}"))?;
                    for (i, line) in text.lines().enumerate() {
                        let line = line.trim();
                        if line.is_empty() || line.starts_with('#') {
                            continue;
                        }
                        let vals: Vec<f64> = line
                            .split(',')
                            .map(|x| {
                                x.trim()
                                    .parse::<f64>()
                                    .map_err(|e| format!("{path}:{}: `{x}`: {e}", i + 1))
                            })
                            .collect::<Result<_, _>>()?;
                        if vals.len() != 3 * n {
                            return Err(format!(
                                "{path}:{}: expected {} numbers (q, qd, qdd), got {}",
                                i + 1,
                                3 * n,
                                vals.len()
                            ));
                        }
                        let v = eval_json(&m, &vals[..n], &vals[n..2 * n], &vals[2 * n..])
                            .map_err(|e| format!("{path}:{}: {e}", i + 1))?;
                        say!("{v}");
                    }
                }
            }
            Ok(())
        }
        Command::Generate {
            file,
            outputs,
            scalar,
            out,
        } => {
            let m = tendyn_core::load(&file).map_err(|e| format!("{file}: {e}"))?;
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
            let elapsed = start.elapsed();
            match out {
                Some(path) => {
                    std::fs::write(&path, &g.source).map_err(|e| format!("{path}: {e}"))?
                }
                None => emit(&g.source),
            }
            eprintln!(
                "generated {} functions for `{}` in {:.2} ms:",
                g.functions.len(),
                m.name,
                elapsed.as_secs_f64() * 1e3
            );
            for (o, ops, closed) in &g.functions {
                eprintln!(
                    "  {:<20} {} ({})",
                    o.name(),
                    ops,
                    if *closed {
                        "closed form"
                    } else {
                        "traced recursion"
                    }
                );
            }
            eprintln!("  {:<20} {}", "all", g.all);
            Ok(())
        }
        Command::Equations { file, outputs } => {
            let m = tendyn_core::load(&file).map_err(|e| format!("{file}: {e}"))?;
            let outputs: Vec<tendyn_codegen::Output> = if outputs.is_empty() {
                [
                    tendyn_codegen::Output::GeneralizedForces,
                    tendyn_codegen::Output::Actuation,
                ]
                .into_iter()
                .filter(|o| tendyn_codegen::outputs::check(&m, &[*o]).is_ok())
                .collect()
            } else {
                outputs
                    .iter()
                    .map(|o| {
                        tendyn_codegen::Output::parse(o)
                            .ok_or_else(|| format!("unknown output `{o}`"))
                    })
                    .collect::<Result<_, _>>()?
            };
            emit(
                &tendyn_codegen::equations::equations(&m, &outputs)
                    .map_err(|e| format!("{file}: {e}"))?,
            );
            Ok(())
        }
        Command::Forward {
            file,
            state: State { q, qd },
            torques,
            tensions,
            json,
        } => {
            let m = tendyn_core::load(&file).map_err(|e| format!("{file}: {e}"))?;
            let mut s = Solver::new(&m);
            let qdd = s
                .forward_dynamics(&q, &qd, &torques, &tensions)
                .map_err(|e| e.to_string())?;
            if json {
                say!("{}", serde_json::json!({ "mechanism": m.name, "qdd": qdd }));
            } else {
                say!("qdd = {qdd:?}");
            }
            Ok(())
        }
    }
}

/// Inverse dynamics and the joint-space terms at one state.
fn evaluate(
    m: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<(InverseDynamics<f64>, JointSpace), String> {
    let mut s = Solver::new(m);
    let e = |e: tendyn_core::Error| e.to_string();
    let r = s.inverse_dynamics(q, qd, qdd).map_err(e)?;
    let js = JointSpace {
        mass: s.mass_matrix(q).map_err(e)?,
        bias: s.bias(q, qd).map_err(e)?,
        gravity: s.gravity(q).map_err(e)?,
    };
    Ok((r, js))
}

fn eval_text(m: &Model<f64>, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<String, String> {
    let (r, js) = evaluate(m, q, qd, qdd)?;
    Ok(report::inverse_text(m, &r, &js))
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
