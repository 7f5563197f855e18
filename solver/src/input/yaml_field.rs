//! Names the scene field behind a YAML parser error: the dotted key path at a line and
//! column of the scene text (block mappings by indentation, flow mappings `{a: {b: 1}}` by
//! nesting), and the parser's type words in the user's terms (`invalid i64` -> `expected an
//! integer`), so that `mesh: {nx: abc}` reads `mesh.nx: expected an integer`.

/// The dotted path of the key whose value (or key) sits at 1-based `line`, `column` of
/// `text`; empty at the top level or past the end.
pub fn field_at(text: &str, line: u64, column: u64) -> String {
    let mut block: Vec<(usize, String)> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let number = i as u64 + 1;
        if number > line {
            break;
        }
        let content = without_comment(raw);
        if content.trim().is_empty() {
            continue;
        }
        let indent = content.len() - content.trim_start().len();
        let rest = content.trim_start().trim_start_matches("- ");
        let Some((key, after)) = split_key(rest) else {
            continue;
        };
        while block.last().is_some_and(|(d, _)| *d >= indent) {
            block.pop();
        }
        block.push((indent, key.to_string()));
        if number == line {
            let value_start = content.len() - after.len();
            let col = (column.max(1) - 1) as usize;
            let key_end = content.find(key).map_or(0, |p| p + key.len());
            if col < key_end {
                // The error points at the key itself.
                return join(&block);
            }
            let flow = flow_path(after, col.saturating_sub(value_start));
            let mut path: Vec<String> = block.into_iter().map(|(_, k)| k).collect();
            path.extend(flow);
            return path.join(".");
        }
    }
    join(&block)
}

fn join(block: &[(usize, String)]) -> String {
    block
        .iter()
        .map(|(_, k)| k.as_str())
        .collect::<Vec<_>>()
        .join(".")
}

/// `key: rest` -> (key, rest after the colon); `None` for a line without a plain key.
fn split_key(s: &str) -> Option<(&str, &str)> {
    let colon = s.find(':')?;
    let key = s[..colon].trim();
    let ok = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-' || c == '.');
    let after = &s[colon + 1..];
    (ok && (after.is_empty() || after.starts_with(' '))).then_some((key, after))
}

/// Keys open in a flow mapping at byte `upto` of `s` (the text after `key:`).
fn flow_path(s: &str, upto: usize) -> Vec<String> {
    let mut open: Vec<Option<String>> = Vec::new(); // per `{`: its key so far
    let mut token = String::new();
    for (i, c) in s.char_indices() {
        if i >= upto {
            break;
        }
        match c {
            '{' => open.push(None),
            '}' => {
                open.pop();
            }
            ',' => {
                if let Some(k) = open.last_mut() {
                    *k = None;
                }
            }
            ':' => {
                if let Some(k) = open.last_mut() {
                    *k = Some(token.trim().to_string());
                }
            }
            _ => {}
        }
        if matches!(c, '{' | '}' | ',' | ':' | '[' | ']') {
            token.clear();
        } else {
            token.push(c);
        }
    }
    // A key being typed at the position (the error points at a key): count it as the field.
    if let Some(last) = open.last_mut() {
        if last.is_none() && !token.trim().is_empty() {
            let rest = &s[upto.min(s.len())..];
            let key_end = rest.find(':').unwrap_or(0);
            *last = Some(format!("{}{}", token.trim(), &rest[..key_end]));
        }
    }
    open.into_iter().flatten().collect()
}

fn without_comment(line: &str) -> &str {
    let mut quote = None;
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, '#') if i == 0 || line[..i].ends_with(' ') => return &line[..i],
            _ => {}
        }
    }
    line
}

/// The parser's message in the user's terms, for a value at `field`.
pub fn explain(message: &str, field: &str) -> String {
    let parent = field.rsplit_once('.').map_or("", |(p, _)| p);
    let leaf = field.rsplit_once('.').map_or(field, |(_, l)| l);
    let words = match message {
        m if m.starts_with("invalid i") || m.starts_with("invalid u") => {
            "expected an integer".to_string()
        }
        "expected a number" | "invalid floating point" => "expected a number".to_string(),
        "expected string scalar" => {
            "expected a single value (a number or a word), not a list or a mapping".to_string()
        }
        "expected end of mapping after enum variant value" => format!(
            "{} takes exactly one kind, and a second one (`{leaf}`) is given here; keep one",
            if parent.is_empty() { "this" } else { parent }
        ),
        other => other.to_string(),
    };
    if field.is_empty() {
        words
    } else {
        format!("{field}: {words}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "\
title: t   # a comment: with a colon
plate: {length: 0.2, width: 0.2, thickness: 0.02}
mesh: {nx: abc, ny: 16, element: q4-sri}
load:
  impactor:
    mass: 18.0
    contact_law: {paper: {length_unit: 1.0}}
  pulse: {force: 1.0, duration: 1.0e-3}
output:
  probes: {A: {x: 0.1, y: 0.0}}
";

    #[test]
    fn fields_are_found_in_block_and_flow_mappings() {
        assert_eq!(field_at(SCENE, 3, 12), "mesh.nx");
        assert_eq!(field_at(SCENE, 3, 21), "mesh.ny");
        assert_eq!(field_at(SCENE, 6, 11), "load.impactor.mass");
        assert_eq!(
            field_at(SCENE, 7, 40),
            "load.impactor.contact_law.paper.length_unit"
        );
        assert_eq!(field_at(SCENE, 8, 3), "load.pulse");
        assert_eq!(field_at(SCENE, 10, 27), "output.probes.A.y");
        assert_eq!(field_at(SCENE, 1, 8), "title");
    }

    #[test]
    fn parser_words_become_the_users() {
        assert_eq!(
            explain("invalid i64", "mesh.nx"),
            "mesh.nx: expected an integer"
        );
        assert_eq!(
            explain("expected end of mapping after enum variant value", "load.pulse"),
            "load.pulse: load takes exactly one kind, and a second one (`pulse`) is given here; keep one"
        );
        assert_eq!(explain("unknown thing", ""), "unknown thing");
    }
}
