//! Names the scene field behind a YAML parser error: the dotted key path at a line and
//! column of the scene text (block mappings by indentation, flow mappings `{a: {b: 1}}` by
//! nesting), and the parser's type words in the user's terms (`invalid i64` -> `expected an
//! integer`), so that `mesh: {nx: abc}` reads `mesh.nx: expected an integer`.

/// The dotted path of the key whose value (or key) sits at 1-based `line`, `column` of
/// `text`; empty at the top level or past the end. Items of a block list of mappings
/// (`checks:` then `- id: ...` lines, as in case files) are numbered: `checks[1].tolerance`.
pub fn field_at(text: &str, line: u64, column: u64) -> String {
    // (indent, name, is a list item); an item's keys sit two columns right of its dash.
    let mut block: Vec<(usize, String, bool)> = Vec::new();
    let mut items: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    for (i, raw) in text.lines().enumerate() {
        let number = i as u64 + 1;
        if number > line {
            break;
        }
        let content = without_comment(raw);
        if content.trim().is_empty() {
            continue;
        }
        let mut indent = content.len() - content.trim_start().len();
        let mut rest = content.trim_start();
        if let Some(item) = rest.strip_prefix("- ") {
            // A new item: leave the previous one (and anything deeper), keep the list's key
            // (at this indent or less: `checks:` then `- ...` may share a column).
            while block
                .last()
                .is_some_and(|(d, _, is_item)| *d > indent || (*d == indent && *is_item))
            {
                block.pop();
            }
            let parent = join(&block);
            let n = items.entry(parent.clone()).or_insert(0);
            block.push((indent, format!("[{n}]"), true));
            *n += 1;
            indent += 2;
            rest = item.trim_start();
        }
        let Some((key, after)) = split_key(rest) else {
            continue;
        };
        while block.last().is_some_and(|(d, _, _)| *d >= indent) {
            block.pop();
        }
        block.push((indent, key.to_string(), false));
        if number == line {
            let value_start = content.len() - after.len();
            let col = (column.max(1) - 1) as usize;
            let key_end = content.find(key).map_or(0, |p| p + key.len());
            if col < key_end {
                // The error points at the key itself.
                return join(&block);
            }
            let flow = flow_path(after, col.saturating_sub(value_start));
            let mut path = join(&block);
            for f in flow {
                path.push('.');
                path.push_str(&f);
            }
            return path;
        }
    }
    join(&block)
}

/// `a`, `b`, `[0]`, `c` -> `a.b[0].c`.
fn join(block: &[(usize, String, bool)]) -> String {
    let mut path = String::new();
    for (_, name, is_item) in block {
        if !path.is_empty() && !is_item {
            path.push('.');
        }
        path.push_str(name);
    }
    path
}

