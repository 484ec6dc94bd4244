//! The import graph of a crate, file by file, read from its `use` paths and the `crate::`,
//! `super::` and `self::` paths of its code (tests and comments left out): which files each
//! file takes names from, and the circles among them.
//!
//! A file that only declares and re-exports its own submodules (`mod x; pub use x::Name;`) is a
//! face, not a dependency: a path through it (`crate::floor::FloorMotion`) is followed to the
//! file the name comes from, and a re-export of one's own submodules draws no arrow.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One file of the crate: its module path and its code without tests and comments.
struct File {
    module: Vec<String>,
    code: String,
}

/// A crate's files and the arrows between them (file -> the names it takes from each file).
pub struct Graph {
    /// Each file (relative to the crate's source folder) and the files it imports, with the
    /// names taken.
    pub arrows: BTreeMap<String, BTreeMap<String, BTreeSet<String>>>,
}

/// The code of `text` without its test module (a `#[cfg(test)]` followed by `mod tests`, which by
/// the project's convention ends the file) and without comments.
pub fn code_without_tests(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let end = lines
        .windows(2)
        .position(|w| w[0].trim() == "#[cfg(test)]" && w[1].trim_start().starts_with("mod tests"))
        .unwrap_or(lines.len());
    lines[..end]
        .iter()
        .map(|line| strip_comment(line))
        .collect::<Vec<_>>()
        .join("\n")
}

/// A line without its `//` comment (a `//` inside a string literal is kept).
fn strip_comment(line: &str) -> &str {
    let mut in_string = false;
    let bytes = line.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if in_string => i += 1,
            b'"' => in_string = !in_string,
            b'/' if !in_string && bytes.get(i + 1) == Some(&b'/') => return &line[..i],
            _ => {}
        }
        i += 1;
    }
    line
}

/// The module path of a file relative to the source folder: `lib.rs` and `main.rs` are the root,
/// `a/mod.rs` is `a`, `a/b.rs` is `a::b`.
fn module_of(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative
        .iter()
        .map(|p| p.to_string_lossy().to_string())
        .collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if !(stem == "mod" || (parts.is_empty() && (stem == "lib" || stem == "main"))) {
        parts.push(stem.to_string());
    }
    parts
}

/// Every `.rs` file under `dir`, relative to `root`.
fn rust_files(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path.strip_prefix(root).unwrap().to_path_buf());
        }
    }
}

/// One path a file names: where it starts and its segments, and whether it is the target of a
/// `pub use` (a re-export).
#[derive(Debug, Clone, PartialEq)]
pub struct Named {
    /// `crate`, `super`, `self` or a plain first segment (a child module, or another crate).
    pub start: String,
    /// The segments after the start (`super::super::x` gives start `super`, segments
    /// `["super", "x"]`).
    pub segments: Vec<String>,
    /// Named by a `pub use` (or `pub(crate) use`).
    pub reexport: bool,
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The paths named in `code`: every `use` declaration's tree, expanded, and every inline path
/// that starts with `crate::`, `super::` or `self::`.
pub fn named_paths(code: &str) -> Vec<Named> {
    let mut out = Vec::new();
    let mut rest = code;
    while !rest.is_empty() {
        let line_end = rest.find('\n').map_or(rest.len(), |n| n + 1);
        let trimmed = rest[..line_end].trim_start();
        let declaration = ["use ", "pub use ", "pub(crate) use ", "pub(super) use "]
            .iter()
            .find(|p| trimmed.starts_with(**p));
        if let Some(prefix) = declaration {
            let from = line_end - trimmed.len() + prefix.len();
            let end = rest[from..].find(';').map_or(rest.len(), |n| from + n);
            let tree = without_renames(&rest[from..end]);
            let mut paths = Vec::new();
            expand_tree(&tree, &mut Vec::new(), &mut paths);
            for segments in paths {
                if let Some((start, segments)) = segments.split_first() {
                    out.push(Named {
                        start: start.clone(),
                        segments: segments.to_vec(),
                        reexport: prefix.starts_with("pub"),
                    });
                }
            }
            rest = &rest[(end + 1).min(rest.len())..];
            continue;
        }
        inline_paths(&rest[..line_end], &mut out);
        rest = &rest[line_end..];
    }
    out
}

/// A use tree without whitespace and without its renames (`a::B as C` -> `a::B`).
fn without_renames(tree: &str) -> String {
    let words: Vec<&str> = tree.split_whitespace().collect();
    let mut kept = String::new();
    let mut i = 0;
    while i < words.len() {
        if words[i] == "as" && i + 1 < words.len() {
            // `as name` may carry the next separator glued to it: `as C,` or `as C}`.
            let tail: String = words[i + 1]
                .trim_start_matches(|c: char| is_ident(c))
                .to_string();
            kept.push_str(&tail);
            i += 2;
            continue;
        }
        kept.push_str(words[i]);
        i += 1;
    }
    kept
}

/// The paths in `line` that start with `crate::`, `super::` or `self::`.
fn inline_paths(line: &str, out: &mut Vec<Named>) {
    let chars: Vec<char> = line.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let mut advanced = false;
        for start in ["crate", "super", "self"] {
            if starts_word(&chars, i, start)
                && chars[i + start.len()..].starts_with(&[':', ':'])
                && !(i >= 2 && chars[i - 1] == ':' && chars[i - 2] == ':')
            {
                let mut j = i + start.len();
                let mut segments = Vec::new();
                while chars[j..].starts_with(&[':', ':']) {
                    let from = j + 2;
                    let mut k = from;
                    while k < chars.len() && is_ident(chars[k]) {
                        k += 1;
                    }
                    if k == from {
                        break;
                    }
                    segments.push(chars[from..k].iter().collect());
                    j = k;
                }
                out.push(Named {
                    start: start.to_string(),
                    segments,
                    reexport: false,
                });
                i = j;
                advanced = true;
                break;
            }
        }
        if !advanced {
            i += 1;
        }
    }
}

