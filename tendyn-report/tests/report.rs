//! The report on Example 1 with a few states: every output and all four evaluators appear,
//! generated and runtime f64 agree with the double-double reference to 1e-12 and f32 to
//! 1e-5 (max-norm relative), and the table, JSON and chart carry every row. Nothing here
//! asserts on time beyond its being a positive number.

use std::time::Duration;
use tendyn_report::{chart, Config, Evaluator, Output, Report, MECHANISMS};

fn example1() -> Report {
    let mech = MECHANISMS
        .iter()
        .find(|m| m.name == "example1_endless")
        .expect("built with the paper's examples (TENDYN_REPORT_FILES unset)");
    let config = Config {
        states: 48,
        samples: 3,
        warmup: Duration::ZERO,
        min_sample: Duration::ZERO,
        seed: 11,
    };
    let mut calls = 0;
    let report =
        tendyn_report::run(std::slice::from_ref(mech), &config, &mut |_| calls += 1).unwrap();
    // Progress: the states, then per output its errors and four timings.
    assert_eq!(calls, 1 + 5 * mech.outputs.len());
    report
}

#[test]
fn example_1_every_output_and_evaluator_within_its_precision() {
    let report = example1();
    assert!(report.notes.is_empty(), "{:?}", report.notes);
    // Example 1 provides all nine outputs; each is measured by all four evaluators.
    assert_eq!(report.rows.len(), Output::DEFAULT.len() * 4);
    for &output in Output::DEFAULT {
        for evaluator in Evaluator::ALL {
            let row = report
                .rows
                .iter()
                .find(|r| r.output == output && r.evaluator == evaluator)
                .unwrap_or_else(|| panic!("{} {} missing", output.name(), evaluator.name()));
            let bound = match evaluator {
                Evaluator::GeneratedF64 | Evaluator::RuntimeF64 => 1e-12,
                Evaluator::GeneratedF32 | Evaluator::RuntimeF32 => 1e-5,
            };
            let what = format!("{} {}", output.name(), evaluator.name());
            assert!(
                row.max_error <= bound,
                "{what}: max error {:e}",
                row.max_error
            );
            assert!(row.median_error <= row.max_error, "{what}");
            assert_eq!(row.failed_states, 0, "{what}");
            assert!(
                row.time.median > 0.0 && row.time.median.is_finite(),
                "{what}"
            );
            assert!(row.time.p25 <= row.time.median && row.time.median <= row.time.p75);
        }
    }
    // f32 is not as accurate as f64: the errors measure something.
    let worst = |e: Evaluator| {
        report
            .rows
            .iter()
            .filter(|r| r.evaluator == e && r.output == Output::GeneralizedForces)
            .map(|r| r.max_error)
            .fold(0.0, f64::max)
    };
    assert!(worst(Evaluator::GeneratedF32) > 1e3 * worst(Evaluator::GeneratedF64));
    assert!(worst(Evaluator::GeneratedF64) > 0.0);
}

#[test]
fn table_json_and_chart_carry_every_row() {
    let report = example1();
    let table = report.table();
    assert_eq!(
        table
            .lines()
            .filter(|l| l.starts_with("example1_endless"))
            .count(),
        report.rows.len()
    );
    assert!(table.contains("IQR") && table.contains("||x - ref||_inf / ||ref||_inf"));
    let json = report.json();
    assert_eq!(json["rows"].as_array().unwrap().len(), report.rows.len());
    assert_eq!(json["rows"][0]["evaluator"], "generated f64");
    assert_eq!(json["rows"][2]["runtime_call"], "generalized_forces");
    assert!(json["rows"][0]["ns_per_call"]["median"].as_f64().unwrap() > 0.0);
    let markdown = report.markdown();
    assert_eq!(markdown.lines().count(), 2 + report.rows.len());

    let path = std::env::temp_dir().join(format!("tendyn-report-{}.svg", std::process::id()));
    chart::write_svg(&report, &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    for &output in Output::DEFAULT {
        assert!(svg.contains(output.name()), "panel {}", output.name());
    }
    for evaluator in Evaluator::ALL {
        assert!(
            svg.contains(evaluator.name()),
            "legend {}",
            evaluator.name()
        );
    }
    // One marker per row (the legend draws four more).
    assert_eq!(svg.matches("<circle").count(), report.rows.len() + 4);
}

#[test]
fn an_unwritable_chart_path_is_an_error_naming_it() {
    let report = example1();
    let path = std::path::Path::new("/nonexistent-dir/chart.svg");
    let e = chart::write_svg(&report, path).unwrap_err();
    assert!(e.contains("/nonexistent-dir/chart.svg"), "{e}");
}
