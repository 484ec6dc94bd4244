//! The book's links hold. Every relative link and image in `book/src/**/*.md` and in README.md
//! names a file that exists, and a `#heading` that the file has (mdBook's anchor rule: the
//! heading's text in lower case, spaces to `-`, other punctuation dropped, `-1`, `-2`, ... for
//! repeats). Every `{{#include}}` names a file that exists. Every page in `book/src` is listed in
//! SUMMARY.md, and every SUMMARY entry has its file.
//!
//! A page is checked as mdBook builds it: with its includes expanded, and the included text's
//! links read from the including page's directory. The included files are also checked where
//! they live, as the repository shows them. A link from a book page to a `.md` file outside the
//! book is refused: mdBook turns it into `.html`, which the built book does not have. A page
//! that is gone may be kept as a redirect of `book/book.toml` (`[output.html.redirect]`).

use crate::common;

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Component, Path, PathBuf};

/// A lexically normalised path: `.` dropped, `..` taken back (never above the start).
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

/// mdBook's id of a heading (`normalize_id` of the heading's text, tags and code marks dropped).
pub fn heading_id(heading: &str) -> String {
    let mut text = String::new();
    let mut in_tag = false;
    for c in heading.chars() {
        match c {
            '<' => in_tag = true,
            '>' if in_tag => in_tag = false,
            _ if !in_tag => text.push(c),
            _ => {}
        }
    }
    // A link in a heading keeps its text only.
    let text = strip_link_targets(&text);
    common::anchor_of(&text)
}

/// `[text](target)` becomes `text`.
fn strip_link_targets(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        let Some(close) = rest[at..].find(')') else {
            break;
        };
        out.push_str(&rest[..at]);
        rest = &rest[at + close + 1..];
    }
    out.push_str(rest);
    out.replace('[', "")
}

/// The lines of `text` outside fenced code blocks, with their line numbers (1-based).
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fence: Option<String> = None;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let marker: String = trimmed
            .chars()
            .take_while(|&c| c == '`' || c == '~')
            .collect();
        if marker.len() >= 3 {
            match &fence {
                None => {
                    fence = Some(marker);
                    continue;
                }
                Some(open) if marker.starts_with(open.as_str()) => {
                    fence = None;
                    continue;
                }
                Some(_) => {}
            }
        }
        if fence.is_none() {
            out.push((i + 1, line));
        }
    }
    out
}

/// The anchors of a page: its headings' ids (repeats numbered as mdBook numbers them) and any
/// explicit `id="..."`.
pub fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut out = BTreeSet::new();
    for (_, line) in prose_lines(text) {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if (1..=6).contains(&hashes) && line[hashes..].starts_with(' ') {
            let id = heading_id(line[hashes..].trim().trim_end_matches('#'));
            let count = seen.entry(id.clone()).or_insert(0);
            out.insert(if *count == 0 {
                id.clone()
            } else {
                format!("{id}-{count}")
            });
            *count += 1;
        }
        let mut rest = line;
        while let Some(at) = rest.find("id=\"") {
            rest = &rest[at + 4..];
            if let Some(end) = rest.find('"') {
                out.insert(rest[..end].to_string());
                rest = &rest[end..];
            }
        }
    }
    out
}

