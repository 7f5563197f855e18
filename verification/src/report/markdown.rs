//! Markdown pages written by other tools (the reconstruction's report.md, the benchmarks'
//! stability.md) embedded in the V&V report: as Markdown in report.md (headings shifted under
//! the report's section, links to local files rewritten to copies next to report.md) and as
//! HTML in index.html (rendered with pulldown-cmark; local images inlined as data URIs so the
//! page stays self-contained).

use std::ops::Range;
use std::path::{Component, Path, PathBuf};

use pulldown_cmark::{CowStr, Event, HeadingLevel, Options, Parser, Tag, TagEnd};

/// How a page is embedded.
pub struct Embed<'a> {
    /// The folder the page's relative links are relative to (the page's own folder).
    pub base: &'a Path,
    /// The heading level the page's top-level headings get (its other headings follow).
    pub top_level: usize,
    /// Prefix of the heading ids in the HTML (keeps them apart from the report's own).
    pub anchor_prefix: &'a str,
    /// The report folder (where index.html and report.md are written).
    pub out: &'a Path,
    /// Subfolder of `out` the linked local files are copied to (empty: to the paths the
    /// page gives, under `out`).
    pub copy_to: &'a str,
    /// The title of the report's section holding the page: a page whose first block is a
    /// title heading with the same words (its only heading at that level) loses it, and its
    /// next level becomes `top_level`.
    pub section_title: Option<&'a str>,
}

/// A page ready for both outputs.
#[derive(Debug, Clone, Default)]
pub struct Embedded {
    pub html: String,
    pub md: String,
    /// Files copied under `out` (relative paths), for the log.
    pub copied: Vec<String>,
    /// Relative links whose file was not found next to the page.
    pub missing: Vec<String>,
}

fn options() -> Options {
    Options::ENABLE_TABLES
        | Options::ENABLE_FOOTNOTES
        | Options::ENABLE_STRIKETHROUGH
        | Options::ENABLE_TASKLISTS
}

/// A link or image destination that names a file next to the page: its path and its path
/// relative to `base` ('/'-separated), and the `#fragment` it carried. None for URLs, anchors,
/// absolute paths and paths that leave `base`.
fn local(base: &Path, url: &str) -> Option<(PathBuf, String, String)> {
    if url.is_empty() || url.starts_with('#') || url.starts_with('/') || url.contains(':') {
        return None;
    }
    let (path, frag) = match url.find(['#', '?']) {
        Some(i) => (&url[..i], &url[i..]),
        None => (url, ""),
    };
    let path = path.replace("%20", " ");
    let rel = Path::new(&path);
    if rel
        .components()
        .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
    {
        return None;
    }
    let rel: Vec<String> = rel
        .components()
        .filter_map(|c| match c {
            Component::Normal(s) => Some(s.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect();
    if rel.is_empty() {
        return None;
    }
    Some((base.join(rel.join("/")), rel.join("/"), frag.to_string()))
}

fn is_svg(p: &Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("svg"))
}

fn mime(p: &Path) -> Option<&'static str> {
    match p.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "svg" => Some("image/svg+xml"),
        "png" => Some("image/png"),
        "jpg" | "jpeg" => Some("image/jpeg"),
        "gif" => Some("image/gif"),
        _ => None,
    }
}

/// Standard base64 (RFC 4648, with padding).
pub fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(data.len().div_ceil(3) * 4);
    for c in data.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= c.len() {
                s.push(A[((n >> shift) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// HTML-escapes text for an attribute or element content.
pub fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            c => o.push(c),
        }
    }
    o
}

/// A file as an `<img>` with a data URI (nothing to fetch; its ids and styles stay its own).
pub fn img_data_uri(path: &Path, alt: &str, title: &str) -> Option<String> {
    let m = mime(path)?;
    let bytes = std::fs::read(path).ok()?;
    let title = if title.is_empty() {
        String::new()
    } else {
        format!(" title=\"{}\"", escape(title))
    };
    Some(format!(
        "<img class=\"figure\" alt=\"{}\"{title} src=\"data:{m};base64,{}\">",
        escape(alt),
        base64(&bytes)
    ))
}

/// A file's modification time, UTC, as 2025-01-31T12:00:00Z.
pub fn modified(path: &Path) -> Option<String> {
    let t = std::fs::metadata(path).ok()?.modified().ok()?;
    let secs = t.duration_since(std::time::UNIX_EPOCH).ok()?.as_secs() as i64;
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm), UTC.
    let (days, rem) = (secs.div_euclid(86400), secs.rem_euclid(86400));
    let z = days + 719468;
    let era = z.div_euclid(146097);
    let doe = z - era * 146097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    Some(format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    ))
}

