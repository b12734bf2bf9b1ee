//! Readable equations for `tendyn equations`: the generated functions printed in
//! mathematical notation, with the joint variables named as in the paper (`th1`, `th1d`,
//! `th1dd`; `S2 = sin th2`, `C2 = cos th2`), every mass, centre of mass, inertia entry and
//! gravity component by name (`m2`, `c2x`, `I2zz`, `gy`) and runtime parameters by theirs,
//! so they can be set beside the paper's Eqs. 28-30, 33 and 35. Lengths and radii are the
//! file's numbers (the routing is derived from them).

use crate::expr::{Graph, Id, Node};
use crate::outputs::{result_labels, trace, Output, Traced};
use tendyn_core::Model;

thread_local! {
    /// Names of the runtime parameters of the mechanism being printed.
    static PARAMETERS: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn input_name(g: &Graph, i: u32) -> String {
    let name = &g.input_names[i as usize];
    let (array, index) = name.split_once('[').expect("array input");
    let k: usize = index.trim_end_matches(']').parse::<usize>().expect("index") + 1;
    match array {
        "params" => PARAMETERS.with(|p| p.borrow()[k - 1].clone()),
        "q" => format!("th{k}"),
        "qd" => format!("th{k}d"),
        "qdd" => format!("th{k}dd"),
        "motor_torques" => format!("tau{k}"),
        "tendon_tensions" => format!("T{k}"),
        other => format!("{other}{k}"),
    }
}

fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let s = format!("{x:.6e}");
    // 1.234500e-2 → 1.2345e-2; short numbers in plain form
    if (1e-3..1e4).contains(&x.abs()) {
        let t = format!("{x:.6}");
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// An expression in infix notation with the fewest parentheses; returns text and precedence.
fn show(g: &Graph, id: Id, names: &dyn Fn(Id) -> Option<String>) -> (String, u8) {
    if let Some(n) = names(id) {
        return (n, 4);
    }
    let operand = |x: Id, min: u8| {
        let (t, p) = show(g, x, names);
        if p < min {
            format!("({t})")
        } else {
            t
        }
    };
    match g.node(id) {
        Node::Const(bits) => {
            let x = f64::from_bits(bits);
            (number(x), if x < 0.0 { 3 } else { 4 })
        }
        Node::Input(i) => (input_name(g, i), 4),
        Node::Add(a, b) => match g.constant_value(b) {
            Some(c) if c < 0.0 => (format!("{} - {}", operand(a, 1), number(-c)), 1),
            _ => (format!("{} + {}", operand(a, 1), operand(b, 1)), 1),
        },
        Node::Sub(a, b) => (format!("{} - {}", operand(a, 1), operand(b, 2)), 1),
        Node::Mul(a, b) => (format!("{}*{}", operand(a, 2), operand(b, 2)), 2),
        Node::Div(a, b) => (format!("{}/{}", operand(a, 2), operand(b, 3)), 2),
        Node::Neg(a) => (format!("-{}", operand(a, 3)), 3),
        Node::Sin(a) => (trig(g, "S", a, names), 4),
        Node::Cos(a) => (trig(g, "C", a, names), 4),
        Node::Sqrt(a) => (format!("sqrt({})", show(g, a, names).0), 4),
        Node::Max(a, b) => (
            format!("max({}, {})", show(g, a, names).0, show(g, b, names).0),
            4,
        ),
    }
}

fn trig(g: &Graph, f: &str, a: Id, names: &dyn Fn(Id) -> Option<String>) -> String {
    match g.node(a) {
        Node::Input(i) => format!("{f}{}", input_name(g, i).trim_start_matches("th")),
        _ => format!(
            "{}({})",
            if f == "S" { "sin" } else { "cos" },
            show(g, a, names).0
        ),
    }
}

/// `model` with every non-zero mass, centre-of-mass component, inertia entry and gravity
/// component made a named parameter (`m2`, `c2x`, `I2zz`, `gy`; pulleys `m_idler3`, ...), so
/// that the equations show them by name. Geometry (lengths, radii) stays numeric: the
/// routing is derived from it.
fn with_named_quantities(model: &Model<f64>) -> Model<f64> {
    use tendyn_core::model::{Parameter, Slot};
    let mut m = model.clone();
    let taken: Vec<Slot> = m.parameter_slots.iter().map(|(s, _)| *s).collect();
    let add = |m: &mut Model<f64>, slot: Slot, name: String, value: f64| {
        if value != 0.0 && !taken.contains(&slot) {
            m.parameter_slots.push((slot, m.parameters.len()));
            m.parameters.push(Parameter { name, value });
        }
    };
    let axes = ["x", "y", "z"];
    for b in 0..model.bodies.len() {
        let body = &model.bodies[b];
        let tag = if b < model.dof {
            format!("{}", b + 1)
        } else {
            format!("_{}", body.name)
        };
        add(&mut m, Slot::Mass(b), format!("m{tag}"), body.mass);
        for (c, axis) in axes.iter().enumerate() {
            add(
                &mut m,
                Slot::Com(b, c),
                format!("c{tag}{axis}"),
                body.com.to_array()[c],
            );
        }
        for (r, c) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)] {
            add(
                &mut m,
                Slot::Inertia(b, r, c),
                format!("I{tag}{}{}", axes[r], axes[c]),
                body.inertia.rows[r][c],
            );
        }
    }
    for (c, axis) in axes.iter().enumerate() {
        add(
            &mut m,
            Slot::Gravity(c),
            format!("g{axis}"),
            model.gravity.to_array()[c],
        );
    }
    m
}

