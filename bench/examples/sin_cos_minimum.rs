//! Sines and cosines of blocks of 8 angles: `tendyn_core::trigonometry::sin_cos_many`
//! against the standard library's `f64::sin_cos` called per angle, as the minimum over 300
//! passes of 1,024 seeded blocks of angles in `[−15, 15]` rad (ns per block of 8).
//!
//! `RUSTFLAGS="-C target-cpu=native" cargo build --release -p tendyn-bench --example
//! sin_cos_minimum`, then `taskset -c 0 target/release/examples/sin_cos_minimum` (without
//! `RUSTFLAGS` for the baseline x86-64).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let blocks: Vec<[f64; 8]> = (0..1024)
        .map(|_| core::array::from_fn(|_| rng.random_range(-15.0..15.0)))
        .collect();
    let (mut library, mut ours) = (f64::INFINITY, f64::INFINITY);
    let per_block = |start: Instant| start.elapsed().as_nanos() as f64 / blocks.len() as f64;
    for _ in 0..300 {
        let start = Instant::now();
        for block in &blocks {
            let block = black_box(*block);
            let out: [(f64, f64); 8] = core::array::from_fn(|i| block[i].sin_cos());
            black_box(out);
        }
        library = library.min(per_block(start));
        let start = Instant::now();
        for block in &blocks {
            let block = black_box(*block);
            let mut out = [(0.0, 0.0); 8];
            tendyn_core::trigonometry::sin_cos_many(&block, &mut out);
            black_box(out);
        }
        ours = ours.min(per_block(start));
    }
    println!("8 angles: f64::sin_cos {library:.1} ns, trigonometry::sin_cos_many {ours:.1} ns");
}
