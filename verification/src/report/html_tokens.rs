//! Table cells of the HTML report break lines at spaces only: every word of a cell's text
//! that holds a character a browser may break after (a hyphen, a slash, a sign, brackets,
//! any non-ASCII letter) is wrapped in `<span class="tok">`, which the stylesheet keeps on
//! one line (`white-space: nowrap`). With `overflow-wrap: normal` on the cells, a long word
//! widens its column instead of being split ("stat us", "toler ance", "rel 1.0e- 8" were
//! the splits of `overflow-wrap: anywhere` and of the emergency breaks of `break-word`).
//! A table that is then wider than the page scrolls sideways in its own box
//! (`<div class="scroll">`, `overflow-x: auto`) rather than widening the page. The report's
//! browser check asserts both on the rendered page.

/// Elements whose content is copied untouched (no text of a cell to protect).
const VERBATIM: [&str; 3] = ["svg", "style", "script"];

/// `html` with the break-prone words of its table cells wrapped in `<span class="tok">` and
/// each table in a `<div class="scroll">`.
pub fn keep_tokens_whole(html: &str) -> String {
    let mut out = String::with_capacity(html.len() + html.len() / 8);
    let mut depth = 0usize; // open <td>/<th>
    let mut rest = html;
    while !rest.is_empty() {
        let Some(lt) = rest.find('<') else {
            push_text(&mut out, rest, depth > 0);
            break;
        };
        push_text(&mut out, &rest[..lt], depth > 0);
        rest = &rest[lt..];
        let Some(gt) = rest.find('>') else {
            out.push_str(rest);
            break;
        };
        let tag = &rest[..=gt];
        let name: String = tag[1..]
            .trim_start_matches('/')
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect::<String>()
            .to_ascii_lowercase();
        let closing = tag.starts_with("</");
        if !closing && VERBATIM.contains(&name.as_str()) && !tag.ends_with("/>") {
            let end = format!("</{name}>");
            let stop = rest.find(&end).map_or(rest.len(), |i| i + end.len());
            out.push_str(&rest[..stop]);
            rest = &rest[stop..];
            continue;
        }
        if name == "td" || name == "th" {
            depth = if closing {
                depth.saturating_sub(1)
            } else {
                depth + 1
            };
        }
        match (name.as_str(), closing) {
            ("table", false) => out.push_str("<div class=\"scroll\">"),
            ("table", true) => {
                out.push_str(tag);
                out.push_str("</div>");
                rest = &rest[gt + 1..];
                continue;
            }
            _ => {}
        }
        out.push_str(tag);
        rest = &rest[gt + 1..];
    }
    out
}

/// A word a browser may break inside: it holds a hyphen or dash, a solidus, or a closing
/// bracket, `!` or `?` before more of the word (Unicode line breaking, UAX #14: classes HY, BA,
/// SY, CL, CP, EX allow a break after them). What closes a word (`.`, `,`, `)` ...) breaks
/// nothing; nor does a lone entity (`&amp;`).
fn breakable(word: &str) -> bool {
    if word.starts_with('&') && word.ends_with(';') && word.matches('&').count() == 1 {
        return false;
    }
    let core: Vec<char> = word
        .trim_end_matches(['.', ',', ';', ':', ')', ']', '}', '!', '?'])
        .chars()
        .collect();
    // A hyphen inside a word even before a digit: Chromium breaks `1.0e-12` after its minus
    // sign (found by the browser check), whatever UAX #14's LB25 suggests; a leading minus
    // before a digit (`-2.5`) does not break, before a letter (`-Z`) it does.
    core.windows(2).enumerate().any(|(i, w)| match w[0] {
        '-' => i > 0 || !w[1].is_ascii_digit(),
        c => "\u{2010}\u{2011}\u{2012}\u{2013}\u{2014}/)]}!?".contains(c),
    })
}

fn push_text(out: &mut String, text: &str, in_cell: bool) {
    if !in_cell {
        out.push_str(text);
        return;
    }
    let mut word = String::new();
    let flush = |out: &mut String, word: &mut String| {
        if breakable(word) {
            out.push_str("<span class=\"tok\">");
            out.push_str(word);
            out.push_str("</span>");
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in text.chars() {
        if c.is_whitespace() {
            flush(out, &mut word);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(out, &mut word);
}

#[cfg(test)]
mod tests {
    //! The cells' words, wrapped or not: a tolerance `rel 1.0e-8`, a check id with hyphens,
    //! a path; prose words and text outside tables untouched; SVG copied as it is.
    use super::*;

    #[test]
    fn break_prone_words_in_cells_are_kept_whole() {
        let html = "<p>a-b outside</p><table><tr><th>status</th><td class=\"num\">rel 1.0e-8</td>\
                    <td><b>mesh-change-impulse</b><br>see reference-data/paper/table1.csv, and more</td></tr></table>";
        let out = keep_tokens_whole(html);
        assert!(out.starts_with("<p>a-b outside</p>"), "{out}");
        assert!(out.contains("<div class=\"scroll\"><table><tr><th>status</th>"));
        assert!(out.ends_with("</table></div>"));
        assert!(
            out.contains(">rel <span class=\"tok\">1.0e-8</span></td>"),
            "{out}"
        );
        assert!(
            out.contains("<b><span class=\"tok\">mesh-change-impulse</span></b>"),
            "{out}"
        );
        assert!(
            out.contains("<span class=\"tok\">reference-data/paper/table1.csv,</span> and more")
        );
    }

    #[test]
    fn svg_and_entities_are_left_as_they_are() {
        let cell = "<tr><td><svg><text>a-b</text></svg> x &amp; y</td></tr>";
        assert_eq!(
            keep_tokens_whole(&format!("<table>{cell}</table>")),
            format!("<div class=\"scroll\"><table>{cell}</table></div>")
        );
        assert!(!breakable("done."));
        assert!(breakable("1.0e-8") && !breakable("-2.5") && breakable("-Z"));
        assert!(!breakable("(mm)") && !breakable("s)"));
        assert!(breakable("f(x)y") && breakable("a/b"));
    }
}
