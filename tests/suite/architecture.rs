//! The layers of docs/ARCHITECTURE.md, checked: every file of the library (`src/**/*.rs` but the
//! command line, `src/cli/` and `src/main.rs`) may use only its own layer and those before it in
//! [`LAYERS`]. A `crate::module` path (grouped imports too) or a `super::` path that climbs to the
//! crate root names the module a file uses; code in comments and strings does not count. A
//! module missing from the table fails, so that a new one is placed before it is used.

use std::path::{Path, PathBuf};

/// The layers in order: a file uses only modules of its layer and of the layers before it.
/// Mirrors the table of docs/ARCHITECTURE.md.
const LAYERS: &[(&str, &[&str])] = &[
    ("numeric", &["numeric", "error"]),
    ("physics", &["physics"]),
    ("solver", &["solver"]),
    ("kernel", &["kernel"]),
    ("gpu", &["gpu"]),
    ("engine", &["engine"]),
    ("law", &["law"]),
    ("plumbing", &["io", "progress", "interrupt"]),
    (
        "work",
        &["map", "scene", "cycle", "profile", "fit", "rough", "dem"],
    ),
    ("output", &["render", "export", "figure_data", "bench"]),
    ("front ends", &["cli"]),
];

/// The layer of a top-level module: its index in [`LAYERS`] and its name.
fn layer(module: &str) -> Option<(usize, &'static str)> {
    LAYERS
        .iter()
        .enumerate()
        .find(|(_, (_, modules))| modules.contains(&module))
        .map(|(i, (name, _))| (i, *name))
}

