//! A mechanism with runtime parameters, for the tests of parameters in the runtime solver
//! and in generated code: the paper's Example 3 with the distal link's mass and z inertia,
//! idler 8's z inertia and gravity's z component as parameters.

const FINGER: &str = include_str!("../../examples/mechanisms/example3_stanford_jpl.ron");

/// Nominal values of the parameters, in declaration order: `m3`, `i3zz`, `g`, `i8`.
pub const NOMINAL: [f64; 4] = [0.02, 0.0000030, -9.81, 0.000000049];

/// The RON text of the parametric finger.
pub fn finger() -> String {
    let replace = |s: String, from: &str, to: &str| {
        assert_eq!(s.matches(from).count(), 1, "`{from}`");
        s.replacen(from, to, 1)
    };
    let s = replace(
        FINGER.to_string(),
        "    tension_floor: 5.0,",
        "    tension_floor: 5.0,\n    parameters: [(name: \"m3\", value: 0.02), (name: \"i3zz\", value: 0.0000030), (name: \"g\", value: -9.81), (name: \"i8\", value: 0.000000049)],",
    );
    let s = replace(
        s,
        "gravity: (0.0, 0.0, -9.81)",
        "gravity: (0.0, 0.0, \"g\")",
    );
    let s = replace(
        s,
        "            mass: 0.02,\n            com: (-0.02, 0.0, 0.0),\n            inertia: (xx: 0.0000006, yy: 0.0000030, zz: 0.0000030),",
        "            mass: \"m3\",\n            com: (-0.02, 0.0, 0.0),\n            inertia: (xx: 0.0000006, yy: 0.0000030, zz: \"i3zz\"),",
    );
    let idler8 = "name: \"idler8\", carrier: \"knuckle\", at: Joint(joint: \"proximal\", height: 0.006), radius: 0.007,\n            mass: 0.002, inertia: (xx: 0.0000000245, yy: 0.0000000245, zz: 0.000000049),";
    replace(s, idler8, &idler8.replace("zz: 0.000000049", "zz: \"i8\""))
}
