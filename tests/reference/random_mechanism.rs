//! Seeded random mechanisms, written as RON text so that they go through the same parsing
//! and validation as a user's file.
//!
//! Each has up to 7 primary links with general Denavit-Hartenberg twists, offsets and
//! joint offsets, full inertia tensors (random principal moments obeying the triangle
//! inequality, random principal axes), random gravity, optionally an external wrench on
//! the last link. The proximal joints whose axes are parallel form a tendon-driven block:
//! either an open-ended routing (one anchor per joint, one tendon more than joints, idlers
//! on every joint axis below the anchor, each carried by a randomly chosen body of that
//! joint) or an endless loop from a motor-driven base pulley to link 2's drum. The other
//! joints have motors. Optionally, tilted and off-axis pulleys with explicit couplings
//! ride on random carriers.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;

/// Which features a random mechanism has.
#[derive(Clone, Copy, Debug)]
pub struct Features {
    /// Tilted, off-axis pulleys with explicit couplings (bearing forces then unavailable).
    pub coupled_pulleys: bool,
    /// The tendon block is an endless loop rather than open-ended tendons.
    pub endless: bool,
}

fn inertia<R: Rng>(rng: &mut R, mass: f64, size: f64) -> String {
    // principal moments with the triangle inequality, then a random rotation
    let a = rng.random_range(0.2..1.0) * mass * size * size;
    let b = rng.random_range(0.2..1.0) * mass * size * size;
    let c = rng.random_range((a - b).abs() * 1.01..(a + b) * 0.99);
    let (r, p, y): (f64, f64, f64) = (
        rng.random_range(-3.0..3.0),
        rng.random_range(-1.5..1.5),
        rng.random_range(-3.0..3.0),
    );
    let (sr, cr, sp, cp, sy, cy) = (r.sin(), r.cos(), p.sin(), p.cos(), y.sin(), y.cos());
    let rot = [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ];
    let d = [a, b, c];
    let mut i = [[0.0; 3]; 3];
    for (r_, row) in i.iter_mut().enumerate() {
        for (c_, e) in row.iter_mut().enumerate() {
            *e = (0..3).map(|k| rot[r_][k] * d[k] * rot[c_][k]).sum();
        }
    }
    format!(
        "(xx: {:e}, yy: {:e}, zz: {:e}, xy: {:e}, xz: {:e}, yz: {:e})",
        i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2]
    )
}

fn v3<R: Rng>(rng: &mut R, s: f64) -> String {
    format!(
        "({:e}, {:e}, {:e})",
        rng.random_range(-s..s),
        rng.random_range(-s..s),
        rng.random_range(-s..s)
    )
}

fn turn<R: Rng>(rng: &mut R) -> &'static str {
    if rng.random_bool(0.5) {
        "Ccw"
    } else {
        "Cw"
    }
}