/// `line` without its inline code spans.
fn without_code_spans(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find('`') {
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let fence = "`".repeat(ticks);
        out.push_str(&rest[..start]);
        let after = &rest[start + ticks..];
        match after.find(&fence) {
            Some(end) => rest = &after[end + ticks..],
            None => {
                rest = after;
                break;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The link targets of a page: (line, target), from `[..](target)`, `![..](target)`,
/// `[label]: target` and HTML `src`/`href`, outside code.
pub fn links(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (number, line) in prose_lines(text) {
        let line = without_code_spans(line);
        let trimmed = line.trim_start();
        if trimmed.starts_with('[') {
            if let Some(end) = trimmed.find("]:") {
                if let Some(target) = trimmed[end + 2..].split_whitespace().next() {
                    out.push((number, target.trim_matches(['<', '>']).to_string()));
                }
                continue;
            }
        }
        let mut rest = line.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            // The target ends at the parenthesis that closes the link.
            let mut depth = 0;
            let mut end = after.len();
            for (k, c) in after.char_indices() {
                match c {
                    '(' => depth += 1,
                    ')' if depth == 0 => {
                        end = k;
                        break;
                    }
                    ')' => depth -= 1,
                    _ => {}
                }
            }
            let target = after[..end].split_whitespace().next().unwrap_or("");
            out.push((number, target.trim_matches(['<', '>']).to_string()));
            rest = &after[end.min(after.len())..];
        }
        for attribute in ["src=\"", "href=\""] {
            let mut rest = line.as_str();
            while let Some(at) = rest.find(attribute) {
                rest = &rest[at + attribute.len()..];
                if let Some(end) = rest.find('"') {
                    out.push((number, rest[..end].to_string()));
                    rest = &rest[end..];
                }
            }
        }
    }
    out
}

/// Whether a link leaves the repository (a URL with a scheme, an e-mail address).
fn is_external(target: &str) -> bool {
    target.contains("://") || target.starts_with("mailto:") || target.starts_with("data:")
}

/// The checker of one repository: its root, and what it has read.
pub struct Checker {
    root: PathBuf,
    /// Redirects of book.toml: the built page (relative to the book, `book/src/model.html`) to
    /// its target, as written.
    redirects: BTreeMap<String, String>,
    /// Problems found, one line each.
    pub problems: Vec<String>,
}

impl Checker {
    /// A checker of the repository at `root` (holding `book/`).
    pub fn new(root: &Path) -> Checker {
        let mut redirects = BTreeMap::new();
        if let Ok(text) = std::fs::read_to_string(root.join("book/book.toml")) {
            if let Ok(table) = text.parse::<toml::Table>() {
                if let Some(map) = table
                    .get("output")
                    .and_then(|o| o.get("html"))
                    .and_then(|h| h.get("redirect"))
                    .and_then(|r| r.as_table())
                {
                    for (from, to) in map {
                        if let Some(to) = to.as_str() {
                            redirects.insert(from.trim_start_matches('/').to_string(), to.into());
                        }
                    }
                }
            }
        }
        Checker {
            root: root.to_path_buf(),
            redirects,
            problems: Vec::new(),
        }
    }

    fn book_src(&self) -> PathBuf {
        self.root.join("book/src")
    }

    fn shown(&self, path: &Path) -> String {
        path.strip_prefix(&self.root)
            .unwrap_or(path)
            .display()
            .to_string()
    }

    /// The text of `page` with its includes expanded (recursively, as mdBook does), and the files
    /// it included. A missing include is a problem.
    pub fn expanded(&mut self, page: &Path, depth: usize) -> (String, Vec<PathBuf>) {
        let (lines, included) = self.expanded_lines(page, depth);
        let text: Vec<String> = lines.into_iter().map(|(line, _)| line).collect();
        (text.join("\n") + "\n", included)
    }

    /// [`Checker::expanded`] line by line, each line with where it comes from: `line N` of the
    /// page, or `line N of FILE` for an included line.
    fn expanded_lines(
        &mut self,
        page: &Path,
        depth: usize,
    ) -> (Vec<(String, String)>, Vec<PathBuf>) {
        let Ok(text) = std::fs::read_to_string(page) else {
            return (Vec::new(), Vec::new());
        };
        let mut out: Vec<(String, String)> = Vec::new();
        let mut included = Vec::new();
        for (number, line) in text.lines().enumerate() {
            let origin = format!("line {}", number + 1);
            let mut current = String::new();
            let mut rest = line;
            while let Some(at) = rest.find("{{#include ") {
                let escaped = at > 0 && rest.as_bytes()[at - 1] == b'\\';
                let Some(close) = rest[at..].find("}}") else {
                    break;
                };
                current.push_str(&rest[..at]);
                let spec = rest[at + "{{#include ".len()..at + close]
                    .trim()
                    .to_string();
                rest = &rest[at + close + 2..];
                if escaped {
                    current.push_str(&format!("{{{{#include {spec}}}}}"));
                    continue;
                }
                let mut parts = spec.splitn(2, ':');
                let file = parts.next().unwrap_or("");
                let range = parts.next();
                let target = normalise(&page.parent().unwrap_or(Path::new(".")).join(file));
                if !target.is_file() {
                    let problem = format!(
                        "{}, {origin}: {{{{#include {spec}}}}}: no file {}",
                        self.shown(page),
                        self.shown(&target)
                    );
                    self.problems.push(problem);
                    continue;
                }
                included.push(target.clone());
                let (inner, more) = if depth < 10 {
                    self.expanded_lines(&target, depth + 1)
                } else {
                    (Vec::new(), Vec::new())
                };
                included.extend(more);
                let shown = self.shown(&target);
                let mut inner: Vec<(String, String)> = select_lines(inner, range)
                    .into_iter()
                    .map(|(l, o)| (l, format!("{o} of {shown}")))
                    .collect();
                // The included text continues the current line and ends a line of its own.
                if let Some(first) = inner.first_mut() {
                    first.0 = format!("{current}{}", first.0);
                    current.clear();
                }
                out.extend(inner);
            }
            current.push_str(rest);
            out.push((current, origin));
        }
        (out, included)
    }

    /// Checks the links of the page `page`, its includes expanded (its directory resolves
    /// them). `in_book`: the page is a page of the built book.
    fn check_links(&mut self, page: &Path, in_book: bool, context: &str) {
        let dir = page.parent().unwrap_or(Path::new(".")).to_path_buf();
        let (lines, _) = self.expanded_lines(page, 0);
        let text: String = lines.iter().map(|(l, _)| format!("{l}\n")).collect();
        for (line, target) in links(&text) {
            if target.is_empty() || is_external(&target) {
                continue;
            }
            let origin = lines
                .get(line - 1)
                .map(|(_, o)| o.clone())
                .unwrap_or_default();
            let (path_part, anchor) = match target.split_once('#') {
                Some((p, a)) => (p.to_string(), Some(a.to_string())),
                None => (target.clone(), None),
            };
            let where_ = format!("{}{context}, {origin}: link {target}", self.shown(page));
            let file = if path_part.is_empty() {
                page.to_path_buf()
            } else {
                let resolved = normalise(&dir.join(&path_part));
                match self.resolve(&resolved, in_book) {
                    Ok(file) => file,
                    Err(why) => {
                        self.problems.push(format!("{where_}: {why}"));
                        continue;
                    }
                }
            };
            if let Some(anchor) = anchor {
                if file.is_dir() || file.extension().is_none_or(|e| e != "md") {
                    continue;
                }
                let text = self.expanded(&file, 0).0;
                if !anchors(&text).contains(&anchor) {
                    let problem = format!(
                        "{where_}: {} has no heading with the anchor #{anchor}",
                        self.shown(&file)
                    );
                    self.problems.push(problem);
                }
            }
        }
    }

    /// The file a link's path names, or why it names none.
    fn resolve(&self, resolved: &Path, in_book: bool) -> Result<PathBuf, String> {
        let src = normalise(&self.book_src());
        if in_book {
            if let Ok(inside) = resolved.strip_prefix(&src) {
                if resolved.exists() {
                    return Ok(resolved.to_path_buf());
                }
                // A page kept as a redirect of book.toml.
                let html = inside
                    .with_extension("html")
                    .to_string_lossy()
                    .replace('\\', "/");
                if let Some(to) = self.redirects.get(&html) {
                    let target = normalise(&resolved.parent().unwrap_or(&src).join(to));
                    let page = target.with_extension("md");
                    return if page.is_file() {
                        Ok(page)
                    } else {
                        Err(format!(
                            "redirected (book.toml) to {to}, whose page {} does not exist",
                            self.shown(&page)
                        ))
                    };
                }
                return Err(format!("no file {}", self.shown(resolved)));
            }
            if resolved.extension().is_some_and(|e| e == "md") {
                return Err(format!(
                    "{} is outside the book: mdBook links it as .html, which the built book \
                     lacks (link its directory, or include it in a page)",
                    self.shown(resolved)
                ));
            }
        }
        if resolved.exists() {
            Ok(resolved.to_path_buf())
        } else {
            Err(format!("no file {}", self.shown(resolved)))
        }
    }

    /// Checks everything: SUMMARY.md against the pages, every book page as built, the files
    /// the pages include where they live, and README.md.
    pub fn check_all(&mut self) {
        let src = normalise(&self.book_src());
        let summary = src.join("SUMMARY.md");
        let summary_text = std::fs::read_to_string(&summary).unwrap_or_default();
        let mut listed = BTreeSet::new();
        for (line, target) in links(&summary_text) {
            if target.is_empty() || is_external(&target) {
                continue;
            }
            let page = normalise(&src.join(target.split('#').next().unwrap_or("")));
            if !page.is_file() {
                let problem = format!(
                    "book/src/SUMMARY.md, line {line}: the entry {target} has no file {}",
                    self.shown(&page)
                );
                self.problems.push(problem);
            }
            listed.insert(page);
        }
        let mut pages = Vec::new();
        collect_markdown(&src, &mut pages);
        pages.sort();
        let mut included_files = BTreeSet::new();
        for page in &pages {
            if *page == summary {
                continue;
            }
            if !listed.contains(page) {
                let problem = format!(
                    "{}: a page of the book that SUMMARY.md does not list",
                    self.shown(page)
                );
                self.problems.push(problem);
            }
            let (_, included) = self.expanded(page, 0);
            self.check_links(page, true, "");
            included_files.extend(included);
        }
        for file in included_files {
            if file.extension().is_some_and(|e| e == "md") && !file.starts_with(&src) {
                self.check_links(&file, false, " (as the repository shows it)");
            }
        }
        self.check_links(&self.root.join("README.md"), false, "");
        // A page read twice (for its links and for another page's anchors) reports once.
        let mut seen = BTreeSet::new();
        self.problems.retain(|p| seen.insert(p.clone()));
    }
}

/// The lines of an include's range (`2`, `2:`, `:10`, `2:10`, 1-based, inclusive), or all of
/// them for no range or a named anchor.
fn select_lines<T>(lines: Vec<T>, range: Option<&str>) -> Vec<T> {
    let Some(range) = range else {
        return lines;
    };
    let number = |s: &str| s.trim().parse::<usize>().ok();
    let (from, to) = match range.split_once(':') {
        Some((a, b)) => (
            number(a).unwrap_or(1),
            if b.trim().is_empty() {
                lines.len()
            } else {
                number(b).unwrap_or(lines.len())
            },
        ),
        None => match number(range) {
            Some(n) => (n, n),
            None => return lines,
        },
    };
    let to = to.min(lines.len());
    let from = from.max(1);
    lines
        .into_iter()
        .enumerate()
        .filter(|(i, _)| *i + 1 >= from && *i < to)
        .map(|(_, l)| l)
        .collect()
}

fn collect_markdown(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        // Symbolic links (figure directories of the repository) hold no pages.
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if kind.is_dir() {
            collect_markdown(&path, out);
        } else if kind.is_file() && path.extension().is_some_and(|e| e == "md") {
            out.push(normalise(&path));
        }
    }
}

#[test]
fn every_link_of_the_book_and_the_readme_resolves() {
    let root = normalise(Path::new(env!("CARGO_MANIFEST_DIR")));
    let mut checker = Checker::new(&root);
    checker.check_all();
    assert!(
        checker.problems.is_empty(),
        "{} broken link(s), include(s) or page(s):\n{}",
        checker.problems.len(),
        checker.problems.join("\n")
    );
}

/// A small repository with a book, written into a scratch directory.
fn repository(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let root = common::scratch_dir(name);
    for (path, text) in files {
        let path = root.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    normalise(&root)
}

fn problems(name: &str, files: &[(&str, &str)]) -> Vec<String> {
    let root = repository(name, files);
    let mut checker = Checker::new(&root);
    checker.check_all();
    checker.problems
}

const SUMMARY: (&str, &str) = (
    "book/src/SUMMARY.md",
    "# Summary\n\n- [Intro](intro.md)\n- [Part](part/page.md)\n",
);

#[test]
fn a_sound_book_passes() {
    let found = problems(
        "book-links-sound",
        &[
            SUMMARY,
            ("book/src/intro.md", "# Intro\n\nSee [the page](part/page.md#a-b-c) and [here](#intro).\n"),
            (
                "book/src/part/page.md",
                "# A, b (`c`)\n\n## Repeat\n\n## Repeat\n\n[back](../intro.md) [second](#repeat-1)\n\
                 ![fig](../../../data/fig.svg) [data](../../../data/)\n\n{{#include ../../../data/notes.md}}\n",
            ),
            ("data/fig.svg", "<svg/>"),
            ("data/notes.md", "# Notes\n\nNo links here.\n"),
            ("README.md", "# Title\n\n[book](book/src/intro.md#intro)\n\n```\n[not a link](nowhere.md)\n```\n"),
        ],
    );
    assert!(found.is_empty(), "{found:#?}");
}

#[test]
fn a_broken_link_a_missing_anchor_and_a_missing_include_are_found() {
    let found = problems(
        "book-links-broken",
        &[
            SUMMARY,
            (
                "book/src/intro.md",
                "# Intro\n\n[gone](part/gone.md) [no heading](part/page.md#nothing) \
                 [bad](#nowhere)\n\n{{#include ../../data/missing.md}}\n",
            ),
            ("book/src/part/page.md", "# Page\n"),
            (
                "README.md",
                "[gone](docs/gone.md) [anchor](book/src/intro.md#outro)\n",
            ),
        ],
    );
    let expect = [
        "book/src/intro.md, line 3: link part/gone.md: no file book/src/part/gone.md",
        "book/src/intro.md, line 3: link part/page.md#nothing: book/src/part/page.md has no heading with the anchor #nothing",
        "book/src/intro.md, line 3: link #nowhere: book/src/intro.md has no heading with the anchor #nowhere",
        "book/src/intro.md, line 5: {{#include ../../data/missing.md}}: no file data/missing.md",
        "README.md, line 1: link docs/gone.md: no file docs/gone.md",
        "README.md, line 1: link book/src/intro.md#outro: book/src/intro.md has no heading with the anchor #outro",
    ];
    for e in expect {
        assert!(
            found.iter().any(|p| p == e),
            "not found: {e}\nin {found:#?}"
        );
    }
    assert_eq!(found.len(), expect.len(), "{found:#?}");
}

#[test]
fn pages_missing_from_the_summary_and_entries_without_pages_are_found() {
    let found = problems(
        "book-links-summary",
        &[
            SUMMARY,
            ("book/src/intro.md", "# Intro\n"),
            ("book/src/orphan.md", "# Orphan\n"),
        ],
    );
    assert!(
        found.contains(
            &"book/src/orphan.md: a page of the book that SUMMARY.md does not list".to_string()
        ),
        "{found:#?}"
    );
    assert!(
        found.contains(
            &"book/src/SUMMARY.md, line 4: the entry part/page.md has no file book/src/part/page.md"
                .to_string()
        ),
        "{found:#?}"
    );
    assert_eq!(found.len(), 2, "{found:#?}");
}

#[test]
fn included_text_links_from_the_including_page_and_from_where_it_lives() {
    // data/notes.md links fig.svg beside it: right where it lives, wrong in the book page that
    // includes it (the built book resolves it from book/src/). A .md outside the book is refused
    // in a book page; a redirect of book.toml keeps an old page's links alive.
    let found = problems(
        "book-links-included",
        &[
            SUMMARY,
            ("book/src/intro.md", "# Intro\n\n{{#include ../../data/notes.md}}\n"),
            ("book/src/part/page.md", "# Page\n\n[notes](../../../data/notes.md) [old](../old/page.md#page)\n"),
            (
                "book/book.toml",
                "[book]\ntitle = \"t\"\n\n[output.html.redirect]\n\"/old/page.html\" = \"../part/page.html\"\n",
            ),
            ("data/notes.md", "# Notes\n\n![fig](fig.svg)\n"),
            ("data/fig.svg", "<svg/>"),
        ],
    );
    assert_eq!(
        found,
        [
            "book/src/intro.md, line 3 of data/notes.md: link fig.svg: no file book/src/fig.svg",
            "book/src/part/page.md, line 3: link ../../../data/notes.md: data/notes.md is outside the book: mdBook links it as .html, which the built book lacks (link its directory, or include it in a page)",
        ],
        "{found:#?}"
    );
}

#[test]
fn anchors_follow_mdbooks_rule() {
    assert_eq!(
        heading_id("The rigid block (`flexrock::rigid`)"),
        "the-rigid-block-flexrockrigid"
    );
    assert_eq!(
        heading_id("7a. Self-weight in the bending"),
        "7a-self-weight-in-the-bending"
    );
    assert_eq!(
        heading_id("Exit codes, limits & warnings"),
        "exit-codes-limits--warnings"
    );
    assert_eq!(
        heading_id("See [the model](model.md) <em>now</em>"),
        "see-the-model-now"
    );
    let found = anchors("# A\n\n## A\n\n```\n# not a heading\n```\n<a id=\"here\"></a>\n");
    assert_eq!(found.into_iter().collect::<Vec<_>>(), ["a", "a-1", "here"]);
}
