//! Runtime parameters: the declared ones checked (unique, finite, each used, every
//! reference declared), the nominal values validation checks with, and the model slots each
//! sets. Invariant: once `parameters` has passed, every `Num::Param` of the file names a
//! declared parameter, so a number's nominal value is always found.

use super::Validator;
use crate::error::{Error, Result};
use crate::format::{MechanismFile, Num};
use crate::model::Slot;

impl Validator<'_> {
    /// A number's nominal value (a parameter's declared value).
    pub(super) fn num(&self, n: &Num) -> f64 {
        match n {
            Num::Value(x) => *x,
            Num::Param(name) => self
                .params
                .iter()
                .find(|(p, _)| p == name)
                .map(|(_, v)| *v)
                .expect("parameter references are checked first"),
        }
    }

    /// The nominal values of an array of numbers.
    pub(super) fn nums<const K: usize>(&self, n: &[Num; K]) -> [f64; K] {
        std::array::from_fn(|k| self.num(&n[k]))
    }

    /// Declared parameters: unique, finite, and every reference to one names a declared
    /// one; a declared parameter nothing uses is an error too. Checked first (every later
    /// check reads their values), after the mechanism's name: errors about the whole file
    /// name it.
    pub(super) fn parameters(&self, f: &MechanismFile) -> Result<Vec<(String, f64)>> {
        if f.name.trim().is_empty() {
            return Err(Error::Invalid {
                item: "the mechanism".into(),
                at: self.locate(&f.name),
                problem: "its `name` is empty; give it one (it names the generated code and \
                          every report)"
                    .into(),
            });
        }
        let mut params: Vec<(String, f64)> = Vec::new();
        for p in &f.parameters {
            if params.iter().any(|(n, _)| *n == p.name) {
                return Err(self.invalid(
                    &p.name,
                    format!("the parameter `{}` is declared twice", p.name),
                ));
            }
            self.finite(&p.name, "value", &[p.value])?;
            params.push((p.name.clone(), p.value));
        }
        let mut used = vec![false; params.len()];
        for (item, field, n) in numbers(f) {
            if let Num::Param(name) = n {
                match params.iter().position(|(p, _)| p == name) {
                    Some(k) => used[k] = true,
                    None => {
                        return Err(self.invalid(
                            item,
                            format!(
                                "`{field}` names the parameter `{name}`, which is not declared; add \
                                 `(name: \"{name}\", value: ...)` to `parameters` or write a number"
                            ),
                        ))
                    }
                }
            }
        }
        if let Some(k) = used.iter().position(|u| !u) {
            let name = &params[k].0;
            return Err(self.invalid(
                name,
                format!(
                    "the parameter `{name}` is declared but no number uses it; remove it or use it"
                ),
            ));
        }
        Ok(params)
    }
}

/// Every number of the file that may name a parameter: (item, field, number).
fn numbers(f: &MechanismFile) -> Vec<(&str, &'static str, &Num)> {
    let mut v: Vec<(&str, &'static str, &Num)> = Vec::new();
    for g in &f.gravity {
        v.push((&f.name, "gravity", g));
    }
    let bodies = f
        .links
        .iter()
        .map(|l| (&l.name, &l.mass, &l.com, &l.inertia))
        .chain(
            f.pulleys
                .iter()
                .map(|p| (&p.name, &p.mass, &p.com, &p.inertia)),
        );
    for (name, mass, com, i) in bodies {
        v.push((name, "mass", mass));
        for c in com {
            v.push((name, "com", c));
        }
        for x in [&i.xx, &i.yy, &i.zz, &i.xy, &i.xz, &i.yz] {
            v.push((name, "inertia", x));
        }
    }
    if let Some(w) = &f.external_wrench {
        for (field, arr) in [
            ("point", &w.point),
            ("force", &w.force),
            ("moment", &w.moment),
        ] {
            for x in arr {
                v.push((&f.name, field, x));
            }
        }
    }
    v
}

/// Which model numbers each parameter sets (links are bodies `0..n`, pulleys follow in
/// file order).
pub(super) fn parameter_slots(f: &MechanismFile) -> Vec<(Slot, usize)> {
    let index = |n: &Num| match n {
        Num::Param(name) => f.parameters.iter().position(|p| p.name == *name),
        Num::Value(_) => None,
    };
    let mut slots = Vec::new();
    let mut push = |n: &Num, slot: Slot| {
        if let Some(k) = index(n) {
            slots.push((slot, k));
        }
    };
    for (c, g) in f.gravity.iter().enumerate() {
        push(g, Slot::Gravity(c));
    }
    let bodies = f
        .links
        .iter()
        .map(|l| (&l.mass, &l.com, &l.inertia))
        .chain(f.pulleys.iter().map(|p| (&p.mass, &p.com, &p.inertia)));
    for (b, (mass, com, i)) in bodies.enumerate() {
        push(mass, Slot::Mass(b));
        for (c, x) in com.iter().enumerate() {
            push(x, Slot::Com(b, c));
        }
        for (x, (r, c)) in [&i.xx, &i.yy, &i.zz, &i.xy, &i.xz, &i.yz].into_iter().zip([
            (0, 0),
            (1, 1),
            (2, 2),
            (0, 1),
            (0, 2),
            (1, 2),
        ]) {
            push(x, Slot::Inertia(b, r, c));
        }
    }
    if let Some(w) = &f.external_wrench {
        for c in 0..3 {
            push(&w.point[c], Slot::WrenchPoint(c));
            push(&w.force[c], Slot::WrenchForce(c));
            push(&w.moment[c], Slot::WrenchMoment(c));
        }
    }
    slots
}
