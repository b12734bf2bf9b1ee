//! `tendyn-report`: the measurement behind `tendyn report` (which builds this crate with the
//! files it is given in `TENDYN_REPORT_FILES`; see `build.rs`). Prints the table (or JSON)
//! on stdout, progress on stderr, and writes the chart.

use clap::Parser;
use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use std::time::Duration;
use tendyn_report::{chart, Config, MECHANISMS};

/// Error against run time of generated code and the runtime solver, f64 and f32, for the
/// mechanisms this crate was built with.
#[derive(Parser)]
#[command(name = "tendyn-report", version)]
struct Args {
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Print the table as Markdown.
    #[arg(long, conflicts_with = "json")]
    markdown: bool,
    /// Where to write the SVG chart.
    #[arg(long, default_value = "target/tendyn-report.svg")]
    svg: std::path::PathBuf,
    /// Random states per mechanism.
    #[arg(long, default_value_t = 1024)]
    states: usize,
    /// Timing samples per evaluator.
    #[arg(long, default_value_t = 31)]
    samples: usize,
    /// Minimum warm-up per evaluator, ms.
    #[arg(long, default_value_t = 300)]
    warmup_ms: u64,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let config = Config {
        states: args.states.max(1),
        samples: args.samples.max(1),
        warmup: Duration::from_millis(args.warmup_ms),
        ..Config::default()
    };
    // On a terminal one line, rewritten as the work goes on; otherwise a line per output.
    let terminal = std::io::stderr().is_terminal();
    let mut progress = |p: tendyn_report::Progress| {
        let mut line = format!("[{}/{}] {}: ", p.mechanism, p.of, p.name);
        match p.output {
            None => line.push_str("reference states"),
            Some(o) => line.push_str(o.name()),
        }
        let mut err = std::io::stderr().lock();
        if terminal {
            if let Some(e) = p.evaluator {
                line.push_str(&format!(", timing {}", e.name()));
            }
            let _ = write!(err, "\r\x1b[2K{line}");
            let _ = err.flush();
        } else if p.evaluator.is_none() {
            let _ = writeln!(err, "{line}");
        }
    };
    let report = match tendyn_report::run(MECHANISMS, &config, &mut progress) {
        Ok(r) => r,
        Err(e) => {
            if terminal {
                eprintln!();
            }
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    if terminal {
        eprintln!();
    }
    if let Some(dir) = args.svg.parent().filter(|d| !d.as_os_str().is_empty()) {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("error: {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
    }
    if let Err(e) = chart::write_svg(&report, &args.svg) {
        eprintln!("error: {e}");
        return ExitCode::FAILURE;
    }
    let text = if args.json {
        format!("{:#}\n", report.json())
    } else if args.markdown {
        report.markdown()
    } else {
        report.table()
    };
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        // A reader that went away is no failure; anything else (a full disk) is.
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            return ExitCode::SUCCESS;
        }
        eprintln!("error: cannot write to standard output: {e}");
        return ExitCode::FAILURE;
    }
    let shown = std::path::absolute(&args.svg).unwrap_or(args.svg);
    eprintln!("chart: {}", shown.display());
    ExitCode::SUCCESS
}
