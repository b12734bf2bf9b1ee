//! `tendyn identify --consistent --write OUT.ron`: the mechanism's own file with every
//! body's `mass`, `com`, `inertia` (and, where it has one, `friction`) replaced by the
//! physically consistent estimate, everything else (comments, layout, order) as written.
//!
//! The text is edited, not re-serialised: a scanner that knows RON's strings and comments
//! finds each body's entry by its `name: "…"` field in the `links` and `pulleys` lists,
//! and the four fields among the entry's own (depth one); a field the entry lacks is added
//! right after its opening parenthesis (its end may be inside a comment). A `mass` given
//! as a runtime parameter's name keeps it, and the parameter's declared value becomes the
//! estimate (refused where the parameter also sets other numbers). The result is parsed
//! and validated again, and each body's parameters compared with the estimate's, before it
//! is written: a file that would not load, or would not hold the estimate, is an error and
//! nothing is written.

use tendyn_core::model::Model;
use tendyn_core::physical_consistency::{BodyEstimate, Consistent};
use tendyn_core::regressor;

/// `text` (the file `model` was loaded from) with the estimate's mass properties.
pub fn with_estimate(text: &str, model: &Model<f64>, c: &Consistent) -> Result<String, String> {
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    // Runtime parameters a whole field names (`mass: "payload"`): their declared values.
    let mut parameters: Vec<(String, f64, String)> = Vec::new();
    for key in ["links", "pulleys"] {
        let Some((start, end)) = top_level_list(text, key) else {
            continue;
        };
        for (entry_start, entry_end) in entries(text, start, end) {
            let entry = &text[entry_start..entry_end];
            let Some(name) = field(entry, "name").and_then(|(s, e)| string_value(&entry[s..e]))
            else {
                continue;
            };
            let Some(b) = model.bodies().iter().position(|b| b.name == name) else {
                continue;
            };
            for edit in entry_edits(entry, &c.bodies[b]) {
                match edit {
                    Edit::Text(s, e, t) => edits.push((entry_start + s, entry_start + e, t)),
                    Edit::Parameter(p, value, field) => {
                        let field = format!("{name}.{field}");
                        if let Some((_, v, other)) = parameters.iter().find(|x| x.0 == p) {
                            if *v != value {
                                return Err(format!(
                                    "the runtime parameter `{p}` sets both `{other}` and \
                                     `{field}`, which the estimate gives different values; \
                                     give them numbers or a parameter each"
                                ));
                            }
                        }
                        parameters.push((p, value, field));
                    }
                    Edit::Refuse(field) => {
                        return Err(format!(
                            "`{name}.{field}` names a runtime parameter inside it; the estimate \
                             can replace a whole field's parameter (`mass: \"payload\"`) but \
                             not one entry's: give numbers there"
                        ))
                    }
                }
            }
        }
    }
    // A parameter that also sets something else (gravity, another field) would change it.
    for (p, _, field) in &parameters {
        let uses = text.matches(&format!("\"{p}\"")).count();
        let masses = parameters.iter().filter(|x| &x.0 == p).count();
        if uses != masses + 1 {
            return Err(format!(
                "the runtime parameter `{p}` that `{field}` names also sets other numbers, \
                 which the estimate would change with it; give `{field}` a parameter of its own"
            ));
        }
    }
    if let Some((start, end)) = top_level_list(text, "parameters") {
        for (entry_start, entry_end) in entries(text, start, end) {
            let entry = &text[entry_start..entry_end];
            let name = field(entry, "name").and_then(|(s, e)| string_value(&entry[s..e]));
            let found = parameters.iter().find(|p| Some(p.0.as_str()) == name);
            if let (Some((_, value, _)), Some((s, e))) = (found, field(entry, "value")) {
                edits.push((entry_start + s, entry_start + e, format!("{value:e}")));
            }
        }
    }
    edits.sort_by_key(|e| std::cmp::Reverse(e.0));
    let mut out = text.to_string();
    for (s, e, t) in edits {
        out.replace_range(s..e, &t);
    }
    // The written file must load and hold the estimate.
    let written = tendyn_core::parse(&out)
        .map_err(|e| format!("the file with the estimate does not load ({e}); nothing written"))?;
    // Each body's parameters against the estimate's, to 1e-9 of that body's largest.
    let (values, estimate) = (regressor::values(&written), &c.parameters);
    let of = regressor::parameters(&written);
    let mut largest = vec![0.0f64; written.bodies().len()];
    for (p, x) in of.iter().zip(estimate) {
        largest[p.body] = largest[p.body].max(x.abs());
    }
    let holds = values.len() == estimate.len()
        && (of.iter().zip(values.iter().zip(estimate)))
            .all(|(p, (v, e))| (v - e).abs() <= 1e-9 * largest[p.body]);
    if !holds {
        return Err(
            "the file with the estimate does not hold it (a body's mass properties could not \
             be found in the text); nothing written"
                .into(),
        );
    }
    Ok(out)
}