/// The RON text of random mechanism `seed`, and its number of links. Not every draw of an
/// open-ended routing is controllable by tendons; callers use [`valid_random_mechanism`].
pub fn random_mechanism(seed: u64, features: Features) -> String {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n: usize = rng.random_range(2..=7);
    // Tendon block: joints 1..=p with parallel axes.
    let p: usize = if features.endless {
        2
    } else {
        rng.random_range(1..=n.min(3))
    };
    let mut s = String::new();
    let g = v3(&mut rng, 10.0);
    writeln!(
        s,
        "(\n  name: \"random_{seed}\",\n  gravity: {g},\n  tension_floor: {:e},",
        rng.random_range(0.0..5.0)
    )
    .unwrap();
    let mut d = Vec::new();
    let mut a = Vec::new();
    writeln!(s, "  links: [").unwrap();
    for j in 1..=n {
        let alpha = if j < p {
            0.0
        } else {
            match rng.random_range(0..4) {
                0 => std::f64::consts::FRAC_PI_2,
                1 => -std::f64::consts::FRAC_PI_2,
                _ => rng.random_range(-3.1..3.1),
            }
        };
        let aj = rng.random_range(0.15..0.4);
        let dj = rng.random_range(-0.1..0.1);
        a.push(aj);
        d.push(dj);
        let mass = rng.random_range(0.2..2.0);
        let inertia = inertia(&mut rng, mass, aj);
        writeln!(
            s,
            "    (name: \"l{j}\", dh: (a: {aj:e}, alpha: {alpha:e}, d: {dj:e}, offset: {:e}), mass: {mass:e}, com: {}, inertia: {inertia}),",
            rng.random_range(-1.0..1.0),
            v3(&mut rng, 0.2)
        )
        .unwrap();
    }
    writeln!(s, "  ],").unwrap();
    // Height along joint j's axis (j = 1-based joint, axis z_{j-1}) of the plane at base z = zeta.
    let height = |j: usize, zeta: f64| zeta - d[..j - 1].iter().sum::<f64>();
    let mut pulleys = String::new();
    let mut tendons = String::new();
    let mut loops = String::new();
    let mut motors = String::new();
    let disc = |rng: &mut ChaCha8Rng, r: f64| {
        let m = rng.random_range(0.01..0.2);
        (
            m,
            format!(
                "(xx: {:e}, yy: {:e}, zz: {:e})",
                m * r * r / 4.0,
                m * r * r / 4.0,
                m * r * r / 2.0
            ),
        )
    };
    if features.endless {
        let zeta = rng.random_range(-0.05..0.05);
        let (r2, r1) = (rng.random_range(0.01..0.05), rng.random_range(0.01..0.05));
        let (m, i) = disc(&mut rng, r1);
        writeln!(pulleys, "    (name: \"drive\", carrier: \"base\", at: Joint(joint: \"l1\", height: {:e}), radius: {r1:e}, mass: {m:e}, inertia: {i}),", height(1, zeta)).unwrap();
        writeln!(pulleys, "    (name: \"drum_l2\", carrier: \"l2\", at: Joint(joint: \"l2\", height: {:e}), radius: {r2:e}, fixed: true),", height(2, zeta)).unwrap();
        writeln!(loops, "    (name: \"belt\", driven: \"drum_l2\", driving: \"drive\", crossed: {}, pretension: {:e}),", rng.random_bool(0.5), rng.random_range(10.0..50.0)).unwrap();
        writeln!(motors, "    (name: \"m_l1\", on: Joint(\"l1\")),\n    (name: \"m_drive\", on: Pulley(\"drive\")),").unwrap();
    } else {
        // One tendon anchored on each block link, plus one more on a random block link.
        let mut anchors: Vec<usize> = (1..=p).collect();
        anchors.push(rng.random_range(1..=p));
        for (k, &link) in anchors.iter().enumerate() {
            let zeta = 0.02 * (k as f64 + 1.0) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let r = rng.random_range(0.01..0.04);
            writeln!(pulleys, "    (name: \"drum{k}\", carrier: \"l{link}\", at: Joint(joint: \"l{link}\", height: {:e}), radius: {r:e}, fixed: true),", height(link, zeta)).unwrap();
            let mut route = format!("(\"drum{k}\", {})", turn(&mut rng));
            for j in (1..link).rev() {
                let r = rng.random_range(0.01..0.04);
                let carrier = if rng.random_bool(0.5) {
                    format!("l{j}")
                } else if j == 1 {
                    "base".into()
                } else {
                    format!("l{}", j - 1)
                };
                let (m, i) = disc(&mut rng, r);
                writeln!(pulleys, "    (name: \"idler{k}_{j}\", carrier: \"{carrier}\", at: Joint(joint: \"l{j}\", height: {:e}), radius: {r:e}, mass: {m:e}, inertia: {i}),", height(j, zeta)).unwrap();
                write!(route, ", (\"idler{k}_{j}\", {})", turn(&mut rng)).unwrap();
            }
            let ang: f64 = rng.random_range(-3.0..3.0);
            writeln!(
                tendons,
                "    (name: \"t{k}\", route: [{route}], exit: ({:e}, {:e}, {zeta:e})),",
                0.3 * ang.cos(),
                0.3 * ang.sin()
            )
            .unwrap();
        }
    }
    for j in (p + 1)..=n {
        writeln!(motors, "    (name: \"m_l{j}\", on: Joint(\"l{j}\")),").unwrap();
    }
    if features.coupled_pulleys {
        for k in 0..rng.random_range(1..4) {
            let carrier = match rng.random_range(0..=n) {
                0 => "base".to_string(),
                c => format!("l{c}"),
            };
            let coupling: Vec<String> = (0..n)
                .map(|_| format!("{:e}", rng.random_range(-2.0..2.0)))
                .collect();
            let mass = rng.random_range(0.05..0.5);
            writeln!(
                pulleys,
                "    (name: \"gear{k}\", carrier: \"{carrier}\", at: Pose(origin: {}, rpy: {}), radius: 0.03, mass: {mass:e}, com: {}, inertia: {}, coupling: [{}]),",
                v3(&mut rng, 0.2),
                v3(&mut rng, 3.0),
                v3(&mut rng, 0.02),
                inertia(&mut rng, mass, 0.05),
                coupling.join(", ")
            )
            .unwrap();
        }
    }
    writeln!(s, "  pulleys: [\n{pulleys}  ],\n  tendons: [\n{tendons}  ],\n  loops: [\n{loops}  ],\n  motors: [\n{motors}  ],").unwrap();
    if rng.random_bool(0.5) {
        writeln!(
            s,
            "  external_wrench: (link: \"l{n}\", point: {}, force: {}, moment: {}),",
            v3(&mut rng, 0.1),
            v3(&mut rng, 5.0),
            v3(&mut rng, 1.0)
        )
        .unwrap();
    }
    s.push_str(")\n");
    s
}

/// The first valid mechanism among a few draws derived from `seed` (open-ended routings
/// with every tendon on the same side of a joint are not controllable and are redrawn).
pub fn valid_random_mechanism(seed: u64, features: Features) -> (String, tendyn_core::Model<f64>) {
    let mut last = None;
    for attempt in 0..64 {
        let text = random_mechanism(seed * 1000 + attempt, features);
        match tendyn_core::parse(&text) {
            Ok(m) => return (text, m),
            Err(e) => last = Some((e, text)),
        }
    }
    let (e, text) = last.expect("attempts were made");
    panic!("no valid mechanism from seed {seed}: last error {e}\n{text}");
}