/// True when `word` starts at `at` as a whole word.
fn starts_word(chars: &[char], at: usize, word: &str) -> bool {
    let w: Vec<char> = word.chars().collect();
    chars[at..].starts_with(&w)
        && (at == 0 || !is_ident(chars[at - 1]))
        && chars.get(at + w.len()).is_none_or(|&c| !is_ident(c))
}

/// Expands a use tree without whitespace (`a::{b::C,d}` -> `a::b::C`, `a::d`) into `out`.
fn expand_tree(tree: &str, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    if let Some(group) = tree.strip_prefix('{') {
        let inner = group.strip_suffix('}').unwrap_or(group);
        for part in split_top(inner) {
            if !part.is_empty() {
                expand_tree(&part, prefix, out);
            }
        }
        return;
    }
    match tree.find("::") {
        Some(at) if !tree[..at].contains('{') => {
            prefix.push(tree[..at].to_string());
            expand_tree(&tree[at + 2..], prefix, out);
            prefix.pop();
        }
        _ => {
            let name = tree;
            let mut path = prefix.clone();
            if name != "self" && name != "*" && !name.is_empty() {
                path.push(name.to_string());
            }
            out.push(path);
        }
    }
}

/// Splits `text` at its commas outside braces.
fn split_top(text: &str) -> Vec<String> {
    let mut parts = vec![String::new()];
    let mut depth = 0;
    for c in text.chars() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(String::new());
                continue;
            }
            _ => {}
        }
        parts.last_mut().unwrap().push(c);
    }
    parts
}

impl Graph {
    /// The graph of the crate whose source folder is `src`.
    pub fn of(src: &Path) -> Graph {
        let mut paths = Vec::new();
        rust_files(src, src, &mut paths);
        let mut files: BTreeMap<String, File> = BTreeMap::new();
        for relative in paths {
            let name = relative.to_string_lossy().replace('\\', "/");
            if name.ends_with("/tests.rs") || name == "tests.rs" {
                continue;
            }
            let text = std::fs::read_to_string(src.join(&relative)).unwrap();
            files.insert(
                name,
                File {
                    module: module_of(&relative),
                    code: code_without_tests(&text),
                },
            );
        }
        let by_module: BTreeMap<Vec<String>, String> = files
            .iter()
            .map(|(name, f)| (f.module.clone(), name.clone()))
            .collect();
        let mut arrows = BTreeMap::new();
        for (name, file) in &files {
            let mut to: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
            for named in named_paths(&file.code) {
                let Some(absolute) = absolute_path(&file.module, &named, &by_module) else {
                    continue;
                };
                // Re-exporting one's own submodules is declaring them, not depending on them.
                if named.reexport && absolute.starts_with(&file.module) {
                    continue;
                }
                if let Some((target, item)) = resolve(&absolute, &by_module, &files, 0) {
                    if &target != name {
                        to.entry(target).or_default().insert(item);
                    }
                }
            }
            arrows.insert(name.clone(), to);
        }
        Graph { arrows }
    }

