//! The `tendyn` binary as a user meets it.

use std::process::Command;

/// Runs `tendyn` from the workspace root: exit code, stdout, stderr. `CARGO` points
/// nowhere: only `tendyn report` would start cargo, and it must say so rather than run.
fn run(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_tendyn"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .env("CARGO", "/nonexistent/cargo-must-not-run")
        .output()
        .expect("runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The text of `examples/mechanisms/NAME.ron`.
fn example(name: &str) -> String {
    let path = format!(
        "{}/../examples/mechanisms/{name}.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

/// A fresh directory of this test process for a test's files (tests run in parallel, so
/// each names its own).
fn scratch_dir(test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("{test}_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// [`run`], with success as a flag.
fn tendyn(args: &[&str]) -> (bool, String, String) {
    let (code, out, err) = run(args);
    (code == Some(0), out, err)
}

#[test]
fn demo_runs_the_three_paper_examples_without_arguments() {
    let (ok, out, err) = tendyn(&["demo"]);
    assert!(ok, "{err}");
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        assert!(out.contains(&format!("mechanism `{name}`: valid")), "{out}");
    }
    assert!(out.contains("structure matrix A") && out.contains("mass matrix M"));
}

#[test]
fn check_prints_couplings_structure_matrix_and_null_vector() {
    let (ok, out, _) = tendyn(&["check", "examples/mechanisms/example2_open_ended.ron"]);
    assert!(ok);
    assert!(
        out.contains("idler3")
            && out.contains("positive null vector")
            && out.contains("condition number")
    );
}

#[test]
fn check_prints_the_static_torque_range_of_each_joint() {
    // Example 2 with T11 ≤ 200 N, every floor 5 N, T32 and T42 without maximum (rows of A:
    // link1 [-0.03, -0.03, 0.04], link2 [0.02, -0.02, 0]). link2 held: T32 = T42 = t ≥ 5,
    // Q1 = -0.06 t + 0.04 T11 ≤ -0.3 + 8 = 7.7, no lower end. link1 held:
    // T32 + T42 = (4/3) T11 ≤ 800/3, Q2 = ±0.02 (800/3 - 10) = ±5.133333.
    let (ok, out, err) = tendyn(&["check", "tests/mechanisms/stress/tendon_max_tension.ron"]);
    assert!(ok, "{err}");
    let header = "static torque range, tendons alone without motors (tendons within floor and \
                  max_tension, every other joint at zero generalized force):";
    let block = format!(
        "{header}\n  link1        [{:>11}, {:>11}] N·m\n  link2        [{:>11}, {:>11}] N·m\n\
         tension system",
        "-inf", "7.70000", "-5.13333", "5.13333"
    );
    assert!(out.contains(&block), "{out}");
    // Without maxima every end is open; without open-ended tendons there is no block.
    let (_, out, _) = tendyn(&["check", "examples/mechanisms/example2_open_ended.ron"]);
    assert!(
        out.contains(&format!(
            "  link2        [{:>11}, {:>11}] N·m",
            "-inf", "inf"
        )),
        "{out}"
    );
    let (_, out, _) = tendyn(&["check", "examples/mechanisms/example1_endless.ron"]);
    assert!(!out.contains("static torque range"), "{out}");
    // With T11 ≤ 7 N, holding link1 needs T32 + T42 = (4/3) T11 ≤ 28/3 < 10: no range.
    let dir = scratch_dir("tendyn_cli_range");
    let file = dir.join("tight.ron");
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/mechanisms/stress/tendon_max_tension.ron"
    ))
    .unwrap()
    .replace("max_tension: 200.0", "max_tension: 7.0");
    std::fs::write(&file, text).unwrap();
    let (ok, out, err) = tendyn(&["check", file.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(
        out.contains(&format!(
            "  link1        [{:>11}, {:>11}] N·m\n  link2        none (",
            "-inf", "-0.0200000"
        )),
        "{out}"
    );
}

#[test]
fn eval_over_a_csv_of_states_prints_one_json_object_per_state() {
    let dir = scratch_dir("tendyn_cli");
    let csv = dir.join("states.csv");
    std::fs::write(
        &csv,
        "# q1,q2,qd1,qd2,qdd1,qdd2\n0.1,0.2,0,0,1,1\n0.3,-0.4,1,2,-3,4\n",
    )
    .unwrap();
    let (ok, out, err) = tendyn(&[
        "eval",
        "examples/mechanisms/example2_open_ended.ron",
        "--states",
        csv.to_str().unwrap(),
        "--json",
    ]);
    assert!(ok, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2);
    for l in lines {
        for key in [
            "\"generalized_forces\"",
            "\"tendon_tensions\"",
            "\"bearings\"",
            "\"mass_matrix\"",
            "\"segment_tensions\"",
            "\"base_reaction\"",
        ] {
            assert!(l.contains(key), "missing {key} in {l}");
        }
    }
}

#[test]
fn a_first_state_line_with_a_typo_is_an_error_not_a_header_and_nothing_is_printed() {
    let dir = scratch_dir("tendyn_cli_typo");
    let csv = dir.join("states.csv");
    // A header, then data whose first line has a typo: reported, never skipped.
    std::fs::write(&csv, "0.1,0.2,0,0,1,1x\n0.3,-0.4,1,2,-3,4\n").unwrap();
    for format in ["--json", "--csv"] {
        let (ok, out, err) = tendyn(&[
            "eval",
            "examples/mechanisms/example2_open_ended.ron",
            "--states",
            csv.to_str().unwrap(),
            format,
        ]);
        assert!(!ok, "{format}: {out}");
        assert!(
            err.contains("states.csv:1:") && err.contains("`1x`"),
            "{err}"
        );
        assert!(out.is_empty(), "{format}: nothing is printed: {out}");
    }
    // A line of names alone is a header.
    std::fs::write(&csv, "q1, q2, qd1, qd2, qdd1, qdd2\n0.3,-0.4,1,2,-3,4\n").unwrap();
    let (ok, out, err) = tendyn(&[
        "eval",
        "examples/mechanisms/example2_open_ended.ron",
        "--states",
        csv.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert_eq!(out.lines().count(), 1);
}

#[test]
fn forward_gives_joint_accelerations_and_bad_input_fails_with_the_reason() {
    let (ok, out, err) = tendyn(&[
        "forward",
        "examples/mechanisms/example1_endless.ron",
        "--q",
        "0.3,0.5",
        "--qd",
        "1,-0.5",
        "--torques",
        "1.5,0.2",
        "--json",
    ]);
    assert!(ok, "{err}");
    assert!(out.contains("\"qdd\""));
    let (ok, _, err) = tendyn(&[
        "forward",
        "examples/mechanisms/example1_endless.ron",
        "--q",
        "0.3",
        "--qd",
        "1,-0.5",
        "--torques",
        "1.5,0.2",
    ]);
    assert!(
        !ok && err.contains("q has 1 entries but the mechanism has 2 joints"),
        "{err}"
    );
    let (ok, _, err) = tendyn(&["check", "does/not/exist.ron"]);
    assert!(!ok && err.contains("does/not/exist.ron"), "{err}");
}

/// Forward dynamics does not know `q̈`, so within the band of rest it takes no friction:
/// it flags the bearings and guides it took so (docs/outputs.md §5), and none where they
/// move.
#[test]
fn forward_flags_the_bearings_and_guides_it_took_at_rest_without_friction() {
    let forward = |file: &str, qd: &str, tensions: &str, json: bool| {
        let mut args = vec![
            "forward",
            file,
            "--q",
            "0.1,0.2",
            "--qd",
            qd,
            "--tensions",
            tensions,
        ];
        if json {
            args.push("--json");
        }
        let (ok, out, err) = tendyn(&args);
        assert!(ok, "{err}");
        out
    };
    let capstan = "examples/mechanisms/example2_capstan.ron";
    let out = forward(capstan, "0,0", "10,10,10", true);
    assert!(
        out.contains(r#""sticking":[]"#)
            && out.contains(
                r#""sticking_guides":[{"pulley":"idler3","tendon":"T32"},{"pulley":"idler4","tendon":"T42"}]"#
            ),
        "{out}"
    );
    let out = forward(capstan, "0,0", "10,10,10", false);
    assert!(
        out.contains("at rest, without friction (exact only away from rest): `T32` over `idler3`, `T42` over `idler4`"),
        "{out}"
    );
    let out = forward(capstan, "1,-0.5", "10,10,10", true);
    assert!(
        out.contains(r#""sticking":[],"sticking_guides":[]"#),
        "{out}"
    );
    assert!(!forward(capstan, "1,-0.5", "10,10,10", false).contains("at rest"));
    let friction = "examples/mechanisms/example2_friction.ron";
    let out = forward(friction, "0,1", "10,10,10", true);
    assert!(out.contains(r#""sticking":["link1"]"#), "{out}");
}

/// `eval`'s text shows each guide with friction as its JSON does: wrap angle, sliding speed,
/// direction and dissipated power, or that it is at rest.
#[test]
fn eval_text_shows_each_guide_with_friction_as_the_json_does() {
    let capstan = "examples/mechanisms/example2_capstan.ron";
    let eval = |qd: &str, json: bool| {
        let mut args = vec![
            "eval", capstan, "--q", "0.3,0.2", "--qd", qd, "--qdd", "1,2",
        ];
        if json {
            args.push("--json");
        }
        let (ok, out, err) = tendyn(&args);
        assert!(ok, "{err}");
        out
    };
    let text = eval("0.5,-1", false);
    let v: serde_json::Value = serde_json::from_str(&eval("0.5,-1", true)).unwrap();
    for g in v["guides"].as_array().unwrap() {
        let pulley = g["pulley"].as_str().unwrap();
        let line = (text.lines())
            .find(|l| l.trim_start().starts_with(&format!("guide {pulley} ")))
            .unwrap_or_else(|| panic!("no line for {pulley} in:\n{text}"));
        let degrees = g["wrap_angle"].as_f64().unwrap().to_degrees();
        assert!(line.contains(&format!("wrap {degrees:.3}°")), "{line}");
        let power = g["dissipated_power"].as_f64().unwrap();
        assert!(power > 0.0 && line.contains("dissipates"), "{line}");
    }
    let at_rest = eval("0,0", false);
    assert_eq!(
        at_rest.matches("(at rest: the impending motion's)").count(),
        2,
        "{at_rest}"
    );
}

#[test]
fn generate_writes_straight_line_rust_and_reports_operation_counts() {
    let dir = scratch_dir("tendyn_gen");
    let out = dir.join("finger.rs");
    let (ok, _, err) = tendyn(&[
        "generate",
        "examples/mechanisms/example3_stanford_jpl.ron",
        "--outputs",
        "generalized_forces,actuation",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let src = std::fs::read_to_string(&out).unwrap();
    assert!(src.contains(
        "pub fn generalized_forces<T: Real>(q: &[T; 3], qd: &[T; 3], qdd: &[T; 3]) -> [T; 3]"
    ));
    assert!(src.contains("pub fn actuation<T: Real>"));
    assert!(
        !src.contains("for ") && !src.contains("Vec") && !src.contains("while "),
        "not straight-line"
    );
    assert!(
        err.contains("generalized_forces") && err.contains("arithmetic"),
        "{err}"
    );
    let (ok, _, err) = tendyn(&[
        "generate",
        "examples/mechanisms/example1_endless.ron",
        "--outputs",
        "torque",
    ]);
    assert!(!ok && err.contains("unknown output `torque`"), "{err}");
}

#[test]
fn equations_print_the_collected_closed_form_with_paper_style_names() {
    let (ok, out, err) = tendyn(&["equations", "examples/mechanisms/example1_endless.ron"]);
    assert!(ok, "{err}");
    assert!(
        out.contains("generalized_forces link2 = ") && out.contains("th1dd") && out.contains("S2"),
        "{out}"
    );
}

// `tendyn report` without running the report itself (that builds and times the generated
// code for a minute; `tendyn-report`'s own tests cover it): bad input fails before any
// build, with the usual located error.

#[test]
fn report_on_a_bad_file_fails_with_the_located_error_and_no_output() {
    let dir = scratch_dir("tendyn_report_cli");
    let bad = dir.join("bad.ron");
    std::fs::write(&bad, "(name: \"bad\",\n links: [\n").unwrap();
    let bad = bad.to_str().unwrap();
    let (code, out, err) = run(&["report", "examples/mechanisms/example1_endless.ron", bad]);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(code, Some(1), "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(err.starts_with(&format!("error: {bad}:")), "{err}");
    assert!(err.contains("line 2, column"), "{err}");
    assert!(!err.contains("cargo"), "{err}");
}

#[test]
fn report_on_a_missing_file_names_it() {
    let (code, _, err) = run(&["report", "no/such/mechanism.ron"]);
    assert_eq!(code, Some(1));
    assert!(
        err.starts_with("error: cannot read no/such/mechanism.ron:"),
        "{err}"
    );
    assert_eq!(err.matches("no/such/mechanism.ron").count(), 1, "{err}");
}

#[test]
fn report_without_cargo_says_so() {
    let (code, out, err) = run(&["report", "--states", "1"]);
    assert_eq!(code, Some(1));
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains("cargo was not found") && err.contains("/nonexistent/cargo-must-not-run"),
        "{err}"
    );
}

#[test]
fn forward_without_the_tensions_of_a_tendon_mechanism_names_the_flag_and_the_tendons() {
    let (code, _, err) = run(&[
        "forward",
        "examples/mechanisms/example2_open_ended.ron",
        "--q",
        "0.1,0.2",
        "--qd",
        "0,0",
    ]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("--tensions has 0 numbers but `example2_open_ended` needs 3")
            && err.contains("T32, T42, T11, in file order"),
        "{err}"
    );
}

#[test]
fn a_standard_output_that_cannot_be_written_is_an_error_not_a_silent_success() {
    // /dev/full fails every write with "no space left on device".
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return; // not a Linux-like system: nothing to check
    };
    let out = Command::new(env!("CARGO_BIN_EXE_tendyn"))
        .args(["generate", "examples/mechanisms/example1_endless.ron"])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .stdout(full)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write to standard output"), "{err}");
}

#[test]
fn generate_to_a_file_writes_it_whole_and_leaves_no_temporary_file() {
    let dir = scratch_dir("tendyn_cli_out");
    let file = dir.join("example1.rs");
    let (ok, _, err) = tendyn(&[
        "generate",
        "examples/mechanisms/example1_endless.ron",
        "-o",
        file.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains("pub fn generalized_forces"));
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "only the output remains: {left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn check_json_holds_what_check_prints_with_the_model_s_own_numbers() {
    let (ok, out, err) = tendyn(&[
        "check",
        "examples/mechanisms/example2_friction.ron",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("one JSON object");
    let m = tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/mechanisms/example2_friction.ron"
    ))
    .unwrap();
    let a: Vec<Vec<f64>> = serde_json::from_value(v["structure_matrix"].clone()).unwrap();
    assert_eq!(a, m.structure_matrix(), "A to the bit");
    assert_eq!(v["joints"], serde_json::json!(["link1", "link2"]));
    assert_eq!(v["couplings"]["idler3"]["role"], "idler of T32");
    assert_eq!(
        v["tension_system"]["null_space"].as_array().map(Vec::len),
        Some(1)
    );
    // Unbounded ends of a static torque range are null (JSON has no infinity).
    assert_eq!(
        v["static_torque_range"]["link2"],
        serde_json::json!({"min": null, "max": null})
    );
    // The ground exit has no acting angle.
    assert_eq!(
        v["segments"]["T11"][0]["acting_angles"][1],
        serde_json::Value::Null
    );
    assert_eq!(v["bearing_friction"]["link1"]["coulomb"], 0.05);
    // No joint has a range in this file.
    assert_eq!(
        v["joint_ranges"],
        serde_json::json!({"link1": null, "link2": null})
    );
    // Without open-ended tendons there is no structure matrix and no range.
    let (_, out, _) = tendyn(&[
        "check",
        "examples/mechanisms/example1_endless.ron",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["structure_matrix"].is_null() && v["static_torque_range"].is_null());
}

/// A reader of standard error that goes away (`2>&1 | head -1`) does not make `generate`
/// fail: the file is written and the notes are dropped.
#[test]
fn generate_succeeds_when_no_one_reads_its_notes() {
    let dir = scratch_dir("tendyn_cli_closed_stderr");
    let file = dir.join("out.rs");
    let mut child = Command::new(env!("CARGO_BIN_EXE_tendyn"))
        .args([
            "generate",
            "examples/mechanisms/example3_stanford_jpl.ron",
            "-o",
        ])
        .arg(&file)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    drop(child.stderr.take());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0));
    assert!(std::fs::read_to_string(&file)
        .unwrap()
        .contains("pub fn generalized_forces"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `check` prints a guide's `mu` as the file gives it, however small, and its `μβ` as the
/// capstan law takes it: 0 where the wrap angle is negative (Example 2 with capstan
/// friction, whose idler4 the tendon bends away from at `q = 0`). At rest, `eval`'s
/// bearing friction is `0`, not `-0`.
#[test]
fn check_prints_the_guides_coefficients_as_the_law_takes_them() {
    let dir = scratch_dir("tendyn_cli_coefficients");
    let file = dir.join("tiny_mu.ron");
    let text = example("example2_capstan").replacen("mu: 0.3,", "mu: 1e-300,", 1);
    std::fs::write(&file, text).unwrap();
    let (ok, out, err) = tendyn(&["check", file.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(
        out.contains(
            "idler3       T32      β = 27.662° (at q = 0), μ = 1.00000e-300, μβ = 4.82787e-301\n"
        ),
        "{out}"
    );
    assert!(
        out.contains(
            "idler4       T42      β = -2.642° (at q = 0), μ = 0.300000, μβ = 0 (negative"
        ),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
    let (ok, out, err) = tendyn(&[
        "eval",
        "examples/mechanisms/example2_friction.ron",
        "--q",
        "0,0",
        "--qd",
        "0,0",
        "--qdd",
        "0,0",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for (body, torque) in v["bearing_friction"].as_object().unwrap() {
        assert!(
            torque.as_f64().unwrap().is_sign_positive(),
            "{body}: {torque}"
        );
    }
}

/// A joint's `range` reaches `check`: the JSON gives it, and each guide whose wrap angle
/// changes with the joint gets the interval the range spans, `wrap + rate·q` at the ends
/// (Example 2 with capstan friction, link1 within `[−0.5, 0.8]` rad); the text prints it.
#[test]
fn check_gives_the_joint_ranges_and_the_wrap_angles_they_span() {
    let dir = scratch_dir("tendyn_cli_ranges");
    let file = dir.join("ranged.ron");
    let text = example("example2_capstan").replacen(
        "dh: (a: 0.30,",
        "range: (-0.5, 0.8), dh: (a: 0.30,",
        1,
    );
    std::fs::write(&file, text).unwrap();
    let (ok, out, err) = tendyn(&["check", file.to_str().unwrap(), "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["joint_ranges"],
        serde_json::json!({"link1": [-0.5, 0.8], "link2": null})
    );
    for guide in v["guides"].as_array().unwrap() {
        let wrap = guide["wrap_angle"].as_f64().unwrap();
        let rate = guide["wrap_angle_rate"][0].as_f64().unwrap();
        let ends = [wrap - 0.5 * rate, wrap + 0.8 * rate];
        let want = [ends[0].min(ends[1]).max(0.0), ends[0].max(ends[1]).max(0.0)];
        assert_ne!(rate, 0.0, "{guide}");
        assert_eq!(
            guide["wrap_angle_over_ranges"],
            serde_json::json!(want),
            "{guide}"
        );
    }
    let (ok, text, err) = tendyn(&["check", file.to_str().unwrap()]);
    assert!(
        ok && text.contains("over the joints' ranges"),
        "{err}{text}"
    );
}

#[test]
fn eval_states_as_csv_prints_a_header_and_one_full_precision_row_per_state() {
    let dir = scratch_dir("tendyn_cli_csv");
    let states = dir.join("states.csv");
    std::fs::write(
        &states,
        "0.3,0.5, 1,-0.5, 2,3\n# a comment\n0.1,0.2,0,0,0,0\n",
    )
    .unwrap();
    let (ok, out, err) = tendyn(&[
        "eval",
        "examples/mechanisms/example2_open_ended.ron",
        "--states",
        states.to_str().unwrap(),
        "--csv",
    ]);
    assert!(ok, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "q_link1,q_link2,qd_link1,qd_link2,qdd_link1,qdd_link2,Q_link1,Q_link2,T_T32,T_T42,T_T11"
    );
    assert_eq!(lines.len(), 3, "{out}");
    // The tensions read back to the runtime solver's, bit for bit.
    let m = tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/mechanisms/example2_open_ended.ron"
    ))
    .unwrap();
    let r = tendyn_core::Data::new(&m)
        .inverse_dynamics(&m, &[0.3, 0.5], &[1.0, -0.5], &[2.0, 3.0])
        .unwrap()
        .clone();
    let row: Vec<f64> = lines[1].split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!(&row[8..], r.tendon_tensions.as_slice());
    // --csv needs --states.
    let (code, _, _) = run(&[
        "eval",
        "examples/mechanisms/example2_open_ended.ron",
        "--csv",
    ]);
    assert_eq!(code, Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn check_warns_of_pulleys_that_overlap_in_one_plane_of_one_carrier() {
    let text = example("example2_open_ended");
    // Nine pins of 10 mm radius on link1, 5 mm apart in the plane of drum1 (40 mm).
    let pins: String = (0..9)
        .map(|i| {
            format!(
                "        (name: \"pin{i}\", carrier: \"link1\", at: Pose(origin: ({}, 0.0, 0.0), rpy: (0.0, 0.0, 0.0)), radius: 0.01, fixed: true),\n",
                -0.1 - 0.005 * i as f64
            )
        })
        .collect();
    let text = text.replacen("    pulleys: [\n", &format!("    pulleys: [\n{pins}"), 1);
    let model = tendyn_core::parse(&text).unwrap();
    // Pins k and l (5 mm · |k − l| apart) overlap when closer than 20 mm: |k − l| ≤ 3.
    let overlaps = tendyn_core::transmission::overlapping_pulleys(model.bodies());
    assert_eq!(overlaps.len(), 8 + 7 + 6, "{overlaps:?}");
    let dir = scratch_dir("tendyn_cli_overlap");
    let file = dir.join("pins.ron");
    std::fs::write(&file, &text).unwrap();
    let (ok, out, err) = tendyn(&["check", file.to_str().unwrap()]);
    assert!(ok, "a warning, not an error: {err}");
    assert!(
        out.contains("warning: pulleys `pin0` and `pin1` on `link1` overlap: their centres are 0.00500000 m apart in one plane"),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
    // The paper's examples have none: their idlers sit at other heights than the drums.
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        let m = tendyn_core::load(format!(
            "{}/../examples/mechanisms/{name}.ron",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        assert!(
            tendyn_core::transmission::overlapping_pulleys(m.bodies()).is_empty(),
            "{name}"
        );
    }
}

#[test]
fn a_state_list_may_have_spaces_after_its_commas_as_in_a_states_file() {
    let file = "examples/mechanisms/example2_open_ended.ron";
    let (ok, spaced, err) = tendyn(&[
        "eval", file, "--q", "0.1, 0.2", "--qd", " 1, -2", "--qdd", "3 ,4", "--json",
    ]);
    assert!(ok, "{err}");
    let (ok, tight, err) = tendyn(&[
        "eval", file, "--q", "0.1,0.2", "--qd", "1,-2", "--qdd", "3,4", "--json",
    ]);
    assert!(ok, "{err}");
    assert_eq!(spaced, tight);
    // Unquoted, the shell splits `--q 0.1, 0.2` into `0.1,` and `0.2`: the same list.
    let (ok, unquoted, err) = tendyn(&[
        "eval", file, "--q", "0.1,", "0.2", "--qd", "1,", "-2", "--qdd", "3,", "4", "--json",
    ]);
    assert!(ok, "{err}");
    assert_eq!(unquoted, tight);
    // A short flag after a trailing comma is a flag, not a number of the list.
    let dir = scratch_dir("tendyn_cli_short_flag");
    let svg = dir.join("x.svg");
    let (ok, _, err) = tendyn(&["draw", file, "--q", "0.1,", "-o", svg.to_str().unwrap()]);
    assert!(!ok && err.contains("q has 1 entries"), "{err}");
    let (_, _, err) = run(&["eval", file, "--q", "0.1,x", "--qd", "0,0", "--qdd", "0,0"]);
    assert!(err.contains("`x` is not a number"), "{err}");
}

#[test]
fn a_missing_file_is_named_once() {
    let (code, out, err) = run(&["check", "no/such/file.ron"]);
    assert_eq!(code, Some(1));
    assert!(out.is_empty());
    assert_eq!(err.matches("no/such/file.ron").count(), 1, "{err}");
}

#[test]
fn check_of_an_uncontrollable_routing_prints_what_it_implies_beside_the_error() {
    let (code, out, err) = run(&["check", "tendyn/tests/ui/mechanisms/uncontrollable.ron"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("not controllable by tendons"), "{err}");
    assert!(out.contains("what the routing implies"), "{out}");
    assert!(
        out.contains("structure matrix A") && out.contains("tension system E"),
        "{out}"
    );
    // `T11` is reversed on `link1`: every tendon pulls it the negative way.
    let link1 = out
        .lines()
        .find(|l| l.trim_start().starts_with("joint link1"))
        .unwrap();
    assert_eq!(link1.matches('-').count(), 3, "{link1}");
}

#[test]
fn check_warns_of_a_segment_that_passes_through_a_pulley_it_does_not_wrap() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/mechanisms/example2_open_ended.ron"
    );
    let text = std::fs::read_to_string(path).unwrap();
    let model = tendyn_core::parse(&text).unwrap();
    assert!(tendyn_core::transmission::segments_through_pulleys(&model).is_empty());
    // T11's one segment runs in the base frame, in the plane z = 0, from drum1 to its exit.
    let s = model
        .strands()
        .iter()
        .position(|s| s.name == "T11")
        .unwrap();
    let g = &model.strands()[s].segments[0];
    let (exit, d) = (g.to.rel, g.dir);
    let on_line = |along: f64, aside: f64, z: f64| {
        [
            exit.x - d.x * along - d.y * aside,
            exit.y - d.y * along + d.x * aside,
            z,
        ]
    };
    // Pins of 5 mm radius beside the segment's middle: 2 mm aside (cut), 8 mm aside (clear),
    // and 2 mm aside but 10 mm out of its plane (clear).
    let pins = [
        ("cut", on_line(0.5 * g.length, 0.002, 0.0)),
        ("clear", on_line(0.3 * g.length, 0.008, 0.0)),
        ("above", on_line(0.7 * g.length, 0.002, 0.01)),
    ];
    let lines: String = pins
        .iter()
        .map(|(name, [x, y, z])| {
            format!(
                "        (name: \"{name}\", carrier: \"base\", at: Pose(origin: ({x:?}, {y:?}, {z:?}), rpy: (0.0, 0.0, 0.0)), radius: 0.005, fixed: true),\n"
            )
        })
        .collect();
    let text = text.replacen("    pulleys: [\n", &format!("    pulleys: [\n{lines}"), 1);
    let model = tendyn_core::parse(&text).unwrap();
    let crossings = tendyn_core::transmission::segments_through_pulleys(&model);
    assert_eq!(crossings.len(), 1, "{crossings:?}");
    let c = crossings[0];
    assert_eq!(model.bodies()[c.pulley].name, "cut");
    assert_eq!(
        (model.strands()[c.strand].name.as_str(), c.segment),
        ("T11", 0)
    );
    assert!((c.distance - 0.002).abs() < 1e-12, "{}", c.distance);
    // A pulley carried by the base on joint 1's axis, coaxial with idler3 and larger: T32's
    // first segment, fixed in link 1, ends tangent to idler3, 0.03 m from that axis.
    let hub = text.replacen(
        "    pulleys: [\n",
        "    pulleys: [\n        (name: \"hub\", carrier: \"base\", at: Joint(joint: \"link1\", height: 0.01), radius: 0.05, fixed: true),\n",
        1,
    );
    let hub_model = tendyn_core::parse(&hub).unwrap();
    let through_hub: Vec<_> = tendyn_core::transmission::segments_through_pulleys(&hub_model)
        .into_iter()
        .filter(|c| hub_model.bodies()[c.pulley].name == "hub")
        .map(|c| {
            (
                hub_model.strands()[c.strand].name.clone(),
                c.segment,
                c.distance,
            )
        })
        .collect();
    assert!(
        through_hub
            .iter()
            .any(|(s, k, d)| s == "T32" && *k == 0 && (d - 0.03).abs() < 1e-12),
        "{through_hub:?}"
    );
    let dir = scratch_dir("tendyn_cli_crossing");
    let file = dir.join("cut.ron");
    std::fs::write(&file, &text).unwrap();
    let (ok, out, err) = tendyn(&["check", file.to_str().unwrap()]);
    assert!(ok, "a warning, not an error: {err}");
    assert!(
        out.contains(
            "warning: segment T11#0 passes through pulley `cut`, 0.00200000 m from its centre"
        ),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn check_and_eval_report_the_guides_tendons_slide_over() {
    let text = example("example2_open_ended");
    // Example 2 with its idlers held fixed: pins the tendons slide over.
    let text = text
        .replacen("name: \"idler3\",", "name: \"idler3\", fixed: true,", 1)
        .replacen("name: \"idler4\",", "name: \"idler4\", fixed: true,", 1);
    let dir = scratch_dir("tendyn_cli_guides");
    let file = dir.join("guides.ron");
    std::fs::write(&file, &text).unwrap();
    let file = file.to_str().unwrap();
    let (ok, out, err) = tendyn(&["check", file]);
    assert!(ok, "{err}");
    assert!(
        out.contains("idler3       r = 0.03     fixed guide"),
        "{out}"
    );
    assert!(
        out.contains("  idler3       T32      β = 27.662° (at q = 0), μ = 0, μβ = 0"),
        "{out}"
    );
    let (ok, out, err) = tendyn(&[
        "eval", file, "--q", "0.3,0.5", "--qd", "1,-0.5", "--qdd", "2,3", "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let guides = v["guides"].as_array().unwrap();
    assert_eq!(guides.len(), 2);
    // T32 leaves idler3 for its exit in the base: it slides over the guide at the speed it
    // is paid out, A_T32 · q̇ = −0.03 · 1 + 0.02 · (−0.5) = −0.04 m/s.
    assert_eq!(guides[0]["pulley"], "idler3");
    assert!((guides[0]["sliding_speed"].as_f64().unwrap() + 0.04).abs() < 1e-15);
    assert_eq!(guides[0]["direction"], -1.0);
    assert_eq!(guides[0]["dissipated_power"], 0.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `draw` writes an SVG of the mechanism; a state of the wrong length is an error and
/// writes nothing; `--tensions` on an incomplete routing says why it cannot.
#[test]
fn draw_writes_an_svg_or_says_what_is_wrong() {
    let dir = scratch_dir("draw");
    let svg = dir.join("mech.svg");
    let svg_path = svg.to_str().unwrap();
    let file = "examples/mechanisms/example2_open_ended.ron";
    let (ok, _, err) = tendyn(&["draw", file, "--q", "0.3,0.4", "--tensions", "-o", svg_path]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<svg") && text.contains("\nT32\n"),
        "{text}"
    );
    let wrong = dir.join("wrong.svg");
    let (ok, _, err) = tendyn(&["draw", file, "--q", "0.3", "-o", wrong.to_str().unwrap()]);
    assert!(
        !ok && err.contains("q has 1 entries but the mechanism has 2 joints"),
        "{err}"
    );
    assert!(!wrong.exists());
}

/// `export --mjcf` refuses what MuJoCo would: a turning link without mass, by name.
#[test]
fn export_names_a_link_mujoco_cannot_take() {
    let dir = scratch_dir("export");
    let file = dir.join("massless.ron");
    std::fs::write(
        &file,
        r#"(
    name: "massless",
    links: [(name: "arm", dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: 0.0, com: (0.0, 0.0, 0.0))],
    motors: [(name: "m", on: Joint("arm"))],
)"#,
    )
    .unwrap();
    let out = dir.join("massless.xml");
    let (ok, _, err) = tendyn(&[
        "export",
        file.to_str().unwrap(),
        "--mjcf",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("`arm` turns but has no positive mass"),
        "{err}"
    );
    assert!(!out.exists());
    let (ok, _, err) = tendyn(&[
        "draw",
        "examples/mechanisms/example2_open_ended.ron",
        "--qd",
        "1",
        "-o",
        dir.join("d.svg").to_str().unwrap(),
    ]);
    assert!(!ok && err.contains("qd has 1 entries"), "{err}");
}

#[test]
fn regressor_lists_the_base_parameters_and_eval_adds_the_regressor_at_a_state() {
    let file = "examples/mechanisms/example1_endless.ron";
    let (ok, out, err) = tendyn(&["regressor", file]);
    assert!(ok, "{err}");
    assert!(out.contains("5 base parameters"), "{out}");
    // Link 1 about joint 1, by the parallel-axis theorem (a₁ = 0.3 m).
    assert!(
        out.contains("link1.zz + 0.6 link1.mx + 0.09 link1.m + 0.09 link2.m + 0.09 drum2.m"),
        "{out}"
    );
    let (ok, out, err) = tendyn(&[
        "eval",
        file,
        "--q",
        "0.1,0.2",
        "--qd",
        "0.3,-0.4",
        "--qdd",
        "1,2",
        "--json",
        "--regressor",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let values: Vec<f64> = v["base_parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["value"].as_f64().unwrap())
        .collect();
    for (k, row) in v["regressor"].as_array().unwrap().iter().enumerate() {
        let row: Vec<f64> = row
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let q: f64 = row.iter().zip(&values).map(|(y, p)| y * p).sum::<f64>()
            + v["regressor_offset"][k].as_f64().unwrap();
        let expected = v["generalized_forces"][k].as_f64().unwrap();
        assert!(
            (q - expected).abs() <= 1e-14 * expected.abs().max(1e-3),
            "{q} {expected}"
        );
    }
}

/// `eval --states --csv` prints q, q̇, q̈, Q, the motor torques and the tensions: the
/// actuators' columns (or Q's) are what `identify` takes, and noise-free data give back the
/// file's base parameters.
#[test]
fn identify_recovers_the_file_s_base_parameters_from_noise_free_measurements() {
    let dir = scratch_dir("tendyn_cli_identify");
    let file = "examples/mechanisms/example2_open_ended.ron";
    let states: String = (0..300)
        .map(|i| {
            let t = i as f64 * 0.05;
            let (a, b) = (1.3 * t, 2.1 * t + 1.0);
            format!(
                "{},{},{},{},{},{}\n",
                a.sin(),
                0.8 * b.sin(),
                1.3 * a.cos(),
                1.68 * b.cos(),
                -1.69 * a.sin(),
                -3.53 * b.sin()
            )
        })
        .collect();
    let states_path = dir.join("states.csv");
    std::fs::write(&states_path, states).unwrap();
    let (ok, table, err) = tendyn(&[
        "eval",
        file,
        "--states",
        states_path.to_str().unwrap(),
        "--csv",
    ]);
    assert!(ok, "{err}");
    // Columns: q (2), qd (2), qdd (2), Q (2), then the three tendons' tensions.
    let keep = |columns: &[usize]| -> String {
        table
            .lines()
            .map(|l| {
                let cells: Vec<&str> = l.split(',').collect();
                columns
                    .iter()
                    .map(|&c| cells[c])
                    .collect::<Vec<_>>()
                    .join(",")
                    + "\n"
            })
            .collect()
    };
    let actuators = dir.join("actuators.csv");
    std::fs::write(&actuators, keep(&[0, 1, 2, 3, 4, 5, 8, 9, 10])).unwrap();
    let forces = dir.join("forces.csv");
    std::fs::write(&forces, keep(&[0, 1, 2, 3, 4, 5, 6, 7])).unwrap();
    for (data, extra) in [(&actuators, None), (&forces, Some("--forces"))] {
        let mut args = vec!["identify", file, "--data", data.to_str().unwrap(), "--json"];
        args.extend(extra);
        let (ok, out, err) = tendyn(&args);
        assert!(ok, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["samples"], 300);
        let base = v["base_parameters"].as_array().unwrap();
        let size = base.iter().fold(0.0f64, |m, b| {
            m.max(b["file_value"].as_f64().unwrap().abs())
        });
        for b in base {
            let (e, f) = (
                b["estimate"].as_f64().unwrap(),
                b["file_value"].as_f64().unwrap(),
            );
            // Each against its own value (or, zero in exact arithmetic, the largest's).
            assert!(
                (e - f).abs() <= 1e-9 * f.abs() + 1e-13 * size,
                "{}: {e} vs {f}",
                b["name"]
            );
        }
        assert!(v["relative_residual"].as_f64().unwrap() < 1e-12);
    }
    // --consistent: every body's mass properties, the file's where the data are the file's
    // own forces (to 1e-6 of the heaviest: the barrier method stays strictly inside the
    // physical set, and a massless drum is on its boundary).
    let forces_path = forces.to_str().unwrap().to_string();
    let consistent = |file: &str, data: &str, last: &[&str]| {
        let mut args = vec!["identify", file, "--data", data, "--forces", "--consistent"];
        args.extend(last);
        tendyn(&args)
    };
    let (ok, out, err) = consistent(file, &forces_path, &["--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let m = tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/mechanisms/example2_open_ended.ron"
    ))
    .unwrap();
    let bodies = v["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), m.bodies().len());
    let heaviest = m.bodies().iter().fold(0.0f64, |x, b| x.max(b.mass));
    for (b, body) in m.bodies().iter().zip(bodies) {
        assert_eq!(body["name"], b.name.as_str());
        let mass = body["mass"].as_f64().unwrap();
        assert!(
            (mass - b.mass).abs() <= 1e-6 * heaviest,
            "{}: {mass}",
            b.name
        );
        assert!(body["on_boundary"].is_boolean());
    }
    for b in v["base_parameters"].as_array().unwrap() {
        let (e, ls) = (
            b["estimate"].as_f64().unwrap(),
            b["least_squares"].as_f64().unwrap(),
        );
        assert!(
            (e - ls).abs() <= 1e-6 * ls.abs() + 1e-9,
            "{}: {e} vs {ls}",
            b["name"]
        );
    }
    assert!(v["relative_residual"].as_f64().unwrap() < 1e-9);
    // --write: the file with the estimate, which loads and gives the same masses; the rest
    // of the text (comments, the routing) as written.
    let written = dir.join("identified.ron");
    let (ok, _, err) = consistent(file, &forces_path, &["--write", written.to_str().unwrap()]);
    assert!(ok, "{err}");
    let identified = tendyn_core::load(&written).unwrap();
    for (b, body) in identified.bodies().iter().zip(bodies) {
        let mass = body["mass"].as_f64().unwrap();
        assert!((b.mass - mass).abs() <= 1e-15 * mass, "{}", b.name);
    }
    let (before, after) = (
        example("example2_open_ended"),
        std::fs::read_to_string(&written).unwrap(),
    );
    let head = |t: &str| t[..t.find("links: [").unwrap()].to_string();
    let tail = |t: &str| t[t.find("tendons: [").unwrap()..].to_string();
    assert_eq!(head(&before), head(&after));
    assert_eq!(tail(&before), tail(&after));
    // With noise the estimate moves, but a pulley whose frame does not spin (axisymmetric
    // in the file) stays axisymmetric, so the written model has the file's structure.
    let noisy = dir.join("noisy.csv");
    let lines: String = std::fs::read_to_string(&forces)
        .unwrap()
        .lines()
        .enumerate()
        .map(|(i, l)| {
            let cells: Vec<String> = (l.split(',').enumerate())
                .map(|(k, x)| match (k, x.parse::<f64>()) {
                    // The two generalized forces (a header line stays as it is).
                    (6 | 7, Ok(v)) => (v + 0.01 * (1.7 * (i + k) as f64).sin()).to_string(),
                    _ => x.to_string(),
                })
                .collect();
            cells.join(",") + "\n"
        })
        .collect();
    std::fs::write(&noisy, lines).unwrap();
    let (ok, _, err) = consistent(
        file,
        noisy.to_str().unwrap(),
        &["--write", written.to_str().unwrap()],
    );
    assert!(ok, "{err}");
    let identified = tendyn_core::load(&written).unwrap();
    for (b, a) in m.bodies().iter().zip(identified.bodies()) {
        assert_eq!(b.spins, a.spins, "{}", b.name);
    }
    assert!(m.bodies().iter().any(|b| !b.spins && b.mass > 0.0));
    // A mass given as a runtime parameter keeps it; the parameter takes the estimate.
    let with_parameter = dir.join("payload.ron");
    std::fs::write(
        &with_parameter,
        before
            .replace(
                "    tension_floor: 5.0,",
                "    tension_floor: 5.0,\n    parameters: [(name: \"payload\", value: 0.8)],",
            )
            .replace("mass: 0.8,", "mass: \"payload\","),
    )
    .unwrap();
    let (ok, _, err) = consistent(
        with_parameter.to_str().unwrap(),
        &forces_path,
        &["--write", written.to_str().unwrap()],
    );
    assert!(ok, "{err}");
    let after = std::fs::read_to_string(&written).unwrap();
    assert!(after.contains("mass: \"payload\""), "{after}");
    let identified = tendyn_core::load(&written).unwrap();
    let link2 = identified
        .bodies()
        .iter()
        .find(|b| b.name == "link2")
        .unwrap();
    let estimate = bodies[1]["mass"].as_f64().unwrap();
    assert!((link2.mass - estimate).abs() <= 1e-15 * estimate);
    // A short line is named with what it should hold.
    std::fs::write(&forces, "0.1,0.2,0,0,0,0,1\n").unwrap();
    let (ok, _, err) = tendyn(&[
        "identify",
        file,
        "--data",
        forces.to_str().unwrap(),
        "--forces",
    ]);
    assert!(!ok);
    assert!(err.contains(":1: expected 8 numbers"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--derivatives` adds the Jacobians as arrays of rows, the library's numbers.
#[test]
fn eval_and_forward_give_their_derivatives_on_request() {
    let file = "examples/mechanisms/example3_stanford_jpl.ron";
    let m = tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/mechanisms/example3_stanford_jpl.ron"
    ))
    .unwrap();
    let mut data = tendyn_core::Data::new(&m);
    let (q, qd, qdd) = ([0.1, 0.2, 0.3], [0.0, 0.5, -1.0], [1.0, 2.0, 3.0]);
    let (ok, out, err) = tendyn(&[
        "eval",
        file,
        "--q",
        "0.1,0.2,0.3",
        "--qd",
        "0,0.5,-1",
        "--qdd",
        "1,2,3",
        "--json",
        "--derivatives",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let d = data
        .generalized_forces_derivatives(&m, &q, &qd, &qdd)
        .unwrap();
    let flat = |key: &str| -> Vec<f64> {
        let rows = v[key].as_array().unwrap();
        assert_eq!(rows.len(), 3, "{key}: one row per joint");
        rows.iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect()
    };
    // (serde_json reads a printed f64 back to within one unit in the last place.)
    let same = |a: &[f64], b: &[f64]| {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .all(|(x, y)| (x - y).abs() <= 4e-16 * y.abs())
    };
    assert!(same(&flat("dQ_dq"), &d.d_q));
    assert!(same(&flat("dQ_dqd"), &d.d_qd));
    let tensions = [10.0, 12.0, 14.0, 20.0];
    let (ok, out, err) = tendyn(&[
        "forward",
        file,
        "--q",
        "0.1,0.2,0.3",
        "--qd",
        "0,0.5,-1",
        "--tensions",
        "10,12,14,20",
        "--json",
        "--derivatives",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let d = data
        .forward_dynamics_derivatives(&m, &q, &qd, &[], &tensions)
        .unwrap();
    let du: Vec<f64> = v["dqdd_du"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
        .collect();
    assert!(same(&du, &d.d_u));
    let rows = |key: &str| -> Vec<f64> {
        let rows = v[key].as_array().unwrap();
        assert_eq!(rows.len(), 3, "{key}: one row per joint");
        rows.iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect()
    };
    assert!(same(&rows("dqdd_dq"), &d.d_q));
    assert!(same(&rows("dqdd_dqd"), &d.d_qd));
    // Without --json the flag is refused by the parser.
    let (code, _, _) = run(&[
        "forward",
        file,
        "--q",
        "0,0,0",
        "--qd",
        "0,0,0",
        "--tensions",
        "1,1,1,1",
        "--derivatives",
    ]);
    assert_eq!(code, Some(2));
}

/// The drawings as a person sees them: Chromium (Debian's `chromium`, or the browser
/// `TENDYN_CHROMIUM` names) renders each paper example's SVG headless at the drawing's
/// size. In the screenshot, left of the legend (whose samples of the colours would
/// otherwise count), every strand shows in its colour, the links show as more black than
/// the joints' squares and the names could make, and the mechanism sits in the middle of
/// the room it has.
#[test]
#[ignore = "needs Chromium (apt-get install chromium): cargo test -p tendyn-cli -- --ignored render"]
fn drawings_render_in_a_headless_browser() {
    // The layout of `tendyn draw`: 800 × 600, a 40-px margin, the legend in the 160 px on
    // the right, the scale bar below the margin's line at 560.
    let (room_right, room_bottom) = (600, 560);
    let browser = std::env::var("TENDYN_CHROMIUM").unwrap_or_else(|_| "chromium".into());
    let dir = scratch_dir("render");
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        let svg = dir.join(format!("{name}.svg"));
        let file = format!("examples/mechanisms/{name}.ron");
        let out = svg.to_str().unwrap();
        // Seen at a slant: seen along a base axis, two strands may run one over the other.
        let (ok, _, err) = tendyn(&["draw", &file, "--view", "iso", "--tensions", "-o", out]);
        assert!(ok, "{err}");
        // Each strand's colour: the strokes wider than the 1-px outlines, black aside.
        let text = std::fs::read_to_string(&svg).unwrap();
        let strands: std::collections::BTreeSet<[u8; 3]> = text
            .split("stroke=\"#")
            .skip(1)
            .filter_map(|rest| {
                let width: f64 = rest
                    .split("stroke-width=\"")
                    .nth(1)?
                    .split('"')
                    .next()?
                    .parse()
                    .ok()?;
                let hex = |i: usize| u8::from_str_radix(&rest[i..i + 2], 16).unwrap();
                Some([hex(0), hex(2), hex(4)]).filter(|c| width > 1.0 && *c != [0, 0, 0])
            })
            .collect();
        assert!(!strands.is_empty(), "{name}: no strand drawn");

        let png = dir.join(format!("{name}.png"));
        let shot = Command::new(&browser)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--hide-scrollbars",
                "--window-size=800,600",
                &format!("--screenshot={}", png.display()),
                &format!("file://{}", svg.display()),
            ])
            .output()
            .unwrap_or_else(|e| panic!("cannot start `{browser}` ({e}); apt-get install chromium"));
        assert!(
            shot.status.success(),
            "{}",
            String::from_utf8_lossy(&shot.stderr)
        );
        let mut decoder =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()));
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
        let frame = reader.next_frame(&mut buffer).unwrap();
        assert_eq!((frame.width, frame.height), (800, 600), "{name}");
        let channels = match frame.color_type {
            png::ColorType::Rgb => 3,
            png::ColorType::Rgba => 4,
            other => panic!("{name}: a screenshot in {other:?}"),
        };
        // The room's pixels, with their places.
        let room: Vec<(i32, i32, [u8; 3])> = buffer[..frame.buffer_size()]
            .chunks(channels)
            .enumerate()
            .map(|(i, p)| ((i % 800) as i32, (i / 800) as i32, [p[0], p[1], p[2]]))
            .filter(|&(x, y, _)| x < room_right && y < room_bottom)
            .collect();
        // Pixels of colour `c`, give or take the browser's blending at a line's edges.
        let count = |c: [u8; 3]| {
            let near = |p: &[u8; 3]| (0..3).all(|i| p[i].abs_diff(c[i]) <= 24);
            room.iter().filter(|(_, _, p)| near(p)).count()
        };
        let shown: Vec<usize> = strands.iter().map(|c| count(*c)).collect();
        assert!(
            shown.iter().all(|&s| s >= 100),
            "{name}: strand colours show in {shown:?} px"
        );
        // Three 9 × 9 joint squares and the names make a few hundred black pixels at
        // most; a link drawn 4 px wide over its length makes a thousand or more.
        let black = count([0, 0, 0]);
        assert!(black >= 1000, "{name}: {black} black pixels");
        // The mechanism's extent (what is not white) is centred in the room.
        let ink: Vec<(i32, i32)> = (room.iter())
            .filter(|(_, _, p)| p.iter().any(|&c| c < 200))
            .map(|&(x, y, _)| (x, y))
            .collect();
        let extent = |f: fn(&(i32, i32)) -> i32| {
            let values = ink.iter().map(f);
            (values.clone().min().unwrap(), values.max().unwrap())
        };
        let ((x0, x1), (y0, y1)) = (extent(|p| p.0), extent(|p| p.1));
        let centre = ((x0 + x1) / 2, (y0 + y1) / 2);
        let off = ((centre.0 - 320).abs(), (centre.1 - 300).abs());
        println!(
            "{name}: strand colours {shown:?} px, black {black} px, drawn over \
             x {x0}–{x1}, y {y0}–{y1}, centre {off:?} px off the room's"
        );
        assert!(
            off.0 <= 40 && off.1 <= 40,
            "{name}: centre {centre:?}, not (320, 300)"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `check` says how far validation showed a routing with capstan friction controllable
/// (format.md §6a), in its text and its JSON alike: Example 2's two guides at every
/// factor they can take, on one box of factors; without guides with friction, nothing to
/// show and no line.
#[test]
fn check_says_how_far_the_routing_was_shown_controllable_with_friction() {
    let capstan = "examples/mechanisms/example2_capstan.ron";
    let (ok, text, err) = tendyn(&["check", capstan]);
    assert!(ok, "{err}");
    assert!(
        text.contains(
            "controllable with this friction: at every capstan factor the guides can take \
             (1 box of factors)"
        ),
        "{text}"
    );
    let (_, out, _) = tendyn(&["check", capstan, "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["sliding_check"],
        serde_json::json!({"covers": "every_factor", "boxes": 1})
    );
    let plain = "examples/mechanisms/example2_open_ended.ron";
    let (_, text, _) = tendyn(&["check", plain]);
    assert!(!text.contains("controllable with this friction"), "{text}");
    let (_, out, _) = tendyn(&["check", plain, "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["sliding_check"],
        serde_json::json!({"covers": "constant"})
    );
}
