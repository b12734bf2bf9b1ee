#[derive(tendyn::TendonMechanism)]
#[tendyn(ron = r#"(
    name: "pendulum",
    links: [
        (name: "link1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: -1.0, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
    ],
    motors: [(name: "motor1", on: Joint("link1"))],
)"#)]
struct Pendulum;

fn main() {}
