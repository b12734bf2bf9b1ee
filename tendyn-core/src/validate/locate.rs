//! Places in the RON text: a syntax error's span, an item's name, a field within an item
//! or a top-level key, turned into the line and column an error shows, and the errors that
//! carry them. Keys and parentheses are sought in code alone (strings and comments
//! blanked); names by their `name: "…"` definitions. Invariant: a
//! place is 1-based (lines, and columns in characters) in the text as written after a
//! byte-order mark, found from the text alone; `0:0` when it is not found (no text).

use super::Validator;
use crate::error::{Error, Location};

/// A RON error at the token it is about (ron's span may start on the whitespace before
/// it), with a hint where ron's message alone does not say what would fix it.
pub(super) fn syntax_error(text: &str, e: &ron::error::SpannedError) -> Error {
    let lines: Vec<&str> = text.lines().collect();
    let (mut line, mut column) = (e.span.start.line, e.span.start.col);
    // Skip forward over whitespace and `//` comments to the offending token (stay put at
    // the end of the text).
    let (mut l, mut c) = (line, column.max(1));
    while l >= 1 && l <= lines.len() {
        let rest: String = lines[l - 1].chars().skip(c - 1).collect();
        match rest.find(|ch: char| !ch.is_whitespace()) {
            Some(k) if !rest[k..].starts_with("//") => {
                (line, column) = (l, c + rest[..k].chars().count());
                break;
            }
            _ => (l, c) = (l + 1, 1),
        }
    }
    let mut message = e.code.to_string();
    match &e.code {
        ron::Error::ExpectedComma => {
            // The previous token (comments and blank lines skipped) on an earlier line: the
            // comma is missing at the end of that line.
            let code = |s: &str| s.split("//").next().unwrap_or("").trim_end().to_string();
            let current = lines.get(line.saturating_sub(1)).copied().unwrap_or("");
            let first_on_line = current
                .chars()
                .take(column.saturating_sub(1))
                .all(char::is_whitespace);
            if first_on_line {
                let before = line.min(lines.len() + 1);
                let prev = (1..before)
                    .rev()
                    .find(|&k| !code(lines[k - 1]).is_empty())
                    .filter(|&k| !code(lines[k - 1]).ends_with([',', '(', '[', '{']));
                if let Some(prev) = prev {
                    message = format!(
                        "{message}: a comma is missing at the end of line {prev}, after the value \
                         there"
                    );
                }
            } else {
                let found: String = current
                    .chars()
                    .skip(column.saturating_sub(1))
                    .take_while(|c| !c.is_whitespace())
                    .take(20)
                    .collect();
                message = format!("{message}, found `{found}`");
            }
        }
        ron::Error::MissingStructField { field, .. } => {
            message =
                format!("{message}: the item that ends here needs a `{field}: ...` entry; add it");
        }
        _ => {}
    }
    Error::Syntax {
        line,
        column,
        message,
    }
}

/// The places of the names in a file's text: every `name: "X"` definition of each name,
/// in order, and the first other quoted occurrence of it. Built once, so that locating
/// every item costs one pass over the text, not one per item (which made loading a file
/// of many pulleys quadratic).
#[derive(Default)]
pub(super) struct NameIndex {
    definitions: std::collections::HashMap<String, Vec<Location>>,
    references: std::collections::HashMap<String, Location>,
}

impl NameIndex {
    pub(super) fn of(text: &str) -> Self {
        let mut index = NameIndex::default();
        for (i, line) in text.lines().enumerate() {
            for (col, name) in string_literals(line) {
                let at = Location {
                    line: i + 1,
                    column: line[..col].chars().count() + 1,
                };
                if is_name_field(&line[..col]) {
                    index
                        .definitions
                        .entry(name.to_string())
                        .or_default()
                        .push(at);
                } else {
                    index.references.entry(name.to_string()).or_insert(at);
                }
            }
        }
        index
    }
}

/// The string literals of one line of RON, as (byte offset of the opening quote, content
/// between the quotes), up to a `//` comment outside them (so a name may hold `//`).
fn string_literals(line: &str) -> Vec<(usize, &str)> {
    let mut found = Vec::new();
    let mut open: Option<usize> = None;
    let mut escaped = false;
    let mut previous = '\0';
    for (at, c) in line.char_indices() {
        match open {
            Some(start) => {
                if escaped {
                    escaped = false;
                } else if c == '\\' {
                    escaped = true;
                } else if c == '"' {
                    found.push((start, &line[start + 1..at]));
                    open = None;
                }
            }
            None if c == '"' => open = Some(at),
            None if c == '/' && previous == '/' => break,
            None => {}
        }
        previous = c;
    }
    found
}