/// `key: rest` -> (key, rest after the colon); `None` for a line without a plain key. A key
/// in double quotes counts as its text: the Python package hands dict scenes over as JSON
/// (`"kinematics": "large"`), whose fields must be named as a file's are.
fn split_key(s: &str) -> Option<(&str, &str)> {
    let colon = s.find(':')?;
    let raw = s[..colon].trim();
    let key = raw
        .strip_prefix('"')
        .and_then(|k| k.strip_suffix('"'))
        .unwrap_or(raw);
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

/// The YAML parser's message without the location it repeats (the caller prints its own) and
/// without hints meant for programmers: its first line, `line N column M:` and
/// `at line N, column M` taken out, the duplicate-key policy hint dropped.
pub fn parser_words(message: &str) -> String {
    let first = message.lines().next().unwrap_or(message).trim();
    let mut text = first.strip_prefix("error: ").unwrap_or(first);
    if let Some(rest) = text.strip_prefix("line ") {
        // "line N column M: message"
        if let Some((_, after)) = rest.split_once(": ") {
            text = after;
        }
    }
    let text = text
        .split(", set DuplicateKeyPolicy")
        .next()
        .unwrap_or(text);
    let text = text.split(" at line ").next().unwrap_or(text);
    match text {
        "invalid floating point" => "expected a number".to_string(),
        other => other.to_string(),
    }
}

/// The parser's message in the user's terms, for a value at `field`.
pub fn explain(message: &str, field: &str) -> String {
    // An item of a list at the top level is no field of a scene.
    let field = if field.starts_with('[') { "" } else { field };
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
        m if m.starts_with("non-finite float") => "must be a finite number".to_string(),
        "expected string key for externally tagged enum"
        | "externally tagged enum expected scalar or mapping"
            if words(leaf).is_some() =>
        {
            format!(
                "expected one word, {}, not a list or a mapping",
                words(leaf).unwrap_or_default()
            )
        }
        "expected string key for externally tagged enum"
        | "externally tagged enum expected scalar or mapping" => {
            format!("expected one kind written as a mapping: {}", kinds(leaf))
        }
        "expected end of mapping after enum variant value" => format!(
            "{} takes exactly one kind, and a second one (`{leaf}`) is given here; keep one",
            if parent.is_empty() { "this" } else { parent }
        ),
        "expected mapping start" if field.is_empty() || field.starts_with('[') => {
            "a scene is a mapping of sections (plate, material, mesh, load, time, output), not a list or a single value".to_string()
        }
        "expected mapping start" if kinds(leaf) != OTHER_KINDS => {
            format!("expected one kind written as a mapping: {}", kinds(leaf))
        }
        "expected mapping start" => {
            "expected its keys (`key: value` lines indented under it, or `{key: value, ...}`), not a single value or a list".to_string()
        }
        "expected sequence start" => "expected a list (`[a, b, ...]`)".to_string(),
        "unexpected value for unit enum variant" => {
            let key = parent.rsplit('.').next().unwrap_or(parent);
            format!("`{leaf}` takes no settings: write `{key}: {leaf}`")
        }
        "invalid boolean" => "expected true or false".to_string(),
        m if m.starts_with("tabs disallowed") => {
            "a tab in the indentation: YAML indents with spaces only".to_string()
        }
        m if m.contains("did not find expected key") => {
            "the indentation does not line up here: a key is expected at this column (YAML indents with spaces only)".to_string()
        }
        m if m.starts_with("unexpected character") => {
            format!("{m}: a character YAML does not allow here (is this a text file?)")
        }
        "alias references unknown anchor" => {
            "`*name` refers to an anchor `&name` that is not defined above it".to_string()
        }
        other => other.to_string(),
    };
    if field.is_empty() {
        words
    } else {
        format!("{field}: {words}")
    }
}

/// The parser's error at 1-based `line`, `column` of `text` as the user's message, with the
/// place it belongs to: an unclosed quote where the string starts, a second document at its
/// `---`, a missing field at the mapping that lacks it; else [`explain`] at the parser's place.
pub fn describe(text: &str, message: &str, line: u64, column: u64) -> (u64, u64, String) {
    describe_document(
        text,
        message,
        (line, column),
        "scene",
        "every scene needs plate, material, mesh, load and time",
    )
}

/// [`describe`] for another YAML document (`document`, e.g. `case file`); `needs` lists the
/// top-level keys it must have.
pub fn describe_document(
    text: &str,
    message: &str,
    (line, column): (u64, u64),
    document: &str,
    needs: &str,
) -> (u64, u64, String) {
    if let Some((l, c)) = unclosed_quote(text) {
        let field = field_at(text, l, c);
        let words = format!(
            "the quoted string that starts at line {l} column {c} is not closed (its closing quote is missing on that line)"
        );
        return (l, c, with_field(&field, words));
    }
    if message.starts_with("multiple YAML documents") {
        let at = separator_line(text, line);
        return (
            at,
            1,
            format!("a {document} is one YAML document; found a second one (---) at line {at}"),
        );
    }
    if let Some(name) = missing_field(message) {
        return missing(text, name, (line, column), document, needs);
    }
    if message.starts_with("unexpected end of input") {
        return (
            line,
            column,
            format!("the {document} is empty (or ends inside a value): {needs}"),
        );
    }
    // A word where a mapping belongs (`load: impactor`): the parser asks for the mapping at
    // the next key, on the next line; the word is the value before it.
    let (line, column) = match message {
        "expected mapping start" => value_before(text, line, column).unwrap_or((line, column)),
        _ => (line, column),
    };
    let number_expected = matches!(message, "expected a number" | "invalid floating point");
    if let Some(token) = overflowing_number(text, line, column).filter(|_| number_expected) {
        return (
            line,
            column,
            with_field(
                &field_at(text, line, column),
                format!("{token} is beyond the largest number (1.8e308): must be a finite number"),
            ),
        );
    }
    (
        line,
        column,
        explain(message, &field_at(text, line, column)),
    )
}

