//! Bad input gets a clear error and no output: every kind of mistake a mechanism file or a
//! solver state can hold is rejected with an error that names the offending item, the line
//! it is defined on, and what is wrong. Each test starts from a small valid mechanism (the
//! paper's Examples 1 and 2), breaks one thing and checks the error.

use tendyn_core::error::Location;
use tendyn_core::{load, parse, Data, Error};

/// Paper Example 2: a planar 2-DOF arm driven by three open-ended tendons.
const OPEN_ENDED: &str = r#"(
    name: "open_ended",
    gravity: (0.0, -9.81, 0.0),
    tension_floor: 5.0,
    links: [
        (
            name: "link1",
            dh: (a: 0.30, alpha: 0.0, d: 0.0),
            mass: 1.2,
            com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009),
        ),
        (
            name: "link2",
            dh: (a: 0.25, alpha: 0.0, d: 0.0),
            mass: 0.8,
            com: (-0.125, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667),
        ),
    ],
    pulleys: [
        (name: "drum2a", carrier: "link2", at: Joint(joint: "link2", height: 0.01), radius: 0.02, fixed: true),
        (name: "drum2b", carrier: "link2", at: Joint(joint: "link2", height: -0.01), radius: 0.02, fixed: true),
        (name: "drum1", carrier: "link1", at: Joint(joint: "link1", height: 0.0), radius: 0.04, fixed: true),
        (
            name: "idler3",
            carrier: "base",
            at: Joint(joint: "link1", height: 0.01),
            radius: 0.03,
            mass: 0.05,
            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),
        ),
        (
            name: "idler4",
            carrier: "base",
            at: Joint(joint: "link1", height: -0.01),
            radius: 0.03,
            mass: 0.05,
            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),
        ),
    ],
    tendons: [
        (name: "T32", route: [("drum2a", Ccw), ("idler3", Cw)], exit: (-0.25, 0.05, 0.01)),
        (name: "T42", route: [("drum2b", Cw), ("idler4", Cw)], exit: (-0.25, -0.05, -0.01)),
        (name: "T11", route: [("drum1", Ccw)], exit: (-0.25, 0.10, 0.0)),
    ],
)
"#;

/// Paper Example 1: the same arm driven by a motor on joint 1 and an endless loop.
const ENDLESS: &str = r#"(
    name: "endless",
    gravity: (0.0, -9.81, 0.0),
    links: [
        (name: "link1", dh: (a: 0.30, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "link2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)),
    ],
    pulleys: [
        (name: "pulley3", carrier: "base", at: Joint(joint: "link1", height: 0.02), radius: 0.03,
            mass: 0.1, inertia: (xx: 0.0000225, yy: 0.0000225, zz: 0.000045)),
        (name: "drum2", carrier: "link2", at: Joint(joint: "link2", height: 0.02), radius: 0.02, fixed: true),
    ],
    loops: [
        (name: "belt", driven: "drum2", driving: "pulley3", crossed: false, pretension: 20.0),
    ],
    motors: [
        (name: "motor1", on: Joint("link1")),
        (name: "motor3", on: Pulley("pulley3")),
    ],
)
"#;

/// `text` with `from`, which must occur in it exactly once, replaced by `to`.
fn with(text: &str, from: &str, to: &str) -> String {
    assert_eq!(
        text.matches(from).count(),
        1,
        "`{from}` must occur exactly once in the base mechanism"
    );
    text.replacen(from, to, 1)
}

/// The 1-based number of the one line of `text` that contains `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    let hits: Vec<usize> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.contains(needle))
        .map(|(i, _)| i + 1)
        .collect();
    assert_eq!(hits.len(), 1, "`{needle}` must be on exactly one line");
    hits[0]
}

fn rejected(text: &str) -> Error {
    match parse(text) {
        Ok(_) => panic!("accepted a bad mechanism:\n{text}"),
        Err(e) => e,
    }
}

/// The error is about `item`, located on the line holding `defined_by`, and says `phrase`.
fn assert_names(err: &Error, text: &str, item: &str, defined_by: &str, phrase: &str) {
    let shown = err.to_string();
    let at = match err {
        Error::Invalid { at, .. } | Error::Routing { at, .. } => *at,
        other => panic!("expected an error about an item, got {other:?}"),
    };
    assert_eq!(err.item(), Some(item), "wrong item in: {shown}");
    assert!(shown.starts_with(item), "item not named first in: {shown}");
    let line = line_of(text, defined_by);
    assert_eq!(at.line, line, "wrong line in: {shown}");
    assert!(
        shown.contains(&format!("(line {line}, column {})", at.column)),
        "location not shown in: {shown}"
    );
    assert!(shown.contains(phrase), "`{phrase}` not said in: {shown}");
}

fn assert_invalid(text: &str, item: &str, defined_by: &str, phrase: &str) -> Error {
    let err = rejected(text);
    assert!(matches!(err, Error::Invalid { .. }), "{err:?}");
    assert_names(&err, text, item, defined_by, phrase);
    err
}

fn assert_routing(text: &str, item: &str, defined_by: &str, phrase: &str) -> Error {
    let err = rejected(text);
    assert!(matches!(err, Error::Routing { .. }), "{err:?}");
    assert_names(&err, text, item, defined_by, phrase);
    err
}

