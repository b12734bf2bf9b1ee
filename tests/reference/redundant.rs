//! A redundantly driven mechanism whose tension null space is two-dimensional.

/// One joint pulled by three tendons (two one way, one the other): a two-dimensional null space.
pub const THREE_ON_ONE: &str = r#"(
    name: "three_on_one", gravity: (0.0, -9.81, 0.0), tension_floor: 2.0,
    links: [(name: "l1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.0, com: (-0.15, 0.0, 0.0), inertia: (xx: 0.001, yy: 0.008, zz: 0.008))],
    pulleys: [
        (name: "d1", carrier: "l1", at: Joint(joint: "l1", height: 0.00), radius: 0.02, fixed: true),
        (name: "d2", carrier: "l1", at: Joint(joint: "l1", height: 0.01), radius: 0.03, fixed: true),
        (name: "d3", carrier: "l1", at: Joint(joint: "l1", height: 0.02), radius: 0.025, fixed: true),
    ],
    tendons: [
        (name: "a", route: [("d1", Ccw)], exit: (-0.2, 0.1, 0.00)),
        (name: "b", route: [("d2", Ccw)], exit: (-0.2, -0.1, 0.01), floor: 4.0),
        (name: "c", route: [("d3", Cw)], exit: (0.0, -0.2, 0.02)),
    ],
)"#;