    /// The circles: every set of two or more files that import each other, round a loop, each
    /// with its arrows inside the set and the names they take.
    pub fn circles(&self) -> Vec<Vec<String>> {
        let names: Vec<&String> = self.arrows.keys().collect();
        let index: BTreeMap<&String, usize> =
            names.iter().enumerate().map(|(i, n)| (*n, i)).collect();
        let edges: Vec<Vec<usize>> = names
            .iter()
            .map(|n| {
                self.arrows[*n]
                    .keys()
                    .filter_map(|t| index.get(t).copied())
                    .collect()
            })
            .collect();
        let mut circles = Vec::new();
        for component in strongly_connected(&edges) {
            if component.len() < 2 {
                continue;
            }
            let members: BTreeSet<&String> = component.iter().map(|&i| names[i]).collect();
            let mut lines = Vec::new();
            for from in &members {
                for (to, items) in &self.arrows[*from] {
                    if members.contains(to) {
                        let items: Vec<&str> = items.iter().map(String::as_str).collect();
                        lines.push(format!("{from} -> {to}: {}", items.join(", ")));
                    }
                }
            }
            circles.push(lines);
        }
        circles
    }
}

/// The module path `named` means, seen from the module `here`; None for another crate's path.
fn absolute_path(
    here: &[String],
    named: &Named,
    by_module: &BTreeMap<Vec<String>, String>,
) -> Option<Vec<String>> {
    let mut base: Vec<String> = match named.start.as_str() {
        "crate" => Vec::new(),
        "self" => here.to_vec(),
        "super" => here[..here.len().saturating_sub(1)].to_vec(),
        child => {
            // A plain first segment: a child module of this one, or a name of another crate.
            let mut path = here.to_vec();
            path.push(child.to_string());
            if !by_module.contains_key(&path) {
                return None;
            }
            path
        }
    };
    let mut segments = named.segments.iter().peekable();
    if named.start == "super" {
        while segments.peek().is_some_and(|s| *s == "super") {
            segments.next();
            base.pop();
        }
    }
    base.extend(segments.cloned());
    Some(base)
}

/// The file that defines the last name of `path` (and that name): the longest module prefix with
/// a file, followed through that file's re-exports of its submodules.
fn resolve(
    path: &[String],
    by_module: &BTreeMap<Vec<String>, String>,
    files: &BTreeMap<String, File>,
    depth: usize,
) -> Option<(String, String)> {
    let (length, file) = (0..=path.len())
        .rev()
        .find_map(|n| by_module.get(&path[..n]).map(|f| (n, f.clone())))?;
    let item = path
        .get(length)
        .cloned()
        .unwrap_or_else(|| "(module)".into());
    if depth < 8 && length < path.len() {
        // A name the file re-exports from one of its submodules comes from that submodule.
        let module = &path[..length];
        for named in named_paths(&files[&file].code) {
            if !named.reexport {
                continue;
            }
            if let Some(absolute) = absolute_path(module, &named, by_module) {
                if absolute.last() == Some(&item) && absolute.starts_with(module) {
                    let mut target = absolute.clone();
                    target.extend(path[length + 1..].iter().cloned());
                    if let Some(found) = resolve(&target, by_module, files, depth + 1) {
                        return Some(found);
                    }
                }
            }
        }
    }
    Some((file, item))
}

/// Tarjan's strongly connected components of the graph `edges` (node -> its successors).
fn strongly_connected(edges: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        edges: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for &w in &s.edges[v] {
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                _ => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            s.out.push(component);
        }
    }
    let n = edges.len();
    let mut s = State {
        edges,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}