/// The equations of `outputs` (default: generalized forces, and the tension system's
/// actuation when there are tendons or motors) as text.
pub fn equations(model: &Model<f64>, outputs: &[Output]) -> Result<String, crate::Error> {
    let named = with_named_quantities(model);
    let model = &named;
    let traced: Traced = trace(model, outputs)?;
    PARAMETERS
        .with(|p| *p.borrow_mut() = model.parameters.iter().map(|p| p.name.clone()).collect());
    let g = &traced.graph;
    let mut out = String::new();
    out.push_str(&format!(
        "# {}: closed-form equations (th_k = joint angle q_k, th_kd, th_kdd its rates; S_k = sin th_k, C_k = cos th_k)\n",
        model.name
    ));
    if !model.tendons.is_empty() {
        out.push_str("\nStructure matrix A (Q = A T; rows per joint, columns per tendon):\n");
        for (j, row) in model.structure_matrix().iter().enumerate() {
            let cells: Vec<String> = row.iter().map(|&x| number(x)).collect();
            out.push_str(&format!(
                "  {:<10} [{}]\n",
                model.bodies[j].name,
                cells.join(", ")
            ));
        }
    }
    for f in &traced.functions {
        out.push_str(&format!(
            "\n{} ({}):\n",
            f.output.name(),
            g.count(&f.results)
        ));
        // Shared subexpressions become named temporaries w1, w2, ...
        let live = g.live(&f.results);
        let mut uses = std::collections::BTreeMap::<Id, usize>::new();
        for &id in &live {
            for c in g.node(id).children() {
                *uses.entry(c).or_default() += 1;
            }
        }
        let shared: Vec<Id> = live
            .iter()
            .copied()
            .filter(|id| {
                uses.get(id).copied().unwrap_or(0) > 1
                    && !matches!(
                        g.node(*id),
                        Node::Const(_) | Node::Input(_) | Node::Sin(_) | Node::Cos(_)
                    )
            })
            .collect();
        let name_of = |id: Id| {
            shared
                .iter()
                .position(|&s| s == id)
                .map(|k| format!("w{}", k + 1))
        };
        for (k, &id) in shared.iter().enumerate() {
            let body = {
                let inner = |x: Id| if x == id { None } else { name_of(x) };
                show(g, id, &inner).0
            };
            out.push_str(&format!("  w{} = {}\n", k + 1, body));
        }
        let labels = result_labels(model, f.output);
        for (i, &r) in f.results.iter().enumerate() {
            let label = match f.output {
                Output::MassMatrix => {
                    let n = model.dof;
                    format!("M[{}][{}]", labels[i / n], labels[i % n])
                }
                _ => labels.get(i).cloned().unwrap_or_else(|| format!("#{i}")),
            };
            let expr = if shared.contains(&r) {
                name_of(r).expect("named")
            } else {
                show(g, r, &name_of).0
            };
            out.push_str(&format!("  {} {label} = {expr}\n", f.output.name()));
        }
    }
    Ok(out)
}