/// `text`'s lines with every string literal (escapes included) and comment (`//` and
/// `/* */`) blanked, each of their characters a space: keys and parentheses are looked for
/// in code alone, at the columns they have in the text.
fn code_lines(text: &str) -> Vec<String> {
    #[derive(PartialEq)]
    enum In {
        Code,
        String,
        Comment,
    }
    let mut state = In::Code;
    let mut lines = Vec::new();
    for line in text.lines() {
        let chars: Vec<char> = line.chars().collect();
        let mut code = String::with_capacity(line.len());
        let mut i = 0;
        while i < chars.len() {
            let (c, next) = (chars[i], chars.get(i + 1).copied());
            let (keep, width) = match state {
                In::Code => match (c, next) {
                    ('/', Some('/')) => (false, chars.len() - i),
                    ('/', Some('*')) => {
                        state = In::Comment;
                        (false, 2)
                    }
                    ('"', _) => {
                        state = In::String;
                        (false, 1)
                    }
                    _ => (true, 1),
                },
                In::String => {
                    if c == '"' {
                        state = In::Code;
                    }
                    (false, if c == '\\' { 2 } else { 1 })
                }
                In::Comment => {
                    if (c, next) == ('*', Some('/')) {
                        state = In::Code;
                        (false, 2)
                    } else {
                        (false, 1)
                    }
                }
            };
            let width = width.min(chars.len() - i);
            match keep {
                true => code.push(c),
                false => code.extend(std::iter::repeat_n(' ', width)),
            }
            i += width;
        }
        lines.push(code);
    }
    lines
}

/// The unmatched `(` before `at` and `)` after it in `code` ([`code_lines`]): the bounds of
/// the item whose field `at` is; the start or end of the text where there is none.
fn enclosing_parentheses(code: &[String], at: Location) -> (Location, Location) {
    let parentheses: Vec<(Location, char)> = (code.iter().enumerate())
        .flat_map(|(i, line)| {
            (line.chars().enumerate())
                .filter(|&(_, c)| c == '(' || c == ')')
                .map(move |(column, c)| {
                    let place = Location {
                        line: i + 1,
                        column: column + 1,
                    };
                    (place, c)
                })
        })
        .collect();
    let order = |l: &Location| (l.line, l.column);
    let split = parentheses.partition_point(|(l, _)| order(l) < order(&at));
    let mut depth = 0i32;
    let open = parentheses[..split].iter().rev().find(|(_, c)| {
        depth += if *c == ')' { 1 } else { -1 };
        depth < 0
    });
    depth = 0;
    let close = parentheses[split..].iter().find(|(_, c)| {
        depth += if *c == '(' { 1 } else { -1 };
        depth < 0
    });
    let end = Location {
        line: usize::MAX,
        column: 0,
    };
    (
        open.map_or(Location::default(), |(l, _)| *l),
        close.map_or(end, |(l, _)| *l),
    )
}

/// The places of `key:` (a whole word of `code`, [`code_lines`]) from `start` up to, not
/// including, `end`, in the order of the text.
fn keys_between(code: &[String], key: &str, start: Location, end: Location) -> Vec<Location> {
    let order = |l: &Location| (l.line, l.column);
    let mut found = Vec::new();
    for (i, line) in code.iter().enumerate().skip(start.line.saturating_sub(1)) {
        for (col, _) in line.match_indices(key) {
            let before_ok = !line[..col]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_alphanumeric() || c == '_');
            let place = Location {
                line: i + 1,
                column: line[..col].chars().count() + 1,
            };
            if order(&place) >= order(&end) {
                return found;
            }
            if before_ok
                && line[col + key.len()..].trim_start().starts_with(':')
                && order(&place) >= order(&start)
            {
                found.push(place);
            }
        }
        if i + 1 >= end.line {
            break;
        }
    }
    found
}

