use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn tokens_num(t: &str) -> Vec<(usize, usize)> {
    let b = t.as_bytes();
    let mut v = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if (b[i].is_ascii_digit() || b[i] == b'-') && (i == 0 || !(b[i-1].is_ascii_alphanumeric() || b[i-1] == b'_')) {
            let s = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.' || b[i] == b'e' || b[i] == b'-') { i += 1; }
            if i > s + 1 || b[s].is_ascii_digit() { v.push((s, i)); }
        } else { i += 1; }
    }
    v
}
fn quoted(t: &str) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    let mut it = t.match_indices('"').map(|x| x.0);
    while let (Some(a), Some(b)) = (it.next(), it.next()) { v.push((a, b + 1)); }
    v
}

#[test]
fn probe() {
    let mut rng = ChaCha8Rng::seed_from_u64(std::env::var("SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(1));
    let files: Vec<String> = ["example1_endless","example2_open_ended","example3_stanford_jpl"].iter().map(|n| std::fs::read_to_string(format!("{}/../examples/mechanisms/{n}.ron", env!("CARGO_MANIFEST_DIR"))).unwrap()).collect();
    let vals = ["0.0","-1.0","1e9","1e-300","0.5","-0.02","0.3","2.0","1e300","-1e-9"];
    std::panic::set_hook(Box::new(|_| {}));
    let mut panics = 0; let mut oks = 0; let mut errs = std::collections::BTreeMap::new();
    for it in 0..4000 {
        let mut t = files[it % 3].clone();
        let nm = rng.random_range(1..4);
        for _ in 0..nm {
            match rng.random_range(0..6) {
                0 | 1 => { let n = tokens_num(&t); if n.is_empty() {continue}; let (a,b) = n[rng.random_range(0..n.len())]; t.replace_range(a..b, vals[rng.random_range(0..vals.len())]); }
                2 => { let q = quoted(&t); let (a,b) = q[rng.random_range(0..q.len())]; let (c,d) = q[rng.random_range(0..q.len())]; let s = t[c..d].to_string(); t.replace_range(a..b, &s); }
                3 => { if rng.random_bool(0.5) { t = t.replacen("Ccw", "Xw", 1).replace("Cw", "Ccw").replace("Xw", "Cw"); } else { let k = rng.random_range(0..3); let mut c = 0; t = t.split("Ccw").map(|s| s.to_string()).collect::<Vec<_>>().join("Ccw"); let _ = (k, &mut c); t = t.replacen(if rng.random_bool(0.5) {"fixed: true"} else {"crossed: false"}, if rng.random_bool(0.5) {"fixed: false"} else {"crossed: true"}, 1); } }
                4 => { let lines: Vec<&str> = t.lines().collect(); let k = rng.random_range(0..lines.len()); if lines[k].trim_start().starts_with("(name") { let mut l: Vec<&str> = lines.clone(); if rng.random_bool(0.5) { l.remove(k); } else { l.insert(k, lines[k]); } t = l.join("\n"); } }
                _ => { t = t.replacen("carrier: \"base\"", "carrier: \"link1\"", 1); }
            }
        }
        let r = std::panic::catch_unwind(|| {
            match tendyn_core::parse(&t) {
                Ok(m) => {
                    let mut s = tendyn_core::Solver::new(&m);
                    let n = m.dof;
                    let q: Vec<f64> = (0..n).map(|i| 0.3 * i as f64 + 0.1).collect();
                    let _ = s.inverse_dynamics(&q, &q, &q);
                    let _ = s.forward_dynamics(&q, &q, &vec![1.0; m.motors.len()], &vec![10.0; m.tendons.len()]);
                    let _ = s.mass_matrix(&q);
                    Ok(())
                }
                Err(e) => Err(e),
            }
        });
        match r {
            Err(p) => { panics += 1; if panics < 6 { let msg = p.downcast_ref::<&str>().map(|s| s.to_string()).or_else(|| p.downcast_ref::<String>().cloned()).unwrap_or_default(); eprintln!("PANIC {msg}\n--- diff:"); for (a,b) in files[it%3].lines().zip(t.lines()) { if a != b { eprintln!("- {a}\n+ {b}"); } } } }
            Ok(Ok(())) => oks += 1,
            Ok(Err(e)) => { let k = match &e { tendyn_core::Error::Invalid{problem,..} | tendyn_core::Error::Routing{problem,..} => problem.chars().take(50).collect::<String>(), o => format!("{o}").chars().take(60).collect() }; let loc0 = matches!(&e, tendyn_core::Error::Invalid{at,..} | tendyn_core::Error::Routing{at,..} if at.line == 0); *errs.entry((k, loc0)).or_insert(0) += 1; }
        }
    }
    eprintln!("panics {panics} oks {oks}");
    for (k, v) in errs { eprintln!("{v:5} {k:?}"); }
}