/// When `line`, `column` is the start of a key, the plain value written on the nearest line
/// above it (`load: impactor` above `time:`): its line and column.
fn value_before(text: &str, line: u64, column: u64) -> Option<(u64, u64)> {
    let lines: Vec<&str> = text.lines().collect();
    let here = without_comment(lines.get((line as usize).checked_sub(1)?)?);
    let indent = here.len() - here.trim_start().len();
    if (column as usize).checked_sub(1)? != indent || split_key(here.trim_start()).is_none() {
        return None;
    }
    let (i, above) = lines[..line as usize - 1]
        .iter()
        .enumerate()
        .rev()
        .map(|(i, l)| (i, without_comment(l)))
        .find(|(_, l)| !l.trim().is_empty())?;
    let (_, after) = split_key(above.trim_start().trim_start_matches("- "))?;
    let value = after.trim();
    if value.is_empty() || value.starts_with(['{', '[', '|', '>', '&', '*', '!']) {
        return None;
    }
    let col = above.len() - after.trim_start().len();
    Some((i as u64 + 1, col as u64 + 1))
}

/// The number written at `line`, `column` when it overflows double precision (`1e999`),
/// which the parser reports as no number at all.
fn overflowing_number(text: &str, line: u64, column: u64) -> Option<String> {
    let raw = text.lines().nth((line as usize).checked_sub(1)?)?;
    let rest: String = raw
        .chars()
        .skip((column as usize).checked_sub(1)?)
        .collect();
    let end = rest
        .find(|c: char| c == ',' || c == '}' || c == ']' || c == '#' || c.is_whitespace())
        .unwrap_or(rest.len());
    let token = &rest[..end];
    let x: f64 = token.parse().ok()?;
    let digits = token.chars().next()?.is_ascii_digit() || token.starts_with(['-', '+', '.']);
    (x.is_infinite() && digits && !token.to_ascii_lowercase().contains("inf"))
        .then(|| token.to_string())
}

fn with_field(field: &str, words: String) -> String {
    if field.is_empty() {
        words
    } else {
        format!("{field}: {words}")
    }
}

/// `missing field `x`` -> `x`.
fn missing_field(message: &str) -> Option<&str> {
    message.strip_prefix("missing field `")?.strip_suffix('`')
}

/// The parser reports a missing field at the last key of the mapping that lacks it: name that
/// mapping, at its own key's line (a block mapping) or where the parser points (a flow one).
fn missing(
    text: &str,
    name: &str,
    (line, column): (u64, u64),
    document: &str,
    needs: &str,
) -> (u64, u64, String) {
    let (parent, at) = match block_key_at(text, line, column) {
        Some(indent) => {
            let mut path: Vec<String> = field_at(text, line, column)
                .split('.')
                .map(str::to_string)
                .collect();
            path.pop();
            (path.join("."), parent_key_line(text, line, indent))
        }
        None => (field_at(text, line, column), Some((line, column))),
    };
    if parent.is_empty() {
        return (
            1,
            1,
            format!("the {document} has no `{name}` section (missing field `{name}`); {needs}"),
        );
    }
    let (l, c) = at.unwrap_or((1, 1));
    (l, c, format!("{parent}: missing field `{name}`"))
}

/// The indent of the block key that starts at `line`, `column`, if one does.
fn block_key_at(text: &str, line: u64, column: u64) -> Option<usize> {
    let raw = text.lines().nth(line.checked_sub(1)? as usize)?;
    let content = without_comment(raw);
    let indent = content.len() - content.trim_start().len();
    split_key(content.trim_start())?;
    ((column.max(1) - 1) as usize <= indent).then_some(indent)
}

/// The line and column of the nearest key above `line` indented less than `indent`; `None`
/// at the top level.
fn parent_key_line(text: &str, line: u64, indent: usize) -> Option<(u64, u64)> {
    let lines: Vec<&str> = text.lines().collect();
    let upto = (line.saturating_sub(1) as usize).min(lines.len());
    lines[..upto].iter().enumerate().rev().find_map(|(i, raw)| {
        let content = without_comment(raw);
        let own = content.len() - content.trim_start().len();
        let is_key = split_key(content.trim_start()).is_some();
        (is_key && own < indent).then_some((i as u64 + 1, own as u64 + 1))
    })
}