/// GitHub-style heading slug: lower case, alphanumerics, '-' and '_' kept, spaces to '-'.
pub fn slug(text: &str) -> String {
    text.trim()
        .chars()
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                Some(c.to_lowercase().next().unwrap_or(c))
            } else if c == ' ' {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

fn level_num(l: HeadingLevel) -> usize {
    l as usize
}

fn shifted(l: HeadingLevel, shift: isize) -> HeadingLevel {
    let n = (level_num(l) as isize + shift).clamp(1, 6) as usize;
    HeadingLevel::try_from(n).unwrap_or(HeadingLevel::H6)
}

/// A heading of a page: its event index, level (1-6), words and source range.
type Heading = (usize, usize, String, Range<usize>);

/// The page's headings, in order.
fn page_headings(text: &str) -> Vec<Heading> {
    let mut v = Vec::new();
    let mut current: Option<Heading> = None;
    for (k, (e, r)) in Parser::new_ext(text, options())
        .into_offset_iter()
        .enumerate()
    {
        match e {
            Event::Start(Tag::Heading { level, .. }) => {
                current = Some((k, level_num(level), String::new(), r))
            }
            Event::Text(t) | Event::Code(t) => {
                if let Some(c) = current.as_mut() {
                    c.2.push_str(&t);
                }
            }
            Event::End(TagEnd::Heading(_)) => v.extend(current.take()),
            _ => {}
        }
    }
    v
}

/// `rel` under the folder `copy_to` (itself when `copy_to` is empty: the page's own paths
/// are already the report's, as `what-changed/X.svg` is beside `what-changed.md`).
fn under(copy_to: &str, rel: &str) -> String {
    if copy_to.is_empty() {
        rel.to_string()
    } else {
        format!("{copy_to}/{rel}")
    }
}

/// A local file the page links to (`path`, `rel` to the page), copied next to the report
/// once: its path there, or None (noted as missing) when it does not exist.
fn copy_local(how: &Embed, path: &Path, rel: &str, out: &mut Embedded) -> Option<String> {
    if !path.is_file() {
        if !out.missing.iter().any(|m| m == rel) {
            out.missing.push(rel.to_string());
        }
        return None;
    }
    let target_rel = under(how.copy_to, rel);
    if !out.copied.contains(&target_rel) {
        let target = how.out.join(&target_rel);
        let same = match (path.canonicalize(), target.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        };
        if !same {
            if let Some(parent) = target.parent() {
                let _ = std::fs::create_dir_all(parent);
            }
            if std::fs::copy(path, &target).is_err() {
                return None;
            }
        }
        out.copied.push(target_rel.clone());
    }
    Some(target_rel)
}

/// Embeds a Markdown page: see the module documentation.
pub fn embed(text: &str, how: &Embed) -> Embedded {
    let mut out = Embedded::default();
    // Heading shift: the page's smallest level becomes `top_level`.
    // A title that repeats the section's: its events (HTML) and source range (Markdown).
    let headings = page_headings(text);
    let top = headings.iter().map(|h| h.1).min();
    let title = headings.first().filter(|h| {
        h.0 == 0
            && Some(h.1) == top
            && headings.iter().filter(|o| o.1 == h.1).count() == 1
            && how.section_title.is_some_and(|t| slug(t) == slug(&h.2))
    });
    let title_range = title.map(|h| h.3.clone());
    let min_level = headings
        .iter()
        .filter(|h| title.is_none_or(|t| t.0 != h.0))
        .map(|h| h.1)
        .min()
        .unwrap_or(how.top_level);
    let shift = how.top_level as isize - min_level as isize;
    let md = markdown_with_edits(text, how, title_range.as_ref(), shift, &mut out);
    out.md = md;
    let html = html_with_figures(text, how, title.is_some(), shift, &mut out.missing);
    out.html = html;
    out
}

/// The Markdown source with edits: heading levels shifted, the repeated title removed, local
/// link and image destinations pointing at the copies.
fn markdown_with_edits(
    text: &str,
    how: &Embed,
    title_range: Option<&Range<usize>>,
    shift: isize,
    out: &mut Embedded,
) -> String {
    let mut edits: Vec<(Range<usize>, String)> = Vec::new();
    let parser = Parser::new_ext(text, options());
    for (_, def) in parser.reference_definitions().iter() {
        if let Some((path, rel, frag)) = local(how.base, &def.dest) {
            if let Some(new) = copy_local(how, &path, &rel, out) {
                let span = &text[def.span.clone()];
                if let Some(colon) = span.find("]:") {
                    if let Some(i) = span[colon..].find(def.dest.as_ref()) {
                        let s = def.span.start + colon + i;
                        edits.push((s..s + def.dest.len(), format!("{new}{frag}")));
                    }
                }
            }
        }
    }
    if let Some(r) = title_range {
        edits.push((r.clone(), String::new()));
    }
    for (event, range) in parser.into_offset_iter() {
        if title_range.is_some_and(|t| range.start >= t.start && range.end <= t.end) {
            continue;
        }
        match event {
            Event::Start(Tag::Heading { level, .. }) if shift != 0 => {
                let at_line_start = range.start == 0 || text.as_bytes()[range.start - 1] == b'\n';
                let src = &text[range.clone()];
                let new = level_num(shifted(level, shift));
                if !at_line_start {
                    continue;
                }
                if src.starts_with('#') {
                    let hashes = src.bytes().take_while(|b| *b == b'#').count();
                    edits.push((range.start..range.start + hashes, "#".repeat(new)));
                } else {
                    // Setext (underlined): becomes an ATX heading; the underline goes.
                    let body = src.trim_end_matches(['\n', '\r']);
                    if let Some(nl) = body.rfind('\n') {
                        edits.push((range.start..range.start, format!("{} ", "#".repeat(new))));
                        edits.push((range.start + nl..range.start + body.len(), String::new()));
                    }
                }
            }
            Event::Start(Tag::Image { dest_url, .. })
            | Event::Start(Tag::Link { dest_url, .. }) => {
                let Some((path, rel, frag)) = local(how.base, &dest_url) else {
                    continue;
                };
                let Some(new) = copy_local(how, &path, &rel, out) else {
                    continue;
                };
                let src = &text[range.clone()];
                for open in ["](<", "]("] {
                    if let Some(i) = src.rfind(&format!("{open}{}", dest_url.as_ref())) {
                        let s = range.start + i + open.len();
                        edits.push((s..s + dest_url.len(), format!("{new}{frag}")));
                        break;
                    }
                }
            }
            _ => {}
        }
    }
    splice(text, edits)
}

/// `text` with each `(range, replacement)` applied, in source order.
fn splice(text: &str, mut edits: Vec<(Range<usize>, String)>) -> String {
    edits.sort_by_key(|e| (e.0.start, e.0.end));
    let mut md = String::with_capacity(text.len() + 64);
    let mut at = 0;
    for (r, new) in &edits {
        if r.start < at {
            continue; // overlapping edit (cannot happen for well-formed input): keep the first
        }
        md.push_str(&text[at..r.start]);
        md.push_str(new);
        at = r.end;
    }
    md.push_str(&text[at..]);
    md
}

/// The page as HTML: the events, headings shifted with ids, local images inlined (each with
/// an id). A link to a local SVG points at the page's inline figure of it; a linked SVG the
/// page does not show is inlined after the top-level block holding the link. `skip_title`:
/// the first heading repeats the section's and is left out.
fn html_with_figures(
    text: &str,
    how: &Embed,
    skip_title: bool,
    shift: isize,
    missing: &mut Vec<String>,
) -> String {
    let events: Vec<Event> = Parser::new_ext(text, options()).collect();
    let shown: Vec<String> = events
        .iter()
        .filter_map(|e| match e {
            Event::Start(Tag::Image { dest_url, .. }) => local(how.base, dest_url)
                .filter(|l| l.0.is_file() && mime(&l.0).is_some())
                .map(|l| l.1),
            _ => None,
        })
        .collect();
    let mut depth_after = Vec::with_capacity(events.len());
    let mut depth = 0usize;
    for e in &events {
        match e {
            Event::Start(_) => depth += 1,
            Event::End(_) => depth = depth.saturating_sub(1),
            _ => {}
        }
        depth_after.push(depth);
    }
    let mut page = HtmlPage {
        how,
        shift,
        events: &events,
        html: Vec::with_capacity(events.len()),
        used_ids: Vec::new(),
        with_id: Vec::new(),
        pending: Vec::new(),
        shown,
        missing,
    };
    let mut i = 0;
    if skip_title {
        i = events
            .iter()
            .position(|e| matches!(e, Event::End(TagEnd::Heading(_))))
            .map_or(0, |j| j + 1);
    }
    while i < events.len() {
        // The last event this step consumed.
        let last = match &events[i] {
            Event::Start(Tag::Heading { .. }) => page.heading(i),
            Event::End(TagEnd::Heading(level)) => {
                page.html
                    .push(Event::End(TagEnd::Heading(shifted(*level, shift))));
                i
            }
            Event::Start(Tag::Image { .. }) => page.image(i),
            Event::Start(Tag::Link { .. }) => page.link(i),
            e => {
                page.html.push(e.clone());
                i
            }
        };
        if !page.pending.is_empty()
            && matches!(events[last], Event::End(_))
            && depth_after[last] == 0
        {
            page.flush_pending();
        }
        i = last + 1;
    }
    if !page.pending.is_empty() {
        page.flush_pending();
    }
    let mut html = String::new();
    pulldown_cmark::html::push_html(&mut html, page.html.into_iter());
    html
}

/// The state of the HTML pass over a page's events.
struct HtmlPage<'e, 'h> {
    how: &'h Embed<'h>,
    shift: isize,
    events: &'e [Event<'e>],
    html: Vec<Event<'e>>,
    used_ids: Vec<String>,
    /// Figures (paths relative to the page) whose inline image carries the figure id.
    with_id: Vec<String>,
    /// Linked SVGs to inline after the current top-level block.
    pending: Vec<String>,
    /// Figures the page shows inline.
    shown: Vec<String>,
    missing: &'h mut Vec<String>,
}

