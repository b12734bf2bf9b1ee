//! `tendyn report` as a user meets it, without running the report itself (that builds and
//! times the generated code for a minute; `tendyn-report`'s own tests cover it): bad input
//! fails before any build, with the usual located error.

use std::process::Command;

fn tendyn(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_tendyn"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        // Were cargo reached, this would fail differently (and loudly).
        .env("CARGO", "/nonexistent/cargo-must-not-run")
        .output()
        .expect("runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn report_on_a_bad_file_fails_with_the_located_error_and_no_output() {
    let dir = std::env::temp_dir().join(format!("tendyn_report_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.ron");
    std::fs::write(&bad, "(name: \"bad\",\n links: [\n").unwrap();
    let bad = bad.to_str().unwrap();
    let (code, out, err) = tendyn(&["report", "examples/mechanisms/example1_endless.ron", bad]);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(code, Some(1), "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(err.starts_with(&format!("error: {bad}:")), "{err}");
    assert!(err.contains("line 2, column"), "{err}");
    assert!(!err.contains("cargo"), "{err}");
}

#[test]
fn report_on_a_missing_file_names_it() {
    let (code, _, err) = tendyn(&["report", "no/such/mechanism.ron"]);
    assert_eq!(code, Some(1));
    assert!(err.starts_with("error: no/such/mechanism.ron:"), "{err}");
}

#[test]
fn report_without_cargo_says_so() {
    let (code, out, err) = tendyn(&["report", "--states", "1"]);
    assert_eq!(code, Some(1));
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains("cargo was not found") && err.contains("/nonexistent/cargo-must-not-run"),
        "{err}"
    );
}