/// The line of the document separator `---` at or before `line` (else `line`).
fn separator_line(text: &str, line: u64) -> u64 {
    text.lines()
        .enumerate()
        .take(line as usize)
        .skip(1)
        .filter(|(_, l)| l.starts_with("---"))
        .map(|(i, _)| i as u64 + 1)
        .last()
        .unwrap_or(line)
}

/// Where a quote that opens a value starts (1-based line, column) when it is not closed on
/// its line: a scene has no multi-line strings, so this is the cause of the parser's error.
pub fn unclosed_quote(text: &str) -> Option<(u64, u64)> {
    text.lines().enumerate().find_map(|(i, raw)| {
        let open = quoted_scalars(raw).find_map(|q| q.end.is_none().then_some(q.start))?;
        Some((i as u64 + 1, open as u64 + 1))
    })
}

/// A quoted scalar in a line: the byte of its opening quote, of its closing one if any.
struct Quoted {
    start: usize,
    end: Option<usize>,
}

/// The quoted scalars of a line that open a value or key (after `:`, `{`, `[`, `,`, `-` or at
/// the line's start); stops at a comment.
fn quoted_scalars(line: &str) -> impl Iterator<Item = Quoted> + '_ {
    let mut at = 0;
    std::iter::from_fn(move || {
        while at < line.len() {
            let c = line[at..].chars().next()?;
            let before = line[..at].trim_end();
            if c == '#' && (at == 0 || line[..at].ends_with(' ')) {
                return None;
            }
            let opens = matches!(c, '"' | '\'')
                && (before.is_empty() || before.ends_with([':', '{', '[', ',', '-']));
            if !opens {
                at += c.len_utf8();
                continue;
            }
            let start = at;
            let end = closing_quote(line, start, c);
            at = end.map_or(line.len(), |e| e + 1);
            return Some(Quoted { start, end });
        }
        None
    })
}

/// The byte of the quote that closes the one at `start` (`\"` escapes in double quotes, `''`
/// in single quotes).
fn closing_quote(line: &str, start: usize, quote: char) -> Option<usize> {
    let bytes = line.as_bytes();
    let mut i = start + 1;
    while i < bytes.len() {
        let b = bytes[i];
        if quote == '"' && b == b'\\' {
            i += 2;
            continue;
        }
        if b == quote as u8 {
            if quote == '\'' && bytes.get(i + 1) == Some(&b'\'') {
                i += 2;
                continue;
            }
            return Some(i);
        }
        i += 1;
    }
    None
}

const OTHER_KINDS: &str = "one key naming the kind, with its settings";

/// The scene's choices written as one word, by the field's last key.
fn words(leaf: &str) -> Option<&'static str> {
    Some(match leaf {
        "kinematics" => "`small` or `finite`",
        "geometry" => "`plane-strain` or `axisymmetric`",
        "model" => "`half` or `full`",
        "ends" => "`clamped`, `roller` or `slider`",
        "indentation_datum" | "force_node" => "`mid-plane` or `top-surface`",
        "estimate" => "`element` or `global`",
        "enforcement" => "`kinematic` or `penalty`",
        _ => return None,
    })
}

/// The one-kind mappings of the scene, in words, by the field's last key.
fn kinds(leaf: &str) -> &'static str {
    match leaf {
        "load" => "`impactor: {...}`, `pulse: {...}` or `traction: {...}`",
        "contact_law" => "`{paper: {length_unit: m}}` or `{johnson: {datum_depth: m}}`",
        "hardening" => "`{linear: Pa}` or `{table: [[eqps, Pa], ...]}`",
        "rate" => "`{cowper_symonds: {D: 1/s, q: -}}` or `{johnson_cook: {A: Pa, B: Pa, n, C, reference_rate: 1/s, m, thermal: {...}}}`",
        _ => OTHER_KINDS,
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

    /// A dict scene from Python arrives as indented JSON: its quoted keys name the field as a
    /// file's do (before, `<dict>:56:17: unknown variant ...` named none).
    #[test]
    fn fields_are_found_in_indented_json() {
        let json = "{\n  \"mesh\": {\n    \"nx\": \"abc\",\n    \"ny\": 16\n  },\n  \"kinematics\": \"large\"\n}";
        assert_eq!(field_at(json, 3, 11), "mesh.nx");
        assert_eq!(field_at(json, 6, 17), "kinematics");
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
