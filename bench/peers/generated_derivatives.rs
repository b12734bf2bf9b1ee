//! tendyn's generated `(Q, ∂Q/∂q, ∂Q/∂q̇)` of `bench/mechanisms/arm6.ron`, timed on the states
//! of the Pinocchio harness with its protocol (warm-up, 51 samples of at least 2 ms, median
//! per call), after checking `Q` and both Jacobians against the file's (tendyn's runtime
//! solver, dual numbers). `run.sh` builds it outside the workspace: the generated function
//! has 16,262 operations and wants `RUST_MIN_STACK` to compile (docs/generated-code.md §4).
//!
//!     generated_derivatives arm6.tree
#[allow(clippy::all)]
mod arm6d; // `tendyn generate arm6.ron --outputs generalized_forces_derivatives,generalized_forces --scalar f64`
use std::hint::black_box;
use std::time::Instant;

fn main() {
    // The states of the Pinocchio harness: the tree file `expanded_tree` writes (header,
    // bodies, then per state q, qd, qdd, Q and the two Jacobians).
    let text = std::fs::read_to_string(std::env::args().nth(1).expect("TREE file")).unwrap();
    let v: Vec<f64> = text.split_whitespace().map(|t| t.parse().unwrap()).collect();
    let (n, bodies) = (v[0] as usize, v[1] as usize);
    let mut at = 5;
    at += if v[at] >= 0.0 { 10 } else { 1 };
    at += bodies * (2 + 12 + 12 + n + 4 + 9);
    let per = 4 * n + 2 * n * n;
    let states: Vec<([f64; 6], [f64; 6], [f64; 6])> = v[at..]
        .chunks_exact(per)
        .map(|x| {
            let a = |k: usize| -> [f64; 6] { core::array::from_fn(|j| x[k * n + j]) };
            (a(0), a(1), a(2))
        })
        .collect();
    assert_eq!(states.len(), 1024);
    // Check: generated Q against the file's (tendyn's runtime) Q.
    let worst = v[at..].chunks_exact(per).zip(&states).fold(0.0f64, |m, (x, s)| {
        let q = arm6d::generalized_forces(&s.0, &s.1, &s.2);
        let scale = x[3 * n..4 * n].iter().fold(1e-300f64, |m, y| m.max(y.abs()));
        (0..n).fold(m, |m, j| m.max((q[j] - x[3 * n + j]).abs() / scale))
    });
    println!("generated Q against the file's: worst {worst:.1e}");
    // And the Jacobians against the file's (tendyn's runtime dual numbers), each relative to
    // the largest entry of both.
    let worst_d = v[at..].chunks_exact(per).zip(&states).fold(0.0f64, |m, (x, s)| {
        let d = arm6d::generalized_forces_derivatives(&s.0, &s.1, &s.2);
        let file = &x[4 * n..];
        let scale = file.iter().fold(1e-300f64, |m, y| m.max(y.abs()));
        let ours = d.d_q.iter().flatten().chain(d.d_qd.iter().flatten());
        ours.zip(file).fold(m, |m, (a, b)| m.max((a - b).abs() / scale))
    });
    println!("generated dQ/dq, dQ/dqd against the file's: worst {worst_d:.1e}");
    let time = |name: &str, f: &dyn Fn(&([f64; 6], [f64; 6], [f64; 6])) -> f64| {
        let pass = || states.iter().map(|s| f(s)).sum::<f64>();
        let t0 = Instant::now();
        let mut passes = 0;
        while t0.elapsed().as_secs_f64() < 0.3 {
            black_box(pass());
            passes += 1;
        }
        let per_pass = 0.3 / passes as f64;
        let reps = (2e-3 / per_pass).ceil().max(1.0) as usize;
        let mut ns: Vec<f64> = (0..51)
            .map(|_| {
                let a = Instant::now();
                for _ in 0..reps {
                    black_box(pass());
                }
                a.elapsed().as_nanos() as f64 / (reps * states.len()) as f64
            })
            .collect();
        ns.sort_by(f64::total_cmp);
        println!("{name}: {:.1} ns per call (median of 51)", ns[25]);
    };
    time("generated Q", &|s| arm6d::generalized_forces(black_box(&s.0), black_box(&s.1), black_box(&s.2))[0]);
    time("generated (Q, dQ/dq, dQ/dqd)", &|s| {
        let d = arm6d::generalized_forces_derivatives(black_box(&s.0), black_box(&s.1), black_box(&s.2));
        d.value[0] + d.d_q[5][5] + d.d_qd[5][5]
    });
}