fn assert_syntax(text: &str, line: usize, column: usize, phrase: &str) {
    match rejected(text) {
        Error::Syntax {
            line: l,
            column: c,
            message,
        } => {
            let shown = rejected(text).to_string();
            assert_eq!((l, c), (line, column), "wrong position in: {shown}");
            assert!(
                shown.contains(&format!("line {line}, column {column}")),
                "position not shown in: {shown}"
            );
            assert!(message.contains(phrase), "`{phrase}` not said in: {shown}");
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

/// 1-based column of `needle` in the one line that holds it.
fn column_of(text: &str, needle: &str) -> usize {
    let line = text.lines().nth(line_of(text, needle) - 1).unwrap();
    line[..line.find(needle).unwrap()].chars().count() + 1
}

#[test]
fn the_base_mechanisms_are_valid() {
    parse(OPEN_ENDED).unwrap();
    parse(ENDLESS).unwrap();
}

// 1. RON syntax.

#[test]
fn ron_syntax_error_is_reported_at_the_line_and_column_of_the_offending_token() {
    let text = with(OPEN_ENDED, "mass: 0.8,", "mass: 0.8 @,");
    let (line, column) = (line_of(&text, "@"), column_of(&text, "@"));
    assert_syntax(&text, line, column, "Expected comma, found `@,`");
}

#[test]
fn a_value_of_the_wrong_type_is_reported_at_the_value_not_at_the_space_before_it() {
    // (`a` is geometry, which cannot name a runtime parameter.)
    let text = with(OPEN_ENDED, "dh: (a: 0.25,", "dh: (a: \"long\",");
    let (line, column) = (line_of(&text, "long"), column_of(&text, "\"long\""));
    assert_syntax(&text, line, column, "Expected float");
}

#[test]
fn a_mass_that_is_neither_a_number_nor_a_name_says_what_it_may_be_at_the_value() {
    // A mass may be a number or a parameter's name; serde's untagged-enum message
    // ("did not match any variant of untagged enum Num") named an internal type and pointed
    // past the value.
    let text = with(OPEN_ENDED, "mass: 0.8,", "mass: [0.8],");
    let (line, column) = (line_of(&text, "[0.8]"), column_of(&text, "[0.8]"));
    assert_syntax(
        &text,
        line,
        column,
        "a number or the name of a declared parameter",
    );
    assert!(!rejected(&text).to_string().contains("untagged"));
}

/// The fuzzer found that 300 nested brackets made ron give up with advice for a Rust
/// developer (`ron::Options::recursion_limit`, `serde_stacker`): the untagged number type
/// buffered them. Read as what a field takes, the first bracket is the error.
#[test]
fn deeply_nested_brackets_are_reported_at_the_first_one_without_advice_for_a_rust_developer() {
    let text = with(
        OPEN_ENDED,
        "mass: 0.8,",
        &format!("mass: {}0.8,", "[".repeat(300)),
    );
    let (line, column) = (line_of(&text, "[[["), column_of(&text, "[[["));
    assert_syntax(
        &text,
        line,
        column,
        "a number or the name of a declared parameter",
    );
    let shown = rejected(&text).to_string();
    assert!(
        !shown.contains("serde_stacker") && !shown.contains("recursion_limit"),
        "{shown}"
    );
}

#[test]
fn an_empty_mechanism_name_is_rejected_as_the_mechanism_s_at_its_line() {
    let text = with(OPEN_ENDED, "name: \"open_ended\"", "name: \"\"");
    let err = rejected(&text);
    assert!(matches!(err, Error::Invalid { .. }), "{err:?}");
    let shown = err.to_string();
    assert!(
        shown.starts_with("the mechanism (line 2, column"),
        "{shown}"
    );
    assert!(shown.contains("`name` is empty"), "{shown}");
}

#[test]
fn an_item_with_an_empty_name_is_rejected_at_its_line_saying_so() {
    let text = with(OPEN_ENDED, "name: \"idler4\"", "name: \"\"");
    let text = text.replace("(\"idler4\", Cw)", "(\"\", Cw)");
    let err = rejected(&text);
    let shown = err.to_string();
    let line = text
        .lines()
        .position(|l| l.trim() == "name: \"\",")
        .unwrap()
        + 1;
    assert!(
        shown.starts_with(&format!("an item (line {line}, column")),
        "{shown}"
    );
    assert!(shown.contains("`name` is empty"), "{shown}");
}

#[test]
fn a_mass_naming_an_undeclared_parameter_is_rejected_naming_the_link_and_the_parameter() {
    let text = with(OPEN_ENDED, "mass: 0.8,", "mass: \"payload\",");
    assert_invalid(
        &text,
        "link2",
        "name: \"link2\"",
        "names the parameter `payload`, which is not declared",
    );
}

#[test]
fn a_declared_parameter_that_nothing_uses_is_rejected() {
    let text = with(
        OPEN_ENDED,
        "tension_floor: 5.0,",
        "tension_floor: 5.0,\n    parameters: [(name: \"spare\", value: 1.0)],",
    );
    let err = rejected(&text);
    assert_eq!(err.item(), Some("spare"), "{err}");
    assert!(
        err.to_string().contains("declared but no number uses it"),
        "{err}"
    );
}

#[test]
fn a_missing_comma_at_the_end_of_a_line_is_reported_with_the_line_it_is_missing_from() {
    let text = with(OPEN_ENDED, "mass: 0.8,", "mass: 0.8");
    let next = line_of(&text, "com: (-0.125, 0.0, 0.0)");
    assert_syntax(
        &text,
        next,
        column_of(&text, "com: (-0.125"),
        &format!(
            "a comma is missing at the end of line {}",
            line_of(&text, "mass: 0.8")
        ),
    );
}

#[test]
fn a_missing_field_is_reported_at_the_end_of_its_item_naming_the_field() {
    let text = with(OPEN_ENDED, "            mass: 0.8,\n", "");
    // The item ends on the line after link2's inertia.
    let end = line_of(&text, "inertia: (xx: 0.0001,") + 1;
    assert_syntax(
        &text,
        end,
        9,
        "missing field named `mass` in `LinkSpec`: the item that ends here needs a `mass: ...` entry",
    );
}

// 2. Unknown and duplicate names.

#[test]
fn a_route_naming_a_pulley_that_does_not_exist_is_rejected_naming_the_tendon() {
    let text = with(OPEN_ENDED, "(\"idler3\", Cw)", "(\"idler33\", Cw)");
    let err = assert_routing(
        &text,
        "T32",
        "name: \"T32\"",
        "its route names `idler33`, which is not a pulley",
    );
    assert!(
        err.to_string().contains("`idler3`"),
        "no candidates in: {err}"
    );
}

#[test]
fn a_motor_on_a_link_that_does_not_exist_is_rejected_naming_the_motor() {
    let text = with(ENDLESS, "on: Joint(\"link1\")", "on: Joint(\"link3\")");
    assert_invalid(
        &text,
        "motor1",
        "name: \"motor1\"",
        "`link3` is not a link; a `Joint` motor names the link its joint moves (the links are `link1`, `link2`)",
    );
}

#[test]
fn a_loop_naming_a_pulley_that_does_not_exist_is_rejected_naming_the_loop() {
    let text = with(ENDLESS, "driving: \"pulley3\"", "driving: \"pulley4\"");
    assert_routing(&text, "belt", "name: \"belt\"", "`pulley4` is not a pulley");
}

#[test]
fn a_duplicate_name_is_rejected_at_its_second_definition() {
    let text = with(OPEN_ENDED, "(name: \"T11\"", "(name: \"T32\"");
    let err = rejected(&text);
    assert!(matches!(err, Error::Invalid { .. }), "{err:?}");
    let second = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.contains("(name: \"T32\""))
        .map(|(i, _)| i + 1)
        .collect::<Vec<_>>();
    assert_eq!(second.len(), 2);
    let Error::Invalid { item, at, .. } = &err else {
        unreachable!()
    };
    assert_eq!((item.as_str(), at.line), ("T32", second[1]), "{err}");
    let shown = err.to_string();
    assert!(
        shown.contains(&format!(
            "the name `T32` is used twice (first at line {})",
            second[0]
        )),
        "{shown}"
    );
    assert!(shown.contains("rename one of them"), "{shown}");
}

#[test]
fn an_item_named_base_is_rejected_because_base_is_the_ground() {
    let text = with(OPEN_ENDED, "name: \"idler4\"", "name: \"base\"");
    assert_invalid(
        &text,
        "base",
        "name: \"base\"",
        "`base` is the ground and cannot name an item",
    );
}

// 3. Carriers.

#[test]
fn a_carrier_that_does_not_exist_is_rejected_naming_the_pulley() {
    let text = with(
        OPEN_ENDED,
        "(name: \"drum1\", carrier: \"link1\"",
        "(name: \"drum1\", carrier: \"link0\"",
    );
    assert_invalid(
        &text,
        "drum1",
        "name: \"drum1\"",
        "its carrier `link0` does not exist; a carrier is `base` or a link name",
    );
}

// 4. Masses.

#[test]
fn a_negative_mass_is_rejected_naming_the_link() {
    let text = with(OPEN_ENDED, "mass: 0.8,", "mass: -0.8,");
    assert_invalid(
        &text,
        "link2",
        "mass: -0.8,",
        "mass is -0.8 kg; a mass must be positive",
    );
}

#[test]
fn a_zero_mass_with_an_inertia_is_rejected_naming_the_pulley() {
    let text = with(
        OPEN_ENDED,
        "radius: 0.03,\n            mass: 0.05,\n            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),\n        ),\n        (\n            name: \"idler4\"",
        "radius: 0.03,\n            mass: 0.0,\n            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),\n        ),\n        (\n            name: \"idler4\"",
    );
    assert_invalid(
        &text,
        "idler3",
        "mass: 0.0,",
        "mass is zero but the inertia is not",
    );
}

#[test]
fn the_line_is_that_of_the_definition_even_where_the_name_is_referenced_first() {
    // Pulleys listed before links: `carrier: "link1"` and `joint: "link1"` come first.
    let links_start = OPEN_ENDED.find("    links: [").unwrap();
    let pulleys_start = OPEN_ENDED.find("    pulleys: [").unwrap();
    let tendons_start = OPEN_ENDED.find("    tendons: [").unwrap();
    let reordered = format!(
        "{}{}{}{}",
        &OPEN_ENDED[..links_start],
        &OPEN_ENDED[pulleys_start..tendons_start],
        &OPEN_ENDED[links_start..pulleys_start],
        &OPEN_ENDED[tendons_start..]
    );
    parse(&reordered).unwrap();
    let text = with(&reordered, "mass: 1.2,", "mass: -1.2,");
    assert_invalid(&text, "link1", "mass: -1.2,", "mass is -1.2 kg");
}

/// A value just below zero is shown as it was written, not as 300 digits: a mass, the
/// default tension floor and a loop's pretension.
#[test]
fn a_tiny_negative_number_is_shown_with_its_exponent() {
    for (text, phrase) in [
        (
            with(OPEN_ENDED, "mass: 1.2,", "mass: -1e-300,"),
            "mass is -1e-300 kg;",
        ),
        (
            with(OPEN_ENDED, "tension_floor: 5.0,", "tension_floor: -1e-300,"),
            "`tension_floor` is -1e-300 N;",
        ),
        (
            with(ENDLESS, "pretension: 20.0", "pretension: -1e-300"),
            "pretension is -1e-300 N;",
        ),
    ] {
        let shown = rejected(&text).to_string();
        assert!(shown.contains(phrase), "{shown}");
    }
}

// 5. Inertias.

#[test]
fn an_inertia_that_is_not_positive_semidefinite_is_rejected_naming_the_link() {
    let text = with(
        OPEN_ENDED,
        "inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)",
        "inertia: (xx: 0.0002, yy: 0.009, zz: 0.009, yz: 0.01)",
    );
    assert_invalid(
        &text,
        "link1",
        "yz: 0.01)",
        "inertia is not positive semi-definite",
    );
}

#[test]
fn inertia_violating_the_triangle_inequality_is_rejected_naming_the_link() {
    let text = with(
        OPEN_ENDED,
        "inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)",
        "inertia: (xx: 0.0001, yy: 0.001, zz: 0.0041667)",
    );
    assert_invalid(
        &text,
        "link2",
        "yy: 0.001, zz",
        "violate the triangle inequality",
    );
}

// 6. Pulley radii.

#[test]
fn a_zero_pulley_radius_is_rejected_naming_the_pulley() {
    let text = with(OPEN_ENDED, "radius: 0.04", "radius: 0.0");
    assert_invalid(
        &text,
        "drum1",
        "name: \"drum1\"",
        "radius is 0 m; a pitch radius must be positive",
    );
}

#[test]
fn a_negative_pulley_radius_is_rejected_naming_the_pulley() {
    let text = with(OPEN_ENDED, "radius: 0.04", "radius: -0.04");
    assert_invalid(
        &text,
        "drum1",
        "name: \"drum1\"",
        "radius is -0.04 m; a pitch radius must be positive",
    );
}

// 7. Anchors.

#[test]
fn a_route_whose_first_pulley_is_not_a_fixed_anchor_is_rejected_naming_the_tendon() {
    let text = with(
        OPEN_ENDED,
        "route: [(\"drum2b\", Cw), (\"idler4\", Cw)]",
        "route: [(\"idler4\", Cw), (\"drum2b\", Cw)]",
    );
    assert_routing(
        &text,
        "T42",
        "name: \"T42\"",
        "its route must start on an anchor (a `fixed: true` drum on a link), but `idler4` turns \
         freely; list the anchor drum first",
    );
}

// 8. Rank of the structure matrix.

#[test]
fn a_joint_nothing_acts_on_is_rejected_naming_the_joint() {
    let text = r#"(
    name: "idle_elbow",
    links: [
        (name: "link1", dh: (a: 0.30, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "link2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)),
    ],
    pulleys: [
        (name: "drum1a", carrier: "link1", at: Joint(joint: "link1", height: 0.0), radius: 0.04, fixed: true),
        (name: "drum1b", carrier: "link1", at: Joint(joint: "link1", height: 0.01), radius: 0.03, fixed: true),
    ],
    tendons: [
        (name: "T1", route: [("drum1a", Ccw)], exit: (-0.25, 0.10, 0.0)),
        (name: "T2", route: [("drum1b", Cw)], exit: (-0.25, -0.10, 0.01)),
    ],
)
"#;
    assert_routing(
        text,
        "link2",
        "name: \"link2\"",
        "the structure matrix does not have full row rank: joint `link2` is acted on by no \
         tendon or motor",
    );
}

#[test]
fn two_joints_driven_identically_are_rejected_naming_both_joints() {
    let text = r#"(
    name: "lockstep",
    links: [
        (name: "link1", dh: (a: 0.30, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "link2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)),
    ],
    tendons: [
        (name: "Ta", structure: [0.02, 0.02]),
        (name: "Tb", structure: [-0.01, -0.01]),
        (name: "Tc", structure: [0.03, 0.03]),
    ],
)
"#;
    assert_routing(
        text,
        "link1",
        "name: \"link1\"",
        "the balances of joint `link1` and joint `link2` are not independent",
    );
}

#[test]
fn a_joint_acted_on_numerically_nothing_beside_the_others_is_rejected_naming_the_joint() {
    let text = r#"(
    name: "lopsided",
    links: [
        (name: "link1", dh: (a: 0.30, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "link2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)),
    ],
    tendons: [
        (name: "Ta", structure: [0.02, 2e-12]),
        (name: "Tb", structure: [-0.01, -1e-12]),
        (name: "Tc", structure: [0.03, -3e-12]),
    ],
)
"#;
    assert_routing(
        text,
        "link2",
        "name: \"link2\"",
        "joint `link2` is acted on so much more weakly than the others",
    );
}

#[test]
fn a_motor_that_can_trade_against_redundant_tendons_is_rejected_naming_the_motor() {
    let text = with(
        OPEN_ENDED,
        "    tendons: [",
        "    motors: [(name: \"m1\", on: Joint(\"link1\"))],\n    tendons: [",
    );
    assert_routing(
        &text,
        "m1",
        "name: \"m1\"",
        "motor `m1` is not determined by the dynamics",
    );
}

// 9. Controllability of open-ended routings.

#[test]
fn a_joint_all_tendons_pull_the_same_way_is_not_controllable_and_the_message_says_why() {
    // T11 reversed: all three tendons now turn joint 1 the same way.
    let text = with(OPEN_ENDED, "[(\"drum1\", Ccw)]", "[(\"drum1\", Cw)]");
    assert_routing(
        &text,
        "link1",
        "name: \"link1\"",
        "not controllable by tendons: every tendon acting on joint `link1` (`T32`, `T42`, `T11`) \
         pulls it the same way",
    );
    assert!(rejected(&text)
        .to_string()
        .contains("no strictly positive null vector"));
}

/// Two joints and three tendons none of which pulls a joint one way only, yet no taut
/// tensions balance: `a (1, 1) + b (1, −1) + c (−1, 2) = 0` forces `c = −2a`. On the
/// combination `2·link1 + link2` the tendons give 3, 1 and 0: all one way.
const COMBINATION_ONE_SIDED: &str = r#"(
    name: "one_sided_combination",
    links: [
        (name: "link1", dh: (a: 0.30, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "link2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)),
    ],
    tendons: [
        (name: "Ta", structure: [0.01, 0.01]),
        (name: "Tb", structure: [0.01, -0.01]),
        (name: "Tc", structure: [-0.01, 0.02]),
    ],
)
"#;

#[test]
fn a_combination_of_joints_every_tendon_pulls_one_way_is_named_with_the_tendons() {
    let err = assert_routing(
        COMBINATION_ONE_SIDED,
        "link1",
        "name: \"link1\"",
        "not controllable by tendons: on the combination",
    );
    let shown = err.to_string();
    assert!(shown.contains("every tendon pulls the same way"), "{shown}");
    // Each tendon's pull on the combination y: Ta and Tb pull it, Tc does not act on it, or
    // all three pull; never one against.
    let (y1, y2) = {
        let part = |joint: &str| -> f64 {
            let at = shown
                .find(&format!("·joint `{joint}`"))
                .expect("joint in combination");
            let start = shown[..at].rfind(['+', '-']).unwrap();
            shown[start..at].parse().unwrap()
        };
        (part("link1"), part("link2"))
    };
    for (a1, a2) in [(0.01, 0.01), (0.01, -0.01), (-0.01, 0.02)] {
        assert!(
            a1 * y1 + a2 * y2 >= -1e-12,
            "a tendon pushes back on y = ({y1}, {y2})"
        );
    }
    // The system is there for `check` to print, with its rows and columns named.
    let implied = err.implied().expect("the implied tension system");
    assert_eq!(implied.rows, ["joint link1", "joint link2"]);
    assert_eq!(implied.unknowns, ["tension Ta", "tension Tb", "tension Tc"]);
    assert_eq!(implied.matrix[1][2], 0.02);
}

#[test]
fn as_many_tendons_as_joints_is_not_controllable_and_the_message_says_why() {
    let text = with(
        OPEN_ENDED,
        "        (name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0)),\n",
        "",
    );
    assert_routing(
        &text,
        "open_ended",
        "name: \"open_ended\"",
        "not controllable by tendons: as many tendon tensions as balances, so the dynamics fixes \
         every tension and some must push",
    );
}

// 10. Non-finite numbers.

#[test]
fn infinite_and_nan_literals_in_the_file_are_rejected_naming_the_item() {
    for (from, to, item, field) in [
        ("mass: 0.8,", "mass: inf,", "link2", "`mass` is inf"),
        ("mass: 1.2,", "mass: -inf,", "link1", "`mass` is -inf"),
        ("radius: 0.04", "radius: NaN", "drum1", "`radius` is NaN"),
        (
            "d: 0.0),\n            mass: 0.8",
            "d: NaN),\n            mass: 0.8",
            "link2",
            "`dh` is NaN",
        ),
        (
            "exit: (-0.25, 0.10, 0.0)",
            "exit: (-0.25, inf, 0.0)",
            "T11",
            "`exit` is inf",
        ),
        (
            "yy: 0.00001125, zz: 0.0000225),\n        ),\n    ],",
            "yy: NaN, zz: 0.0000225),\n        ),\n    ],",
            "idler4",
            "`inertia` is NaN",
        ),
    ] {
        let text = with(OPEN_ENDED, from, to);
        // At the line of the number.
        let line = to.lines().next().unwrap();
        let err = assert_invalid(&text, item, line, "every number must be finite");
        assert!(err.to_string().contains(field), "{err}");
    }
}

#[test]
fn a_non_finite_gravity_is_rejected_at_the_gravity_line() {
    let text = with(
        OPEN_ENDED,
        "gravity: (0.0, -9.81, 0.0)",
        "gravity: (0.0, NaN, 0.0)",
    );
    let err = rejected(&text);
    assert_eq!(err.item(), Some("open_ended"));
    let Error::Invalid { at, .. } = &err else {
        panic!("{err:?}")
    };
    assert_eq!(
        *at,
        Location {
            line: line_of(&text, "gravity:"),
            column: 5
        }
    );
    assert!(err
        .to_string()
        .contains("`gravity` is NaN; every number must be finite"));
}

#[test]
fn a_radius_too_small_to_turn_its_pulley_at_a_finite_rate_is_rejected_naming_the_pulley() {
    // A subnormal radius passes `radius > 0` but the routing would turn the idler at an
    // infinite rate: the model would hold non-finite couplings. It is below the smallest
    // pitch radius (format.md §12), which is what the error says.
    let text = with(
        OPEN_ENDED,
        "height: 0.01),\n            radius: 0.03,",
        "height: 0.01),\n            radius: 1e-320,",
    );
    assert_invalid(
        &text,
        "idler3",
        "radius: 1e-320,",
        "`radius` is 1e-320 m, below the smallest pitch radius of 1e-9 m",
    );
}

#[test]
fn a_negative_default_tension_floor_is_rejected_at_the_tension_floor_line() {
    let text = with(OPEN_ENDED, "tension_floor: 5.0", "tension_floor: -5.0");
    let err = rejected(&text);
    assert_eq!(err.item(), Some("open_ended"));
    let Error::Invalid { at, .. } = &err else {
        panic!("{err:?}")
    };
    assert_eq!(at.line, line_of(&text, "tension_floor:"), "{err}");
    assert!(
        err.to_string()
            .contains("`tension_floor` is -5 N; the tension floor must not be negative"),
        "{err}"
    );
}

#[test]
fn an_external_wrench_on_a_link_that_does_not_exist_is_rejected_at_the_wrench() {
    // Each bad wrench is reported at the `external_wrench:` line, saying what is wrong.
    for (wrench, phrase) in [
        (
            "(link: \"link3\", force: (1.0, 0.0, 0.0))",
            "external_wrench names `link3`, which is not a link",
        ),
        (
            "(link: \"link2\", force: (NaN, 0.0, 0.0))",
            "`external_wrench` on `link2` has NaN in it; every number must be finite",
        ),
    ] {
        let text = with(
            OPEN_ENDED,
            "    tendons: [",
            &format!("    external_wrench: {wrench},\n    tendons: ["),
        );
        let err = rejected(&text);
        let Error::Invalid { at, .. } = &err else {
            panic!("{err:?}")
        };
        assert_eq!(at.line, line_of(&text, "external_wrench:"), "{err}");
        assert!(err.to_string().contains(phrase), "{err}");
    }
}

#[test]
fn a_nan_in_the_state_is_rejected_naming_the_vector_and_entry() {
    let model = parse(OPEN_ENDED).unwrap();
    let mut solver = Data::new(&model);
    let ok = [0.1, 0.2];
    for (q, qd, qdd, named) in [
        ([f64::NAN, 0.2], ok, ok, "q[0] is NaN"),
        (ok, [0.1, f64::INFINITY], ok, "qd[1] is inf"),
        (ok, ok, [f64::NEG_INFINITY, 0.0], "qdd[0] is -inf"),
    ] {
        match solver.inverse_dynamics(&model, &q, &qd, &qdd) {
            Err(e @ Error::State(_)) => {
                let shown = e.to_string();
                assert!(shown.contains(named), "{shown}");
                assert!(shown.contains("every entry must be finite"), "{shown}");
            }
            other => panic!("expected a state error, got {other:?}"),
        }
    }
    match solver.forward_dynamics(&model, &ok, &ok, &[], &[10.0, f64::NAN, 10.0]) {
        Err(e @ Error::State(_)) => assert!(e.to_string().contains("tendon tension is NaN"), "{e}"),
        other => panic!("expected a state error, got {other:?}"),
    }
}

#[test]
fn a_state_of_the_wrong_length_is_rejected_naming_the_vector() {
    let model = parse(OPEN_ENDED).unwrap();
    let mut solver = Data::new(&model);
    let ok = [0.1, 0.2];
    for (q, qd, qdd, named) in [
        (&[0.1][..], &ok[..], &ok[..], "q has 1 entries"),
        (&ok[..], &[0.1, 0.2, 0.3][..], &ok[..], "qd has 3 entries"),
        (&ok[..], &ok[..], &[][..], "qdd has 0 entries"),
    ] {
        match solver.inverse_dynamics(&model, q, qd, qdd) {
            Err(e @ Error::State(_)) => {
                let shown = e.to_string();
                assert!(shown.contains(named), "{shown}");
                assert!(shown.contains("but the mechanism has 2 joints"), "{shown}");
            }
            other => panic!("expected a state error, got {other:?}"),
        }
    }
}

// 11. Routing geometry and explicit data that contradicts it.

#[test]
fn an_explicit_coupling_that_disagrees_with_the_routing_is_rejected_naming_the_pulley() {
    let text = with(
        OPEN_ENDED,
        "at: Joint(joint: \"link1\", height: 0.01),\n            radius: 0.03,",
        "at: Joint(joint: \"link1\", height: 0.01),\n            radius: 0.03,\n            coupling: [5.0, 5.0],",
    );
    assert_routing(
        &text,
        "idler3",
        "name: \"idler3\"",
        "its explicit coupling [5.0, 5.0] disagrees with the routing",
    );
}

#[test]
fn an_explicit_structure_column_that_disagrees_with_the_route_is_rejected_naming_the_tendon() {
    let text = with(
        OPEN_ENDED,
        "exit: (-0.25, 0.10, 0.0))",
        "exit: (-0.25, 0.10, 0.0), structure: [0.0, 0.04])",
    );
    assert_routing(
        &text,
        "T11",
        "name: \"T11\"",
        "its explicit structure column [0.0, 0.04] disagrees with its route",
    );
}

#[test]
fn overlapping_pulleys_with_no_common_tangent_are_rejected_naming_the_tendon() {
    // idler3 (on joint 1's axis) grown until it overlaps drum2a (on joint 2's, 0.30 m away).
    let text = with(
        OPEN_ENDED,
        "height: 0.01),\n            radius: 0.03,",
        "height: 0.01),\n            radius: 0.29,",
    );
    assert_routing(
        &text,
        "T32",
        "name: \"T32\"",
        "segment from pulley `drum2a` to pulley `idler3`: no common tangent on the given sides",
    );
}

#[test]
fn a_pulley_on_a_joint_axis_carried_by_a_body_that_joint_does_not_connect_is_rejected() {
    // idler4 rides on the base but is put on joint 2's axis (between link 1 and link 2).
    let text = with(
        OPEN_ENDED,
        "at: Joint(joint: \"link1\", height: -0.01)",
        "at: Joint(joint: \"link2\", height: -0.01)",
    );
    assert_invalid(
        &text,
        "idler4",
        "name: \"idler4\"",
        "sits on the axis of joint `link2` but is carried by `base`; a pulley on a joint axis is \
         carried by one of the two bodies that joint connects (`link1` or `link2`)",
    );
}

#[test]
fn an_unreadable_file_path_is_reported_with_the_path() {
    match load("/nonexistent.ron") {
        Err(e @ Error::Io { .. }) => {
            let Error::Io { path, .. } = &e else {
                unreachable!()
            };
            assert_eq!(path, "/nonexistent.ron");
            assert!(
                e.to_string().starts_with("cannot read /nonexistent.ron: "),
                "{e}"
            );
        }
        other => panic!("expected an I/O error, got {other:?}"),
    }
}

/// A joint that only one tendon acts on, while the other joint is redundantly driven.
const ONE_TENDON_ON_JOINT2: &str = r#"(
    name: "lonely",
    gravity: (0.0, 0.0, -9.81),
    tension_floor: 1.0,
    links: [
        (name: "link1", dh: (a: 0.30, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0), inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "link2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0), inertia: (xx: 0.0001, yy: 0.004, zz: 0.004)),
    ],
    pulleys: [
        (name: "drum2", carrier: "link2", at: Joint(joint: "link2", height: 0.01), radius: 0.02, fixed: true),
        (name: "drum1", carrier: "link1", at: Joint(joint: "link1", height: 0.0), radius: 0.04, fixed: true),
        (name: "idler", carrier: "base", at: Joint(joint: "link1", height: 0.01), radius: 0.03, mass: 0.05, inertia: (xx: 0.00001, yy: 0.00001, zz: 0.00002)),
    ],
    tendons: [
        (name: "tA", route: [("drum2", Ccw), ("idler", Cw)], exit: (-0.25, 0.05, 0.01)),
        (name: "tB", route: [("drum1", Cw)], exit: (-0.25, -0.10, 0.0)),
        (name: "tC", route: [("drum1", Ccw)], exit: (-0.25, 0.10, 0.0)),
    ],
)"#;

#[test]
fn a_joint_that_one_tendon_alone_pulls_is_not_controllable_even_when_another_joint_is_redundant() {
    // The null space is one-dimensional but has no component on tA: its tension is fixed
    // by joint 2's dynamics and would have to push half the time.
    assert_routing(
        ONE_TENDON_ON_JOINT2,
        "link2",
        "name: \"link2\"",
        "every tendon acting on joint `link2` (`tA`) pulls it the same way",
    );
}

#[test]
fn an_exit_point_without_a_route_is_rejected_naming_the_tendon() {
    let text = with(
        OPEN_ENDED,
        "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0)),",
        "(name: \"T11\", structure: [0.04, 0.0], exit: (-0.25, 0.10, 0.0)),",
    );
    assert_routing(
        &text,
        "T11",
        "name: \"T11\"",
        "has an `exit` but no `route`",
    );
}

#[test]
fn a_negative_default_floor_is_rejected_even_when_every_tendon_overrides_it() {
    let text = with(OPEN_ENDED, "tension_floor: 5.0,", "tension_floor: -5.0,")
        .replace(
            "exit: (-0.25, 0.05, 0.01))",
            "exit: (-0.25, 0.05, 0.01), floor: 1.0)",
        )
        .replace(
            "exit: (-0.25, -0.05, -0.01))",
            "exit: (-0.25, -0.05, -0.01), floor: 1.0)",
        )
        .replace(
            "exit: (-0.25, 0.10, 0.0))",
            "exit: (-0.25, 0.10, 0.0), floor: 1.0)",
        );
    let err = rejected(&text);
    assert_eq!(err.item(), Some("open_ended"));
    assert!(err.to_string().contains("`tension_floor` is -5 N"), "{err}");
}

#[test]
fn a_name_with_a_slash_is_rejected() {
    let text = with(OPEN_ENDED, "name: \"T11\"", "name: \"T/11\"");
    assert_invalid(&text, "T/11", "name: \"T/11\"", "must not contain `/`");
}

// 12. Inputs that broke tendyn (found by fuzzing parse, solve and generate; issue 14). Each
// file in `mechanisms/reproducers/` says in its first line what it reproduced. Every one now
// gets a named error (item, line, what would fix it) or a correct result: no panic, no
// non-finite number inside an `Ok`.

/// The path and text of a reproducer.
fn reproducer(name: &str) -> (String, String) {
    let path = format!(
        "{}/mechanisms/reproducers/{name}.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap();
    (path, text)
}

/// A reproducer is rejected by `load` as `Error::Invalid` about `item`, at the line of its
/// definition, saying `phrase`; the message is returned.
fn reproducer_rejected(name: &str, item: &str, phrase: &str) -> String {
    let (path, text) = reproducer(name);
    let err = match load(&path) {
        Ok(_) => panic!("{name} accepted"),
        Err(e) => e,
    };
    assert!(matches!(err, Error::Invalid { .. }), "{name}: {err:?}");
    assert_names(&err, &text, item, &format!("name: \"{item}\""), phrase);
    err.to_string()
}

/// F01's one-link, one-motor mechanism with a sensible mass.
fn one_motor_link() -> tendyn_core::Model<f64> {
    let (_, text) = reproducer("F01-codegen-f32-constant-overflow-panic");
    parse(&with(&text, "mass: 1e39,", "mass: 0.5,")).unwrap()
}

fn generated(
    model: &tendyn_core::Model<f64>,
    scalar: tendyn_codegen::Scalar,
) -> Result<tendyn_codegen::Generated, tendyn_codegen::Error> {
    tendyn_codegen::generate(
        model,
        &tendyn_codegen::available_outputs(model),
        scalar,
        "bad_input",
    )
}

#[test]
fn f01_a_mass_f32_cannot_hold_is_rejected_naming_the_link_in_a_file_and_in_code() {
    let shown = reproducer_rejected(
        "F01-codegen-f32-constant-overflow-panic",
        "arm",
        "`mass` is 1e39 kg, beyond the range of a mass (at most 1e12 kg in size; format.md §12",
    );
    assert!(shown.contains("check its unit (kilograms)"), "{shown}");
    // Nor can a model hold it when built in code: models are immutable, and the
    // constructor checks what validation checks (code generation never sees such a mass).
    let err = rigid_link_with(|body| body.mass = 1e39).unwrap_err();
    assert!(
        err.to_string()
            .contains("`mass` is 1e39 kg, beyond the range of a mass"),
        "{err}"
    );
}

/// A joint that moves no mass has a zero pivot in `M`: generating forward dynamics for it
/// is refused naming that joint (the reproducer that found it: F01's link without mass,
/// `tendyn generate`, whose error named only an infinite constant), while what needs no
/// `M⁻¹` still generates.
#[test]
fn generating_forward_dynamics_names_the_joint_that_moves_no_mass() {
    let (_, text) = reproducer("F01-codegen-f32-constant-overflow-panic");
    let massless = parse(&with(&text, "mass: 1e39,", "mass: 0.0,")).unwrap();
    for scalar in [tendyn_codegen::Scalar::F64, tendyn_codegen::Scalar::F32] {
        let err = generated(&massless, scalar).unwrap_err().to_string();
        assert!(
            err.starts_with("output `forward_dynamics`:")
                && err.contains("joint `arm` moves nothing with mass or inertia")
                && err.contains("leave `forward_dynamics` out of the outputs"),
            "{err}"
        );
    }
    let inverse = [tendyn_codegen::Output::GeneralizedForces];
    tendyn_codegen::generate(
        &massless,
        &inverse,
        tendyn_codegen::Scalar::F64,
        "bad_input",
    )
    .unwrap();
}

/// The link of [`one_motor_link`] as a rigid tree built in code, changed by `change`.
fn rigid_link_with(
    change: impl FnOnce(&mut tendyn_core::model::Body<f64>),
) -> Result<tendyn_core::Model<f64>, Error> {
    let model = one_motor_link();
    let mut body = model.bodies()[0].clone();
    change(&mut body);
    let g = model.gravity().to_array();
    tendyn_core::Model::rigid_tree(model.name(), g, 1, vec![body], None)
}

#[test]
fn f01_a_folded_constant_f32_cannot_hold_is_an_error_naming_the_output() {
    // Every number within its range, but a heavy gear turning 1e15 times as fast as its
    // joint: its inertia about its axis enters the mass matrix as zz · 1e30 = 2e50, which f32
    // cannot hold.
    let text = r#"(
    name: "geared",
    links: [(name: "arm", dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: 0.5, com: (-0.1, 0.0, 0.0))],
    pulleys: [(name: "gear", carrier: "base", at: Joint(joint: "arm", height: 0.0), radius: 0.01,
        mass: 0.01, inertia: (xx: 1e20, yy: 1e20, zz: 2e20), coupling: [1e15])],
    motors: [(name: "m", on: Joint("arm"))],
)"#;
    let model = parse(text).unwrap();
    match generated(&model, tendyn_codegen::Scalar::F32) {
        Err(e @ tendyn_codegen::Error::Constant { .. }) => {
            let shown = e.to_string();
            assert!(shown.starts_with("output `"), "{shown}");
            assert!(
                shown.contains("a constant folded from the mechanism's numbers is")
                    && shown.contains("which f32 cannot hold"),
                "{shown}"
            );
        }
        other => panic!("expected a constant error, got {:?}", other.map(|_| ())),
    }
    generated(&model, tendyn_codegen::Scalar::F64).unwrap();
}

#[test]
fn f02_a_centre_of_mass_whose_square_overflows_is_rejected_naming_the_link_in_a_file_and_in_code() {
    reproducer_rejected(
        "F02-codegen-f64-folded-constant-overflow-panic",
        "arm",
        "`com` is -1e200 m, beyond the range of a length (at most 1e6 m in size",
    );
    // Built in code, the model is refused as well.
    let err = rigid_link_with(|body| body.com.x = -1e200).unwrap_err();
    assert!(
        err.to_string()
            .contains("`com` is -1e200 m, beyond the range of a length"),
        "{err}"
    );
}

#[test]
fn f03_a_drum_and_exit_whose_distance_overflows_are_rejected_naming_the_drum() {
    reproducer_rejected(
        "F03-validation-accepts-nan-segment-direction",
        "drum",
        "`height` is 1e308 m, beyond the range of a length (at most 1e6 m in size",
    );
}

#[test]
fn f04_an_exit_far_out_of_its_drums_plane_is_rejected_naming_the_tendon() {
    reproducer_rejected(
        "F04-validation-coplanarity-bypassed-by-huge-offset",
        "flex",
        "`exit` is 1e200 m, beyond the range of a length (at most 1e6 m in size",
    );
    // Within the range, the coplanarity test sees the offset.
    let (_, text) = reproducer("F04-validation-coplanarity-bypassed-by-huge-offset");
    let text = with(&text, "1e200)", "1e6)");
    assert_routing(
        &text,
        "flex",
        "name: \"flex\"",
        "the two circles are not in one plane",
    );
}

#[test]
fn f06_a_twist_too_large_to_resolve_is_rejected_not_snapped_to_a_right_angle() {
    let shown = reproducer_rejected(
        "F06-huge-twist-snapped-to-right-angle",
        "l1",
        "`alpha` is 1e300 rad, beyond the range of an angle (at most 1e3 rad in size",
    );
    assert!(shown.contains("reduce it modulo 2π"), "{shown}");
    // Within the range, a twist 100 turns away from -π/2 is that right angle exactly.
    let (path, text) = reproducer("F06-reference-twist-minus-90deg");
    let reference = load(&path).unwrap();
    let turned = -std::f64::consts::FRAC_PI_2 + 200.0 * std::f64::consts::PI;
    let model = parse(&with(
        &text,
        "alpha: -1.5707963267948966",
        &format!("alpha: {turned:?}"),
    ))
    .unwrap();
    let q = [0.4, -0.7];
    let m = Data::new(&model).mass_matrix(&model, &q).unwrap().to_vec();
    assert_eq!(
        m,
        Data::new(&reference).mass_matrix(&reference, &q).unwrap()
    );
}

#[test]
fn f07_a_radius_too_small_to_compute_with_is_rejected_naming_the_drum_not_as_uncontrollable() {
    let shown = reproducer_rejected(
        "F07-tiny-radius-misleading-not-controllable",
        "drum",
        "`radius` is 1e-163 m, below the smallest pitch radius of 1e-9 m",
    );
    assert!(!shown.contains("controllable"), "{shown}");
    assert!(shown.contains("check its unit (metres)"), "{shown}");
}

#[test]
fn c3_a_leading_byte_order_mark_is_skipped() {
    let (path, text) = reproducer("C3-byte-order-mark");
    assert!(text.starts_with('\u{feff}'));
    let with_mark = load(&path).unwrap();
    let without = parse(text.trim_start_matches('\u{feff}')).unwrap();
    let (q, qd, qdd) = ([0.3, -0.2], [1.0, 0.5], [2.0, -1.0]);
    let a = Data::new(&with_mark)
        .inverse_dynamics(&with_mark, &q, &qd, &qdd)
        .unwrap()
        .clone();
    let b = Data::new(&without)
        .inverse_dynamics(&without, &q, &qd, &qdd)
        .unwrap()
        .clone();
    assert_eq!(a.generalized_forces, b.generalized_forces);
    // Lines and columns are counted after the mark.
    let one_line =
        "(name: \"one\", links: [(name: \"arm\", dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: -1.0)])";
    let err = assert_invalid(
        &format!("\u{feff}{one_line}"),
        "arm",
        "name: \"arm\"",
        "mass is -1 kg",
    );
    let Error::Invalid { at, .. } = err else {
        unreachable!()
    };
    assert_eq!((at.line, at.column), (1, column_of(one_line, "mass: -1.0")));
}

#[test]
fn forward_dynamics_scale_checks_its_inputs_and_result_as_forward_dynamics_does() {
    let model = one_motor_link();
    let mut solver = Data::new(&model);
    let one = [1.0];
    for torques in [
        &[f64::INFINITY][..],
        &[f64::NAN][..],
        &[][..],
        &[1.0, 2.0, 3.0][..],
    ] {
        let scale = solver.forward_dynamics_scale(&model, &one, &one, torques, &[]);
        let fd = solver.forward_dynamics(&model, &one, &one, torques, &[]);
        assert!(
            matches!(scale, Err(Error::State(_))),
            "{torques:?}: {scale:?}"
        );
        assert_eq!(scale.unwrap_err(), fd.unwrap_err(), "{torques:?}");
    }
    for (q, qd) in [(&[f64::NAN][..], &one[..]), (&one[..], &[1.0, 2.0][..])] {
        let scale = solver.forward_dynamics_scale(&model, q, qd, &one, &[]);
        let fd = solver.forward_dynamics(&model, q, qd, &one, &[]);
        assert!(matches!(scale, Err(Error::State(_))), "{scale:?}");
        assert_eq!(scale.unwrap_err(), fd.unwrap_err());
    }
    // Finite inputs whose terms overflow.
    let scale = solver.forward_dynamics_scale(&model, &one, &[1e200], &one, &[]);
    assert!(matches!(scale, Err(Error::State(_))), "{scale:?}");
    // A valid state: a finite scale at least as large as the acceleration it bounds.
    let scale = solver
        .forward_dynamics_scale(&model, &one, &one, &[2.0], &[])
        .unwrap();
    let qdd = solver
        .forward_dynamics(&model, &one, &one, &[2.0], &[])
        .unwrap();
    assert!(
        scale.is_finite() && scale >= qdd[0].abs(),
        "{scale} {qdd:?}"
    );
    // A massless link: the mass matrix is singular for both.
    let (_, text) = reproducer("F01-codegen-f32-constant-overflow-panic");
    let massless = parse(&with(&text, "mass: 1e39,", "mass: 0.0,")).unwrap();
    let mut solver = Data::new(&massless);
    let scale = solver.forward_dynamics_scale(&massless, &one, &one, &one, &[]);
    assert!(matches!(scale, Err(Error::Singular(_))), "{scale:?}");
    assert_eq!(
        scale.unwrap_err(),
        solver
            .forward_dynamics(&massless, &one, &one, &one, &[])
            .unwrap_err()
    );
}

// 13. Ranges of magnitude (format.md §12): outside, a named error; at the edges, a model
// whose every result is finite.

#[test]
fn each_number_outside_its_range_of_magnitude_is_rejected_naming_the_item() {
    // An explicitly coupled gear placed by a pose.
    let with_pose = |text: &str| {
        with(
            text,
            "radius: 0.04, fixed: true),",
            "radius: 0.04, fixed: true),\n        (name: \"gear\", carrier: \"link1\", at: Pose(origin: (0.0, 0.0, -0.01), rpy: (0.0, 0.0, 0.0)), radius: 0.01, coupling: [1.0, 0.0]),",
        )
    };
    for (from, to, item, phrase) in [
        (
            "mass: 0.8,",
            "mass: 2e12,",
            "link2",
            "`mass` is 2e12 kg, beyond the range of a mass",
        ),
        (
            "inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)",
            "inertia: (xx: 1e25, yy: 1e25, zz: 1e25)",
            "link2",
            "`inertia` is 1e25 kg·m², beyond the range of an inertia entry (at most 1e24 kg·m²",
        ),
        (
            "com: (-0.125, 0.0, 0.0)",
            "com: (-0.125, 2e6, 0.0)",
            "link2",
            "`com` is 2e6 m, beyond the range of a length (at most 1e6 m",
        ),
        (
            "dh: (a: 0.25, alpha: 0.0, d: 0.0)",
            "dh: (a: 1e7, alpha: 0.0, d: 0.0)",
            "link2",
            "`a` is 1e7 m, beyond the range of a length",
        ),
        (
            "dh: (a: 0.25, alpha: 0.0, d: 0.0)",
            "dh: (a: 0.25, alpha: 0.0, d: -1.5e6)",
            "link2",
            "`d` is -1.5e6 m, beyond the range of a length",
        ),
        (
            "dh: (a: 0.25, alpha: 0.0, d: 0.0)",
            "dh: (a: 0.25, alpha: 1000.5, d: 0.0)",
            "link2",
            "`alpha` is 1000.5 rad, beyond the range of an angle (at most 1e3 rad",
        ),
        (
            "dh: (a: 0.25, alpha: 0.0, d: 0.0)",
            "dh: (a: 0.25, alpha: 0.0, d: 0.0, offset: -2e3)",
            "link2",
            "`offset` is -2000 rad, beyond the range of an angle",
        ),
        (
            "radius: 0.04",
            "radius: 1e-10",
            "drum1",
            "`radius` is 1e-10 m, below the smallest pitch radius of 1e-9 m",
        ),
        (
            "radius: 0.04",
            "radius: 3e6",
            "drum1",
            "`radius` is 3e6 m, beyond the range of a length",
        ),
        (
            "height: 0.0), radius: 0.04",
            "height: 1e9), radius: 0.04",
            "drum1",
            "`height` is 1e9 m, beyond the range of a length",
        ),
        (
            "exit: (-0.25, 0.10, 0.0)",
            "exit: (-1e7, 0.10, 0.0)",
            "T11",
            "`exit` is -1e7 m, beyond the range of a length",
        ),
    ] {
        let text = with(OPEN_ENDED, from, to);
        // At the line of the number.
        let err = assert_invalid(&text, item, to, phrase);
        assert!(
            err.to_string()
                .contains("format.md §12, ranges of magnitude"),
            "{err}"
        );
    }
    // A placement's origin and angles.
    parse(&with_pose(OPEN_ENDED)).unwrap_or_else(|e| panic!("{e}"));
    for (from, to, phrase) in [
        (
            "origin: (0.0, 0.0, -0.01)",
            "origin: (0.0, 5e6, -0.01)",
            "`origin` is 5e6 m, beyond the range of a length",
        ),
        (
            "rpy: (0.0, 0.0, 0.0)",
            "rpy: (0.0, 0.0, 1e4)",
            "`rpy` is 10000 rad, beyond the range of an angle",
        ),
    ] {
        let text = with(&with_pose(OPEN_ENDED), from, to);
        assert_invalid(&text, "gear", to, phrase);
    }
    // The external wrench's point, at the `external_wrench:` line.
    let text = with(
        OPEN_ENDED,
        "    tendons: [",
        "    external_wrench: (link: \"link2\", point: (0.0, -3e6, 0.0), force: (1.0, 0.0, 0.0)),\n    tendons: [",
    );
    let err = rejected(&text);
    let Error::Invalid { at, .. } = &err else {
        panic!("{err:?}")
    };
    assert_eq!(at.line, line_of(&text, "external_wrench:"), "{err}");
    assert!(
        err.to_string().contains(
            "the `point` of `external_wrench` on `link2` has -3e6 m, beyond the range of a length"
        ),
        "{err}"
    );
}

#[test]
fn a_runtime_parameter_outside_its_range_is_rejected() {
    let text = with(
        &with(OPEN_ENDED, "mass: 0.8,", "mass: \"payload\","),
        "tension_floor: 5.0,",
        "tension_floor: 5.0,\n    parameters: [(name: \"payload\", value: 0.8)],",
    );
    let model = parse(&text).unwrap();
    model.with_parameters(&[1e12]).unwrap();
    let err = model.with_parameters(&[1e13]).unwrap_err();
    assert!(
        err.to_string()
            .contains("`mass` is 1e13 kg, beyond the range of a mass"),
        "{err}"
    );
    // Its nominal value is checked like any number.
    let text = with(&text, "value: 0.8", "value: 1e13");
    assert_invalid(&text, "link2", "mass: \"payload\"", "`mass` is 1e13 kg");
    // The external wrench's point.
    let text = with(
        OPEN_ENDED,
        "    tendons: [",
        "    parameters: [(name: \"px\", value: 0.1)],\n    external_wrench: (link: \"link2\", point: (\"px\", 0.0, 0.0), force: (1.0, 0.0, 0.0)),\n    tendons: [",
    );
    let model = parse(&text).unwrap();
    model.with_parameters(&[1e6]).unwrap();
    let err = model.with_parameters(&[-2e6]).unwrap_err();
    assert_eq!(err.item(), Some("open_ended"));
    assert!(
        err.to_string()
            .contains("`external_wrench.point` is -2e6 m, beyond the range of a length"),
        "{err}"
    );
}

#[test]
fn a_body_at_the_edges_of_every_range_gives_finite_results_and_f32_code() {
    let (_, text) = reproducer("F01-codegen-f32-constant-overflow-panic");
    let text = with(
        &text,
        "dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: 1e39, com: (-0.1, 0.0, 0.0)",
        "dh: (a: 1e6, alpha: 1e3, d: -1e6, offset: -1e3), mass: 1e12, com: (-1e6, 1e6, -1e6), \
         inertia: (xx: 1e24, yy: 1e24, zz: 1e24, xy: -1e-9)",
    );
    let model = parse(&text).unwrap();
    let mut solver = Data::new(&model);
    let (q, qd, qdd) = ([1e4], [1e3], [1e6]);
    let r = solver
        .inverse_dynamics(&model, &q, &qd, &qdd)
        .unwrap()
        .clone();
    assert!(r.generalized_forces.iter().all(|x| x.is_finite()));
    let qdd = solver
        .forward_dynamics(&model, &q, &qd, &r.unknowns, &[])
        .unwrap();
    assert!((qdd[0] - 1e6).abs() <= 1e-6 * 1e6, "{qdd:?}");
    for scalar in [tendyn_codegen::Scalar::F32, tendyn_codegen::Scalar::F64] {
        let g = generated(&model, scalar).unwrap();
        assert!(!g.source().contains("inf") && !g.source().contains("NaN"));
    }
    // A pulley radius at both ends.
    for r in ["1e-9", "1e6"] {
        let (_, text) = reproducer("F07-tiny-radius-misleading-not-controllable");
        let text = with(&text, "radius: 1e-163", &format!("radius: {r}"))
            .replace("exit: (-0.1, 0.05, 0.0)", "exit: (-3e6, 0.05, 0.0)")
            .replace("exit: (-0.1, -0.05, 0.0)", "exit: (-3e6, -0.05, 0.0)");
        let err = parse(&text).unwrap_err();
        // (-3e6 is itself out of range: the exits move in to the edge instead.)
        assert!(err.to_string().contains("`exit` is -3e6 m"), "{err}");
        let text = text.replace("-3e6", "-1e6");
        let model = parse(&text).unwrap_or_else(|e| panic!("radius {r}: {e}"));
        let r = Data::new(&model)
            .inverse_dynamics(&model, &[0.5], &[1.0], &[2.0])
            .unwrap()
            .clone();
        assert!(r.unknowns.iter().all(|x| x.is_finite()));
    }
}

#[test]
fn negative_bearing_friction_is_rejected_at_the_body_that_has_it() {
    for (friction, phrase) in [
        (
            "(coulomb: -0.1)",
            "`friction.coulomb` is -0.1 N·m; friction opposes motion, so give its size",
        ),
        (
            "(coulomb: 0.1, viscous: -0.02)",
            "`friction.viscous` is -0.02 N·m·s/rad; friction opposes motion",
        ),
        (
            "(viscous: inf)",
            "`friction.viscous` is inf; every number must be finite",
        ),
        (
            "(coulomb: 1e30)",
            "beyond the range of a friction torque (at most 1e18 N·m",
        ),
    ] {
        let text = with(
            OPEN_ENDED,
            "            mass: 1.2,",
            &format!("            mass: 1.2,\n            friction: {friction},"),
        );
        assert_invalid(&text, "link1", &format!("friction: {friction}"), phrase);
    }
    let text = with(
        OPEN_ENDED,
        "            radius: 0.03,\n            mass: 0.05,\n            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),\n        ),\n        (\n            name: \"idler4\"",
        "            radius: 0.03,\n            friction: (viscous: -1.0),\n            mass: 0.05,\n            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),\n        ),\n        (\n            name: \"idler4\"",
    );
    assert_invalid(
        &text,
        "idler3",
        "friction: (viscous: -1.0)",
        "`friction.viscous` is -1 N·m·s/rad",
    );
}

#[test]
fn friction_on_a_fixed_drum_is_rejected_since_it_has_no_bearing() {
    let text = with(
        OPEN_ENDED,
        "radius: 0.04, fixed: true)",
        "radius: 0.04, fixed: true, friction: (coulomb: 0.01))",
    );
    assert_invalid(
        &text,
        "drum1",
        "name: \"drum1\"",
        "a `fixed` drum does not turn on its carrier, so its bearing has no friction",
    );
}

#[test]
fn a_friction_smoothing_speed_outside_its_range_is_rejected_at_its_line() {
    for v in ["0.0", "-0.01", "1e-12", "1e9"] {
        let text = with(
            OPEN_ENDED,
            "tension_floor: 5.0,",
            &format!("tension_floor: 5.0,\n    friction_smoothing: {v},"),
        );
        let err = rejected(&text);
        assert_eq!(err.item(), Some("open_ended"));
        let Error::Invalid { at, .. } = &err else {
            panic!("{err:?}")
        };
        assert_eq!(at.line, line_of(&text, "friction_smoothing:"), "{err}");
        assert!(
            err.to_string().contains("`friction_smoothing` is")
                && err.to_string().contains("a number from 1e-9 to 1e6 rad/s"),
            "{err}"
        );
    }
}

/// A joint's `range` must be two finite angles within their range of magnitude, the
/// lower below the upper: each is an `Invalid` error at the link's line that names the
/// field; a good one is accepted and kept.
#[test]
fn a_joint_range_that_is_empty_reversed_or_absurd_is_rejected_at_its_link() {
    let good = with(
        OPEN_ENDED,
        "dh: (a: 0.30, alpha: 0.0, d: 0.0),",
        "dh: (a: 0.30, alpha: 0.0, d: 0.0),\n            range: (-1.5, 2.0),",
    );
    assert_eq!(parse(&good).unwrap().joint_range(0), Some([-1.5, 2.0]));
    for (range, says) in [
        ("(1.0, 1.0)", "lower end must be below its upper"),
        ("(2.0, -2.0)", "lower end must be below its upper"),
        ("(-1e4, 1.0)", "`range`"),
        ("(0.0, inf)", "must be finite"),
    ] {
        let text = with(
            OPEN_ENDED,
            "dh: (a: 0.30, alpha: 0.0, d: 0.0),",
            &format!("dh: (a: 0.30, alpha: 0.0, d: 0.0),\n            range: {range},"),
        );
        let err = rejected(&text);
        assert_eq!(err.item(), Some("link1"), "{err}");
        let Error::Invalid { at, .. } = &err else {
            panic!("{err:?}")
        };
        assert_eq!(at.line, line_of(&text, "range: "), "{err}");
        assert!(err.to_string().contains(says), "{range}: {err}");
    }
}

/// An error about one field is at that field's line, whether the item writes it before or
/// after its `name`, and never at a like-named field of the next item.
#[test]
fn an_error_about_a_field_is_at_the_fields_line_before_or_after_the_name() {
    let before = with(
        OPEN_ENDED,
        "        (\n            name: \"idler3\",",
        "        (\n            mass: -0.05,\n            name: \"idler3\",",
    );
    let before = with(
        &before,
        "radius: 0.03,\n            mass: 0.05,\n            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),\n        ),\n        (\n            name: \"idler4\"",
        "radius: 0.03,\n            inertia: (xx: 0.00001125, yy: 0.00001125, zz: 0.0000225),\n        ),\n        (\n            name: \"idler4\"",
    );
    assert_invalid(&before, "idler3", "mass: -0.05,", "mass is -0.05 kg");
    // A zero mass by default, with an inertia: not at the mass idler3 writes before
    // idler4's name (outside idler4's parentheses), but at idler4's name.
    let unwritten = with(
        OPEN_ENDED,
        "height: -0.01),\n            radius: 0.03,\n            mass: 0.05,\n",
        "height: -0.01),\n            radius: 0.03,\n",
    );
    assert_invalid(
        &unwritten,
        "idler4",
        "name: \"idler4\"",
        "mass is zero but the inertia is not",
    );
    // Keys within strings and comments are not fields.
    let one_line = "(name: \"one\", links: [(name: \"arm mass: 2\", /* mass: 1, ( */ dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: -1.0)])";
    let err = rejected(one_line);
    let Error::Invalid { at, .. } = err else {
        panic!("{err:?}")
    };
    assert_eq!((at.line, at.column), (1, column_of(one_line, "mass: -1.0")));
}

#[test]
fn a_name_holding_a_comment_marker_is_still_located_at_its_definition() {
    // `//` inside a string is not a comment: the locator reads string literals first.
    let text = with(OPEN_ENDED, "name: \"idler4\"", "name: \"idler//4\"");
    let text = text.replace("(\"idler4\", Cw)", "(\"idler//4\", Cw)");
    assert_invalid(
        &text,
        "idler//4",
        "name: \"idler//4\"",
        "the name `idler//4` cannot be used",
    );
}

#[test]
fn forces_ratios_and_gravity_beyond_their_ranges_are_rejected_where_they_are_written() {
    // (from, to, item, the line it is reported at, what is said)
    for (from, to, item, at, phrase) in [
        (
            "tension_floor: 5.0,",
            "tension_floor: 1e308,",
            "open_ended",
            "tension_floor:",
            "`tension_floor` is 1e308 N, beyond the range of a force (at most 1e15 N",
        ),
        (
            "gravity: (0.0, -9.81, 0.0),",
            "gravity: (0.0, -1e7, 0.0),",
            "open_ended",
            "gravity:",
            "`gravity` is -1e7 m/s², beyond the range of an acceleration (at most 1e6 m/s²",
        ),
        (
            "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0)),",
            "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0), max_tension: 2e15),",
            "T11",
            "name: \"T11\"",
            "`max_tension` is 2e15 N, beyond the range of a force",
        ),
        (
            "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0)),",
            "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0), floor: 1e16),",
            "T11",
            "name: \"T11\"",
            "`floor` is 1e16 N, beyond the range of a force",
        ),
    ] {
        let text = with(OPEN_ENDED, from, to);
        let err = rejected(&text);
        assert_eq!(err.item(), Some(item), "{err}");
        let Error::Invalid { at: location, .. } = &err else {
            panic!("{err:?}")
        };
        assert_eq!(location.line, line_of(&text, at), "{err}");
        assert!(err.to_string().contains(phrase), "{err}");
    }
    let text = with(
        OPEN_ENDED,
        "    tendons: [",
        "    external_wrench: (link: \"link2\", force: (0.0, 2e15, 0.0)),\n    tendons: [",
    );
    let err = rejected(&text);
    assert!(
        err.to_string()
            .contains("`external_wrench.force` is 2e15 N, beyond the range of a force"),
        "{err}"
    );
}

#[test]
fn an_overflowing_state_names_the_input_to_blame() {
    let model = parse(OPEN_ENDED).unwrap();
    let err = Data::new(&model)
        .inverse_dynamics(&model, &[0.1, 0.2], &[1e200, 0.0], &[0.0, 0.0])
        .unwrap_err();
    let shown = err.to_string();
    assert!(matches!(err, Error::State(_)), "{err:?}");
    assert!(
        shown.contains("the largest input is qd[0] = 1e200"),
        "{shown}"
    );
}

#[test]
fn more_than_thirty_links_are_refused_naming_the_limit() {
    let links: String = (1..=31)
        .map(|k| {
            format!(
                "        (name: \"l{k}\", dh: (a: 0.1, alpha: 0, d: 0, offset: 0), mass: 0.1),\n"
            )
        })
        .collect();
    let motors: String = (1..=31)
        .map(|k| format!("        (name: \"m{k}\", on: Joint(\"l{k}\")),\n"))
        .collect();
    let text = format!(
        "(\n    name: \"long\",\n    gravity: (0, -9.81, 0),\n    links: [\n{links}    ],\n    motors: [\n{motors}    ],\n)\n"
    );
    let err = assert_invalid(&text, "long", "name: \"long\"", "at most 30 are supported");
    assert!(!err.to_string().contains("  "), "{err}");
    // Thirty are fine.
    let thirty = text
        .replace(
            "        (name: \"l31\", dh: (a: 0.1, alpha: 0, d: 0, offset: 0), mass: 0.1),\n",
            "",
        )
        .replace("        (name: \"m31\", on: Joint(\"l31\")),\n", "");
    parse(&thirty).unwrap();
}

/// Sixty-five guides with friction that one pull slides together (one class of guides,
/// each free to rest under `friction_smoothing`): validation counts the corners it would
/// enumerate before it shifts by their number, so it neither panics (a shift by 64 or
/// more) nor builds them, and the routing is validated as beyond its limit of systems.
#[test]
fn sixty_five_guides_sliding_together_are_validated_without_overflow() {
    let guides: Vec<String> = (1..=65)
        .map(|k| {
            format!(
                "(name: \"g{k}\", carrier: \"base\", at: Pose(origin: ({}, 0.0, 0.0), \
                 rpy: (0.0, 0.0, 0.0)), radius: 0.01, fixed: true, mu: 0.1)",
                0.1 * k as f64
            )
        })
        .collect();
    let route: Vec<String> = (1..=65).map(|k| format!("(\"g{k}\", Ccw)")).collect();
    let text = format!(
        "(name: \"guides65\", friction_smoothing: 0.01,
          links: [(name: \"l1\", dh: (a: 0.1, alpha: 0.0, d: 0.0), mass: 1.0)],
          pulleys: [
            (name: \"dA\", carrier: \"l1\", at: Joint(joint: \"l1\", height: 0.0), radius: 0.01, fixed: true),
            (name: \"dB\", carrier: \"l1\", at: Joint(joint: \"l1\", height: 0.05), radius: 0.01, fixed: true),
            {}],
          tendons: [
            (name: \"a\", route: [(\"dA\", Ccw), {}], exit: (10.0, -0.01, 0.0)),
            (name: \"b\", route: [(\"dB\", Cw)], exit: (0.0, 1.0, 0.05)),
          ])",
        guides.join(",\n"),
        route.join(", ")
    );
    let model = parse(&text).expect("a controllable routing");
    assert_eq!(model.guides().count(), 65);
}

/// A body that turns without spinning keeps its housing frame, so what it carried would
/// not turn with it: a rigid tree with such a body as a parent is refused, naming it.
#[test]
fn a_rigid_tree_refuses_a_body_turning_without_spinning_that_carries_another() {
    let file = load("../examples/mechanisms/example3_stanford_jpl.ron").unwrap();
    let mut links = file.bodies()[..file.dof()].to_vec();
    let a = links[0].axis.to_array();
    let axisymmetric: [[f64; 3]; 3] = core::array::from_fn(|i| {
        core::array::from_fn(|j| {
            let identity = if i == j { 1.0 } else { 0.0 };
            2e-4 * a[i] * a[j] + 1e-4 * (identity - a[i] * a[j])
        })
    });
    let first = &mut links[0];
    first.spins = false;
    first.com = -first.joint_to_origin + first.axis.scale(0.01);
    first.inertia.rows = axisymmetric;
    let g = file.gravity().to_array();
    // Alone it is a valid tree; carrying the second link it is not.
    let mut alone = links[..1].to_vec();
    alone[0].coupling.truncate(1);
    let alone = tendyn_core::Model::rigid_tree("alone", g, 1, alone, None);
    assert!(alone.is_ok(), "{:?}", alone.err());
    let err = tendyn_core::Model::rigid_tree("carrying", g, file.dof(), links, None).unwrap_err();
    let message = err.to_string();
    assert!(
        message.starts_with(&format!("{}: ", file.bodies()[0].name))
            && message.contains(&format!("carries `{}`", file.bodies()[1].name))
            && message.contains("let it spin"),
        "{message}"
    );
}

/// A tree of bodies built in code has no routing: an idler (whose strand would be looked
/// up by everything that reports on it) or a loop's driving pulley is refused, naming the
/// roles it may have.
#[test]
fn a_rigid_tree_refuses_an_idler_which_needs_a_routing() {
    let file = load("../examples/mechanisms/example3_stanford_jpl.ron").unwrap();
    let n = file.dof();
    let idler = file.bodies()[n..]
        .iter()
        .find(|b| {
            matches!(
                b.kind,
                tendyn_core::model::BodyKind::Pulley {
                    role: tendyn_core::model::PulleyRole::Idler { .. },
                    ..
                }
            )
        })
        .expect("Example 3 has idlers")
        .clone();
    let mut bodies = file.bodies()[..n].to_vec();
    bodies.push(idler);
    let g = file.gravity().to_array();
    let err = tendyn_core::Model::rigid_tree("idler", g, n, bodies, None).unwrap_err();
    assert!(err.to_string().contains("`Fixed` or `Coupled`"), "{err}");
}