/// What the estimate does to one field of a body's entry.
enum Edit {
    /// Replace `start..end` of the entry by the text.
    Text(usize, usize, String),
    /// The field is the runtime parameter named: set its declared value (and the field).
    Parameter(String, f64, &'static str),
    /// A runtime parameter is named inside the field (one entry of a tuple).
    Refuse(&'static str),
}

/// The edits of one entry, offsets in the entry.
fn entry_edits(entry: &str, e: &BodyEstimate) -> Vec<Edit> {
    let i = &e.inertia;
    let mut values: Vec<(&'static str, String)> = vec![
        ("mass", format!("{:e}", e.mass)),
        (
            "com",
            format!("({:e}, {:e}, {:e})", e.com[0], e.com[1], e.com[2]),
        ),
        (
            "inertia",
            format!(
                "(xx: {:e}, yy: {:e}, zz: {:e}, xy: {:e}, xz: {:e}, yz: {:e})",
                i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2]
            ),
        ),
    ];
    if let Some((coulomb, viscous)) = e.friction {
        values.push((
            "friction",
            format!("(coulomb: {coulomb:e}, viscous: {viscous:e})"),
        ));
    }
    let mut edits = Vec::new();
    let mut missing = String::new();
    for (key, value) in values {
        match field(entry, key) {
            Some((s, end)) => {
                let written = &entry[s..end];
                // Only `mass` is one number; the others are tuples.
                if let Some(p) = string_value(written).filter(|_| key == "mass") {
                    edits.push(Edit::Parameter(p.to_string(), e.mass, key));
                } else if scan(written).any(|t| t.1 == '"') {
                    edits.push(Edit::Refuse(key));
                } else {
                    edits.push(Edit::Text(s, end, value));
                }
            }
            None => missing.push_str(&format!("{key}: {value}, ")),
        }
    }
    if !missing.is_empty() {
        // First, right after the opening parenthesis (fields may come in any order): the
        // end of the entry may be inside a comment.
        edits.push(Edit::Text(1, 1, missing));
    }
    edits
}

/// The span `[`…`]` (brackets included) of the top-level key `key`'s list.
fn top_level_list(text: &str, key: &str) -> Option<(usize, usize)> {
    let outer = first_open(text)?;
    let (s, e) = field(&text[outer..], key)?;
    let (s, e) = (outer + s, outer + e);
    text[s..e].starts_with('[').then_some((s, e))
}

/// The byte offset of the first `(` outside comments: the mechanism's own.
fn first_open(text: &str) -> Option<usize> {
    scan(text)
        .find(|&(_, c, depth)| c == '(' && depth == 0)
        .map(|(at, _, _)| at)
}

/// The `(`…`)` entries of the list spanning `[start, end)` (brackets included).
fn entries(text: &str, start: usize, end: usize) -> Vec<(usize, usize)> {
    let mut found = Vec::new();
    let mut open = None;
    for (at, c, depth) in scan(&text[start..end]) {
        match (c, depth) {
            ('(', 1) => open = Some(at),
            (')', 2) => {
                if let Some(s) = open.take() {
                    found.push((start + s, start + at + 1));
                }
            }
            _ => {}
        }
    }
    found
}

/// The span of field `key`'s value among the fields of the parenthesised item that
/// `item` starts with (depth one), trimmed.
fn field(item: &str, key: &str) -> Option<(usize, usize)> {
    let tokens: Vec<(usize, char, usize)> = scan(item).collect();
    for (k, &(at, _, depth)) in tokens.iter().enumerate() {
        // `key` starts a field: at depth one, preceded by `(` or `,` and followed by `:`.
        if depth != 1 || !item[at..].starts_with(key) {
            continue;
        }
        let before = tokens[..k].iter().rev().find(|t| !t.1.is_whitespace());
        if !matches!(before, Some(&(_, '(' | ',', _))) {
            continue;
        }
        let after: Vec<&(usize, char, usize)> = tokens[k..]
            .iter()
            .skip(key.chars().count())
            .skip_while(|t| t.1.is_whitespace())
            .collect();
        if !matches!(after.first(), Some(&&(_, ':', _))) {
            continue;
        }
        let value: Vec<&&(usize, char, usize)> = after[1..]
            .iter()
            .skip_while(|t| t.1.is_whitespace())
            .collect();
        let start = value.first()?.0;
        // The value ends before the `,` or `)` that is back at depth one.
        let end = value
            .iter()
            .find(|t| t.2 == 1 && (t.1 == ',' || t.1 == ')'))
            .map_or(item.len(), |t| t.0);
        let end = start + item[start..end].trim_end().len();
        return Some((start, end));
    }
    None
}

/// The text of a RON string literal `"…"` (no escapes in names).
fn string_value(literal: &str) -> Option<&str> {
    literal.strip_prefix('"')?.strip_suffix('"')
}

/// The characters of `text` outside comments and string literals' insides (a string's
/// quotes are kept, its content is not), each with its byte offset and the bracket depth
/// before it (an opening bracket at depth `d` is reported at `d`, its closing one at
/// `d + 1`).
fn scan(text: &str) -> impl Iterator<Item = (usize, char, usize)> + '_ {
    let mut chars = text.char_indices().peekable();
    let mut depth = 0usize;
    std::iter::from_fn(move || loop {
        let (at, c) = chars.next()?;
        match c {
            '/' if chars.peek().is_some_and(|&(_, n)| n == '/') => {
                for (_, n) in chars.by_ref() {
                    if n == '\n' {
                        break;
                    }
                }
            }
            '/' if chars.peek().is_some_and(|&(_, n)| n == '*') => {
                chars.next();
                let mut last = '\0';
                for (_, n) in chars.by_ref() {
                    if last == '*' && n == '/' {
                        break;
                    }
                    last = n;
                }
            }
            '"' => {
                let mut escaped = false;
                for (_, n) in chars.by_ref() {
                    if escaped {
                        escaped = false;
                    } else if n == '\\' {
                        escaped = true;
                    } else if n == '"' {
                        break;
                    }
                }
                return Some((at, '"', depth));
            }
            '(' | '[' | '{' => {
                depth += 1;
                return Some((at, c, depth - 1));
            }
            ')' | ']' | '}' => {
                let d = depth;
                depth = depth.saturating_sub(1);
                return Some((at, c, d));
            }
            _ => return Some((at, c, depth)),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A field's value is found among the item's own fields only: not in a nested item, a
    /// string or a comment, and whatever the spacing.
    #[test]
    fn a_field_is_the_item_s_own_not_a_nested_one_a_string_s_or_a_comment_s() {
        let item = r#"(name: "mass: 1, (", at: Pose(mass: 2), // mass: 3,
            /* mass: 4 */ mass :  5.0 , com: (1, 2, 3))"#;
        let (s, e) = field(item, "mass").unwrap();
        assert_eq!(&item[s..e], "5.0");
        let (s, e) = field(item, "com").unwrap();
        assert_eq!(&item[s..e], "(1, 2, 3)");
        let (s, e) = field(item, "name").unwrap();
        assert_eq!(string_value(&item[s..e]), Some("mass: 1, ("));
        assert_eq!(field(item, "inertia"), None);
        assert_eq!(field(item, "ma"), None);
    }

    /// The entries of a top-level list, each `(`…`)`.
    #[test]
    fn a_top_level_list_s_entries_are_its_parenthesised_items() {
        let text = "// (not this)\n(name: \"m\", links: [(name: \"a\", x: (1)), (name: \"b\"),], \
                    pulleys: [])";
        let (s, e) = top_level_list(text, "links").unwrap();
        let found: Vec<&str> = entries(text, s, e)
            .into_iter()
            .map(|(a, b)| &text[a..b])
            .collect();
        assert_eq!(found, ["(name: \"a\", x: (1))", "(name: \"b\")"]);
        let (s, e) = top_level_list(text, "pulleys").unwrap();
        assert!(entries(text, s, e).is_empty());
    }
}