impl<'e> HtmlPage<'e, '_> {
    fn figure_id(&self, rel: &str) -> String {
        format!(
            "{}fig-{}",
            self.how.anchor_prefix,
            slug(&rel.replace(['/', '.'], "-"))
        )
    }

    /// `img` with the figure id of `rel`.
    fn with_figure_id(&self, img: &str, rel: &str) -> String {
        img.replacen("<img ", &format!("<img id=\"{}\" ", self.figure_id(rel)), 1)
    }

    fn flush_pending(&mut self) {
        self.html.push(Event::Html(CowStr::from(format!(
            "<p>{}</p>\n",
            self.pending.join(" ")
        ))));
        self.pending.clear();
    }

    /// The heading opened at event `i`, shifted, with a unique id (prefixed).
    fn heading(&mut self, i: usize) -> usize {
        let events = self.events;
        let Event::Start(Tag::Heading {
            level,
            id,
            classes,
            attrs,
        }) = &events[i]
        else {
            return i;
        };
        let mut j = i + 1;
        let mut words = String::new();
        while j < events.len() && !matches!(events[j], Event::End(TagEnd::Heading(_))) {
            if let Event::Text(t) | Event::Code(t) = &events[j] {
                words.push_str(t);
            }
            j += 1;
        }
        let mut anchor = format!(
            "{}{}",
            self.how.anchor_prefix,
            id.as_deref()
                .map(str::to_string)
                .unwrap_or_else(|| slug(&words))
        );
        let base_anchor = anchor.clone();
        let mut k = 1;
        while self.used_ids.contains(&anchor) {
            anchor = format!("{base_anchor}-{k}");
            k += 1;
        }
        self.used_ids.push(anchor.clone());
        self.html.push(Event::Start(Tag::Heading {
            level: shifted(*level, self.shift),
            id: Some(CowStr::from(anchor)),
            classes: classes.clone(),
            attrs: attrs.clone(),
        }));
        i
    }

    /// The image opened at event `i`: a local one inlined (up to its end, which it consumes),
    /// a remote one kept.
    fn image(&mut self, i: usize) -> usize {
        let events = self.events;
        let Event::Start(Tag::Image {
            dest_url, title, ..
        }) = &events[i]
        else {
            return i;
        };
        // The alt text, up to the matching end.
        let mut j = i + 1;
        let mut nested = 0;
        let mut alt = String::new();
        while j < events.len() {
            match &events[j] {
                Event::Start(Tag::Image { .. }) => nested += 1,
                Event::End(TagEnd::Image) if nested == 0 => break,
                Event::End(TagEnd::Image) => nested -= 1,
                Event::Text(t) | Event::Code(t) => alt.push_str(t),
                _ => {}
            }
            j += 1;
        }
        let Some((path, rel, _)) = local(self.how.base, dest_url) else {
            self.html.push(events[i].clone());
            return i;
        };
        let img = match img_data_uri(&path, &alt, title) {
            Some(img) if !self.with_id.contains(&rel) => {
                self.with_id.push(rel.clone());
                self.with_figure_id(&img, &rel)
            }
            Some(img) => img,
            None => {
                if !self.missing.contains(&rel) {
                    self.missing.push(rel.clone());
                }
                format!(
                    "<span class=\"missing\">[figure {} not found next to the page]</span>",
                    escape(&rel)
                )
            }
        };
        self.html.push(Event::InlineHtml(CowStr::from(img)));
        j.min(events.len() - 1)
    }

    /// The link opened at event `i`: anchors prefixed, local files pointing at their copies,
    /// a local SVG at its inline figure (inlined after the block when the page does not show it).
    fn link(&mut self, i: usize) -> usize {
        let events = self.events;
        let Event::Start(Tag::Link {
            link_type,
            dest_url,
            title,
            id,
        }) = &events[i]
        else {
            return i;
        };
        let link = |dest: String| {
            Event::Start(Tag::Link {
                link_type: *link_type,
                dest_url: CowStr::from(dest),
                title: title.clone(),
                id: id.clone(),
            })
        };
        if let Some(anchor) = dest_url.strip_prefix('#') {
            self.html
                .push(link(format!("#{}{anchor}", self.how.anchor_prefix)));
        } else if let Some((path, rel, frag)) = local(self.how.base, dest_url) {
            if is_svg(&path) && self.shown.contains(&rel) {
                self.html.push(link(format!("#{}", self.figure_id(&rel))));
            } else if let Some(img) = is_svg(&path)
                .then(|| img_data_uri(&path, &rel, title))
                .flatten()
            {
                self.html.push(link(format!("#{}", self.figure_id(&rel))));
                let tagged = self.with_figure_id(&img, &rel);
                self.pending.push(tagged);
                self.shown.push(rel.clone());
                self.with_id.push(rel);
            } else {
                self.html
                    .push(link(format!("{}{frag}", under(self.how.copy_to, &rel))));
            }
        } else {
            self.html.push(events[i].clone());
        }
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_examples() {
        for (a, b) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(a.as_bytes()), b);
        }
    }

    #[test]
    fn a_title_repeating_the_section_goes() {
        let dir = std::env::temp_dir();
        let how = |t| Embed {
            base: &dir,
            top_level: 3,
            anchor_prefix: "",
            out: &dir,
            copy_to: "x",
            section_title: t,
        };
        let text = "# Reproducing Dokko & Kim (2004)\n\nIntro.\n\n## Summary\n\nText.\n";
        let e = embed(text, &how(Some("Reproducing Dokko & Kim (2004)")));
        assert_eq!(e.md, "\nIntro.\n\n### Summary\n\nText.\n");
        assert!(
            e.html.starts_with("<p>Intro.</p>")
                && e.html.contains("<h3 id=\"summary\">Summary</h3>"),
            "{}",
            e.html
        );
        // Another title, or none asked for: kept.
        for t in [Some("Something else"), None] {
            let e = embed(text, &how(t));
            assert!(
                e.md.starts_with("### Reproducing Dokko & Kim (2004)\n")
                    && e.md.contains("#### Summary"),
                "{}",
                e.md
            );
        }
    }

    #[test]
    fn local_links_only() {
        let b = Path::new("/x");
        assert!(local(b, "https://a.b/c.svg").is_none());
        assert!(local(b, "#sec").is_none());
        assert!(local(b, "/etc/passwd").is_none());
        assert!(local(b, "../secret.svg").is_none());
        assert_eq!(
            local(b, "./plots/a.svg#v").map(|l| (l.1, l.2)),
            Some(("plots/a.svg".into(), "#v".into()))
        );
    }

    #[test]
    fn headings_shift_links_rewrite_images_inline() {
        let dir = std::env::temp_dir().join(format!("impact-md-unit-{}", std::process::id()));
        let out = dir.join("out");
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(dir.join("fig.svg"), "<?xml version=\"1.0\"?><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"></svg>").unwrap();
        std::fs::write(
            dir.join("other.svg"),
            "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>",
        )
        .unwrap();
        let text = "# Title\n\nSee [fig](fig.svg) and [the part](#part-two).\n\nPart two\n--------\n\n![a figure](fig.svg)\n\n```\n# not a heading\n```\n\n![gone](gone.svg)\n\n- a list, [only linked](other.svg)\n- more\n\nAfter.\n\n[ref]: fig.svg\n";
        let e = embed(
            text,
            &Embed {
                base: &dir,
                top_level: 3,
                anchor_prefix: "p-",
                out: &out,
                copy_to: "page",
                section_title: None,
            },
        );
        assert!(e.md.starts_with("### Title\n"), "{}", e.md);
        assert!(e.md.contains("#### Part two\n\n"), "{}", e.md);
        assert!(
            e.md.contains("[fig](page/fig.svg)")
                && e.md.contains("![a figure](page/fig.svg)")
                && e.md.contains("[ref]: page/fig.svg"),
            "{}",
            e.md
        );
        assert!(e.md.contains("# not a heading"), "code blocks untouched");
        assert!(e.md.contains("![gone](gone.svg)"));
        assert!(out.join("page/fig.svg").is_file());
        assert_eq!(e.missing, vec!["gone.svg".to_string()]);
        assert!(
            e.html.contains("<h3 id=\"p-title\">Title</h3>")
                && e.html.contains("<h4 id=\"p-part-two\">"),
            "{}",
            e.html
        );
        assert!(e.html.contains("href=\"#p-part-two\""));
        assert_eq!(
            e.html.matches("src=\"data:image/svg+xml;base64,").count(),
            2,
            "each SVG inlined once: {}",
            e.html
        );
        assert!(
            e.html.contains("<a href=\"#p-fig-fig-svg\">fig</a>")
                && e.html.contains("<img id=\"p-fig-fig-svg\""),
            "a link to a shown figure jumps to it"
        );
        // A linked SVG the page does not show: inlined after the list that holds the link.
        let (list_end, fig, after) = (
            e.html.find("</ul>").unwrap(),
            e.html.find("id=\"p-fig-other-svg\"").unwrap(),
            e.html.find("After.").unwrap(),
        );
        assert!(list_end < fig && fig < after, "{}", e.html);
        assert!(e.md.contains("[only linked](page/other.svg)"));
        assert!(e.html.contains("figure gone.svg not found"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
