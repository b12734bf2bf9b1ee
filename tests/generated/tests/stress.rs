//! Generated code on the stress suite (`tendyn_spec::stress`): for every case whose
//! mechanism `build.rs` generated code for (the paper's examples, and `STRESS`), every
//! generated output against the double-double reference under the suite's condition rule:
//! within `C u κ` always, within 1e-9 on well-conditioned cases and 1e-12 on the paper's
//! examples (max-norm relative per output, floored at 1 % of the output's typical size).

use tendyn_generated_tests::{Mechanism, MECHANISMS, STRESS};
use tendyn_spec::stress::{self, measure_case, Group, Options, WELL_CONDITIONED_TARGET};

#[test]
fn generated_code_on_the_stress_cases_is_within_its_condition_bound() {
    let u = f64::EPSILON / 2.0;
    let registry: Vec<&Mechanism> = MECHANISMS.iter().chain(STRESS).collect();
    let mut covered = Vec::new();
    for case in stress::cases() {
        let Some(mech) = registry.iter().find(|m| m.ron == case.text) else {
            continue;
        };
        let evaluate = |q: &[f64], qd: &[f64], qdd: &[f64], mt: &[f64], tt: &[f64]| {
            (mech.evaluate)(q, qd, qdd, mt, tt, &[])
        };
        let options = Options {
            states: 40,
            f32: false,
        };
        let f = measure_case(&case, options, Some(&evaluate)).unwrap();
        let g = f.generated_f64.expect("generated figures");
        for o in &f.outputs {
            let Some(e) = o.generated_f64.filter(|e| e.count > 0) else {
                continue;
            };
            let bound = f.bound(o, u);
            assert!(
                e.max <= bound,
                "{} {}: generated is {:.2e} from the reference, above C u κ = {bound:.2e}",
                case.name,
                o.name,
                e.max
            );
        }
        if f.well_conditioned() {
            assert!(
                g.max <= WELL_CONDITIONED_TARGET,
                "{}: {:.2e}",
                case.name,
                g.max
            );
        }
        if case.group == Group::PaperExample {
            assert!(g.max <= 1e-12, "{}: {:.2e}", case.name, g.max);
        }
        covered.push(format!("{} {:.1e}/{:.1e}", case.name, g.max, g.median));
    }
    println!("{}", covered.join("\n"));
    // The examples (with their extreme states) and every STRESS mechanism (the chain with
    // its extreme states).
    assert!(
        covered.len() >= 3 + 8 + STRESS.len() + 3,
        "covered only {covered:?}"
    );
}