/// The source with comments, strings and character literals blanked (newlines kept, so that
/// line numbers stay right).
fn code_only(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let blank = |out: &mut String, ch: char| out.push(if ch == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < c.len() {
        let at = |k: usize| c.get(k).copied().unwrap_or('\0');
        if c[i] == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                blank(&mut out, c[i]);
                i += 1;
            }
        } else if c[i] == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            loop {
                if i >= c.len() {
                    break;
                }
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, c[i]);
                    i += 1;
                }
            }
        } else if let Some(hashes) = raw_string_start(&c, i) {
            // r"..", r#".."#, br#".."#: no escapes, ends at a quote and as many hashes.
            let mut j = i;
            while c[j] != '"' {
                j += 1;
            }
            j += 1;
            while j < c.len() && !(c[j] == '"' && (1..=hashes).all(|k| at(j + k) == '#')) {
                j += 1;
            }
            let end = (j + 1 + hashes).min(c.len());
            for &ch in &c[i..end] {
                blank(&mut out, ch);
            }
            i = end;
        } else if c[i] == '"' {
            blank(&mut out, c[i]);
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    blank(&mut out, c[i]);
                    i += 1;
                }
                if i < c.len() {
                    blank(&mut out, c[i]);
                    i += 1;
                }
            }
            if i < c.len() {
                blank(&mut out, c[i]);
                i += 1;
            }
        } else if c[i] == '\'' && (at(i + 1) == '\\' || (at(i + 1) != '\'' && at(i + 2) == '\'')) {
            // A character literal ('x', '\n', '\u{..}'); a lifetime or label has no closing quote.
            let mut j = i + 1;
            if at(j) == '\\' {
                j += 2;
            }
            while j < c.len() && c[j] != '\'' {
                j += 1;
            }
            let end = (j + 1).min(c.len());
            for &ch in &c[i..end] {
                blank(&mut out, ch);
            }
            i = end;
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// The number of hashes of a raw string that starts at `i` (`r"`, `r#"`, `br"`, ...).
fn raw_string_start(c: &[char], i: usize) -> Option<usize> {
    let before = if i > 0 { c[i - 1] } else { ' ' };
    if before.is_alphanumeric() || before == '_' {
        return None;
    }
    let mut j = i;
    if c.get(j) == Some(&'b') {
        j += 1;
    }
    if c.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let mut hashes = 0;
    while c.get(j) == Some(&'#') {
        hashes += 1;
        j += 1;
    }
    (c.get(j) == Some(&'"')).then_some(hashes)
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`
    Sep,
    Punct(char),
}

fn tokens(code: &str) -> Vec<(Tok, usize)> {
    let c: Vec<char> = code.chars().collect();
    let (mut out, mut line, mut i) = (Vec::new(), 1, 0);
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch.is_alphanumeric() || ch == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push((Tok::Ident(c[start..i].iter().collect()), line));
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            out.push((Tok::Sep, line));
            i += 2;
        } else {
            out.push((Tok::Punct(ch), line));
            i += 1;
        }
    }
    out
}

/// The module path of a file under `src/` (`rough/wet.rs` is `[rough, wet]`, `rough/mod.rs`
/// is `[rough]`).
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" {
        parts.push(stem.to_string());
    }
    parts
}

/// The top-level modules (or crate-root items) that the file's paths name, with their lines.
fn uses(rel: &Path, src: &str) -> Vec<(String, usize)> {
    let toks = tokens(&code_only(src));
    let own = module_path(rel);
    let ident = |k: usize| match toks.get(k) {
        Some((Tok::Ident(s), _)) => Some(s.as_str()),
        _ => None,
    };
    let is = |k: usize, t: &Tok| toks.get(k).map(|(x, _)| x) == Some(t);
    // Inline modules (`mod tests { .. }`) open a level of the path that `super` climbs.
    let mut inline: Vec<usize> = Vec::new();
    let mut depth = 0usize;
    let mut found = Vec::new();
    let mut k = 0;
    while k < toks.len() {
        let line = toks[k].1;
        match &toks[k].0 {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth = depth.saturating_sub(1);
                if inline.last() == Some(&depth) {
                    inline.pop();
                }
            }
            Tok::Ident(w)
                if w == "mod" && ident(k + 1).is_some() && is(k + 2, &Tok::Punct('{')) =>
            {
                inline.push(depth);
            }
            Tok::Ident(w)
                if (w == "crate" || w == "super")
                    && is(k + 1, &Tok::Sep)
                    && !(k > 0 && (is(k - 1, &Tok::Sep) || is(k - 1, &Tok::Punct('$')))) =>
            {
                // Where the path starts: `crate` is the root; each `super` climbs one level.
                let mut level = own.len() + inline.len();
                let mut j = k;
                if w == "crate" {
                    level = 0;
                    j += 2;
                } else {
                    while ident(j) == Some("super") && is(j + 1, &Tok::Sep) {
                        level = level.saturating_sub(1);
                        j += 2;
                    }
                }
                if level == 0 {
                    if let Some(name) = ident(j) {
                        found.push((name.to_string(), line));
                    } else if is(j, &Tok::Punct('{')) {
                        // A group: the first segment of each item.
                        let (mut d, mut first) = (0, true);
                        for (t, l) in &toks[j..] {
                            match t {
                                Tok::Punct('{') => {
                                    d += 1;
                                    first = d == 1;
                                    continue;
                                }
                                Tok::Punct('}') => {
                                    d -= 1;
                                    if d == 0 {
                                        break;
                                    }
                                }
                                Tok::Punct(',') if d == 1 => {
                                    first = true;
                                    continue;
                                }
                                Tok::Ident(s) if first && d == 1 && s != "self" => {
                                    found.push((s.clone(), *l));
                                }
                                _ => {}
                            }
                            first = false;
                        }
                    }
                }
                k = j;
                continue;
            }
            _ => {}
        }
        k += 1;
    }
    found
}

/// Every import of `src` (the file `rel` under `src/`) that runs back up the layers or names
/// something outside the table, as a message naming file, line and layers.
fn violations(rel: &Path, src: &str) -> Vec<String> {
    let own = module_path(rel);
    let file = Path::new("src").join(rel).display().to_string();
    let Some((from, from_name)) = layer(&own[0]) else {
        return vec![format!(
            "{file}: module `{}` has no layer: place it in tests/suite/architecture.rs and docs/ARCHITECTURE.md",
            own[0]
        )];
    };
    let mut out = Vec::new();
    for (name, line) in uses(rel, src) {
        if name == own[0] {
            continue;
        }
        match layer(&name) {
            None => out.push(format!(
                "{file}:{line}: `crate::{name}` is no module of the table (a crate-root re-export or a new module): import it from its module, or place the module in the layers"
            )),
            Some((to, to_name)) if to > from => out.push(format!(
                "{file}:{line}: layer {from_name} uses `{name}` of layer {to_name}, which comes after it"
            )),
            _ => {}
        }
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

#[test]
fn the_library_keeps_its_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    // Every top-level module has a layer, used or not.
    let (mut bad, mut unplaced) = (Vec::new(), Vec::new());
    for e in std::fs::read_dir(&src).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_stem().unwrap().to_string_lossy().into_owned();
        let module = p.is_dir() || p.extension().is_some_and(|x| x == "rs");
        if module && name != "lib" && name != "main" && layer(&name).is_none() {
            bad.push(format!(
                "src/{name}: module has no layer: place it in tests/suite/architecture.rs and docs/ARCHITECTURE.md"
            ));
            unplaced.push(name);
        }
    }
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut checked = 0;
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let skip = rel == Path::new("lib.rs") || rel == Path::new("main.rs");
        if skip || rel.starts_with("cli") || unplaced.contains(&module_path(rel)[0]) {
            continue;
        }
        bad.extend(violations(rel, &std::fs::read_to_string(f).unwrap()));
        checked += 1;
    }
    assert!(checked > 50, "only {checked} files read");
    assert!(
        bad.is_empty(),
        "imports against the layers:\n{}",
        bad.join("\n")
    );
}

#[test]
fn an_import_back_up_fails() {
    let src =
        "use crate::physics::md::point;\nfn f() {\n    let e = crate::engine::Engine::Cpu;\n}\n";
    let v = violations(Path::new("solver/curve.rs"), src);
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(v[0].starts_with("src/solver/curve.rs:3: layer solver uses `engine` of layer engine"));
    // Grouped imports, and `super` climbing to the root from a module's own file.
    let v = violations(
        Path::new("physics/md.rs"),
        "use crate::{numeric::root, solver::X};",
    );
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(v[0].contains("`solver`"), "{v:?}");
    let v = violations(Path::new("engine.rs"), "use super::{map::axis, physics};");
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(v[0].contains("`map` of layer work"), "{v:?}");
    let v = violations(Path::new("gpu/mod.rs"), "use super::super::map::axis;");
    assert_eq!(v.len(), 1, "{v:?}");
}

#[test]
fn comments_strings_and_inner_supers_do_not_count() {
    let src = r##"
//! Uses `crate::map` in a comment.
/* crate::render::x /* nested crate::fit */ */
const S: &str = "crate::engine::Engine";
const R: &str = r#"crate::rough"#;
const C: char = '"';
fn f<'a>(x: &'a str) -> &'a str { x }
mod tests {
    use super::*;
    use super::super::physics::md;
}
"##;
    assert_eq!(
        violations(Path::new("solver/curve.rs"), src),
        Vec::<String>::new()
    );
    // In a module's own file `super` is the crate root.
    let v = violations(
        Path::new("solver/curve.rs"),
        "mod t { use super::super::super::fit; }",
    );
    assert_eq!(v.len(), 1, "{v:?}");
}

#[test]
fn unknown_modules_and_root_items_fail() {
    let v = violations(Path::new("rough/wet.rs"), "fn f(l: crate::ContactLaw) {}");
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(v[0].contains("`crate::ContactLaw` is no module"), "{v:?}");
    let v = violations(Path::new("newthing.rs"), "");
    assert!(v[0].contains("module `newthing` has no layer"), "{v:?}");
}