/// Whether the text before a quoted string ends in `name:` (the string is an item's name).
fn is_name_field(before: &str) -> bool {
    let Some(rest) = before.trim_end().strip_suffix(':') else {
        return false;
    };
    let Some(rest) = rest.trim_end().strip_suffix("name") else {
        return false;
    };
    !rest
        .chars()
        .next_back()
        .is_some_and(|c| c.is_alphanumeric() || c == '_')
}

/// `"the links are `a`, `b`"`: what a misspelt reference could have meant.
pub(super) fn candidates<'n>(kind: &str, names: impl Iterator<Item = &'n str>) -> String {
    let names: Vec<String> = names.map(|n| format!("`{n}`")).collect();
    if names.is_empty() {
        format!("the file has no {kind}")
    } else {
        format!("the {kind} are {}", names.join(", "))
    }
}

impl Validator<'_> {
    /// Line and column of the item named `name`: its `name: "…"` field, or failing that
    /// the first quoted occurrence. Text in `//` comments is not looked at.
    pub(super) fn locate(&self, name: &str) -> Location {
        self.locate_nth(name, 0)
    }

    /// Line and column of the `nth` (0-based) `name: "…"` definition of `name`, or
    /// failing that the first quoted occurrence of it.
    pub(super) fn locate_nth(&self, name: &str, nth: usize) -> Location {
        let names = &self.names;
        names
            .definitions
            .get(name)
            .and_then(|d| d.get(nth))
            .or_else(|| names.references.get(name))
            .copied()
            .unwrap_or_default()
    }

    /// Line and column of a top-level field `key:` (`gravity`, `external_wrench`, …).
    pub(super) fn locate_key(&self, key: &str) -> Location {
        let end = Location {
            line: usize::MAX,
            column: 0,
        };
        keys_between(&code_lines(self.text), key, Location::default(), end)
            .into_iter()
            .next()
            .unwrap_or_default()
    }

    /// Line and column of the field `path` of the item named `name` (`"mu"`, or
    /// `"friction.coulomb"`: each key within the one before), within the parentheses of the
    /// item whose `name: "…"` it is: after the name, then before it; the item's name where
    /// the field is not written (a default), or a name given twice: its first definition.
    pub(super) fn locate_field(&self, name: &str, path: &str) -> Location {
        let at = self.locate(name);
        if at.line == 0 {
            return at;
        }
        let code = code_lines(self.text);
        let (open, close) = enclosing_parentheses(&code, at);
        let mut keys = path.split('.');
        let first = keys.next().unwrap_or(path);
        let chain = |start: Location, end: Location| {
            keys.clone().try_fold(start, |from, key| {
                keys_between(&code, key, from, end).into_iter().next()
            })
        };
        let after = keys_between(&code, first, at, close).into_iter().next();
        let before = keys_between(&code, first, open, at).into_iter().last();
        (after.and_then(|k| chain(k, close)))
            .or_else(|| before.and_then(|k| chain(k, at)))
            .unwrap_or(at)
    }

    /// A file's error about the field `path` of `item` ([`Validator::locate_field`]), at
    /// that field's place.
    pub(super) fn invalid_field(
        &self,
        item: &str,
        path: &str,
        problem: impl Into<String>,
    ) -> Error {
        Error::Invalid {
            item: item.to_string(),
            at: self.locate_field(item, path),
            problem: problem.into(),
        }
    }

    /// A file's error about `item`, at the place of its name.
    pub(super) fn invalid(&self, item: &str, problem: impl Into<String>) -> Error {
        Error::Invalid {
            item: item.to_string(),
            at: self.locate(item),
            problem: problem.into(),
        }
    }

    /// A routing's error about `item`, at the place of its name (the system it implies is
    /// added where one has been built).
    pub(super) fn routing(&self, item: &str, problem: impl Into<String>) -> Error {
        Error::Routing {
            item: item.to_string(),
            at: self.locate(item),
            problem: problem.into(),
            implied: None,
        }
    }

    /// An error about the mechanism's top-level field `key`, at its line (at the
    /// mechanism's, should the key not be found).
    pub(super) fn invalid_at_key(&self, item: &str, key: &str, problem: String) -> Error {
        let at = self.locate_key(key);
        Error::Invalid {
            item: item.to_string(),
            at: if at.line == 0 { self.locate(item) } else { at },
            problem,
        }
    }
}
