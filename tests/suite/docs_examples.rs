//! The documentation's examples, run: every shell example quoted in README.md and docs/**/*.md
//! must print what it shows, so the documents cannot drift from the tool.
//!
//! An example is a fenced block with lines starting with `$ `. Each `$ COMMAND` line is followed
//! by the output it shows, up to the next `$ ` line or the closing fence.
//!
//! - `$ tabor ARGS` runs the binary built with this test, in a scratch directory (one per
//!   document, shared by its blocks in order), stdout and stderr merged as a terminal shows them.
//!   It must exit 0 and print the lines shown. `TABOR_*` variables are removed from its
//!   environment.
//! - `$ cat FILE` defines FILE with the lines shown (for the document's later commands), or, if
//!   FILE is already there (copied from the repository or written by an earlier command),
//!   compares them with its content.
//! - A repository file named by an argument (`examples/si_tip_40rh.json`, `tests/data/...`,
//!   `gallery/...`, also after `--flag=`) is copied into the scratch directory at the same
//!   relative path before the command runs: an example that writes `gallery/fit.png` writes the
//!   copy, never the tracked file.
//! - Trailing spaces and trailing blank lines are not compared.
//!
//! What the shown text may leave out, and the markers (use them sparingly, always with a reason):
//! - a line that is only `...` (any indentation) stands for any number of lines, also none;
//! - `...` inside a line stands for any text there (that line is then compared as text only);
//! - `<!-- check: skip (REASON) -->` on the line before the opening fence: the block's commands
//!   are not run (its `$ cat` lines still define files);
//! - `<!-- check: digits N (REASON) -->` there: every number is compared to N significant
//!   digits (for figures that differ between machines in float noise), the rest exactly.
//!
//! Any other command, shell syntax (pipes, redirections) or an unknown marker is reported as a
//! mismatch. Every mismatch is reported at once (file, line, command, a diff), then the test fails.

use std::fmt::Write as _;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// One `$ ` line of an example and the output shown after it.
struct Step {
    line: usize,
    command: String,
    shown: Vec<String>,
}

/// One fenced example with its markers.
struct Block {
    steps: Vec<Step>,
    skip: Option<String>,
    digits: Option<usize>,
    /// Marker errors (unknown keyword, missing reason), reported at the block's first line.
    marker_errors: Vec<String>,
    line: usize,
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every Markdown file under docs/, in a stable order.
fn documents() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        let mut paths: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        paths.sort();
        for p in paths {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "md") {
                out.push(p);
            }
        }
    }
    let mut docs = vec![repo().join("README.md")];
    walk(&repo().join("docs"), &mut docs);
    docs
}

/// The markers directly above a fence at index `fence` (0-based): (skip, digits, errors).
fn markers(lines: &[&str], fence: usize) -> (Option<String>, Option<usize>, Vec<String>) {
    let (mut skip, mut digits, mut errors) = (None, None, Vec::new());
    let mut i = fence;
    while i > 0 {
        i -= 1;
        let l = lines[i].trim();
        let Some(body) = l
            .strip_prefix("<!-- check:")
            .and_then(|b| b.strip_suffix("-->"))
        else {
            break;
        };
        let body = body.trim();
        let (word, rest) = body.split_once(' ').unwrap_or((body, ""));
        let rest = rest.trim();
        let reason_ok = |r: &str| r.starts_with('(') && r.ends_with(')') && r.len() > 2;
        match word {
            "skip" if reason_ok(rest) => skip = Some(rest.to_string()),
            "digits" => {
                let (n, reason) = rest.split_once(' ').unwrap_or((rest, ""));
                match n.parse::<usize>() {
                    Ok(n) if (1..=17).contains(&n) && reason_ok(reason.trim()) => digits = Some(n),
                    _ => errors.push(format!("bad marker `{l}`: write `digits N (reason)`")),
                }
            }
            _ => errors.push(format!(
                "bad marker `{l}`: use `skip (reason)` or `digits N (reason)`"
            )),
        }
    }
    (skip, digits, errors)
}

/// The examples of one document: fenced blocks with at least one `$ ` line.
fn blocks(text: &str) -> Vec<Block> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if !lines[i].trim_start().starts_with("```") {
            i += 1;
            continue;
        }
        let open = i;
        let mut steps: Vec<Step> = Vec::new();
        i += 1;
        while i < lines.len() && !lines[i].trim_start().starts_with("```") {
            if let Some(cmd) = lines[i].strip_prefix("$ ") {
                steps.push(Step {
                    line: i + 1,
                    command: cmd.trim().to_string(),
                    shown: vec![],
                });
            } else if let Some(step) = steps.last_mut() {
                step.shown.push(lines[i].to_string());
            }
            i += 1;
        }
        i += 1;
        if !steps.is_empty() {
            let (skip, digits, marker_errors) = markers(&lines, open);
            out.push(Block {
                steps,
                skip,
                digits,
                marker_errors,
                line: open + 1,
            });
        }
    }
    out
}

/// Splits a command line as a shell would for plain words and quotes; refuses other syntax.
fn split(command: &str) -> Result<Vec<String>, String> {
    let (mut words, mut word, mut quote, mut any) = (Vec::new(), String::new(), None, false);
    for c in command.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.push(c),
            (None, '\'' | '"') => (quote, any) = (Some(c), true),
            (None, c) if c.is_whitespace() => {
                if any {
                    words.push(std::mem::take(&mut word));
                }
                any = false;
            }
            (None, '|' | '>' | '<' | ';' | '&' | '`' | '$' | '*' | '\\') => {
                return Err(format!("shell syntax `{c}` is not supported here"))
            }
            (None, c) => (word, any) = (word + &c.to_string(), true),
        }
    }
    if quote.is_some() {
        return Err("unclosed quote".into());
    }
    if any {
        words.push(word);
    }
    Ok(words)
}

/// Copies the repository files an argument names into `dir`, and makes the parent directories
/// of paths under repository directories, so that outputs land in `dir`.
fn stage(args: &[String], dir: &Path) {
    for arg in args {
        let path = arg.split_once('=').map_or(arg.as_str(), |(_, v)| v);
        let rel = Path::new(path);
        if path.is_empty() || rel.is_absolute() || path.contains("..") {
            continue;
        }
        let (src, dst) = (repo().join(rel), dir.join(rel));
        if let Some(parent) = rel.parent().filter(|p| !p.as_os_str().is_empty()) {
            if repo().join(parent).is_dir() {
                std::fs::create_dir_all(dir.join(parent)).unwrap();
            }
        }
        if src.is_file() && !dst.exists() {
            std::fs::copy(&src, &dst).unwrap();
        }
    }
}

/// Runs the binary with stdout and stderr merged in one pipe; returns (exit code, output).
fn run_tabor(args: &[String], dir: &Path) -> (Option<i32>, String) {
    let (mut reader, writer) = std::io::pipe().unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_tabor"));
    cmd.args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(writer.try_clone().unwrap())
        .stderr(writer);
    for (key, _) in std::env::vars_os() {
        if key.to_string_lossy().starts_with("TABOR_") {
            cmd.env_remove(key);
        }
    }
    let mut child = cmd.spawn().unwrap();
    // The command holds the pipe's write ends: drop it, or reading never ends.
    drop(cmd);
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes).unwrap();
    let status = child.wait().unwrap();
    (status.code(), String::from_utf8_lossy(&bytes).into_owned())
}

/// Lines without trailing spaces and without trailing blank lines.
fn normalise<S: AsRef<str>>(lines: &[S]) -> Vec<String> {
    let mut v: Vec<String> = lines
        .iter()
        .map(|l| l.as_ref().trim_end().to_string())
        .collect();
    while v.last().is_some_and(|l| l.is_empty()) {
        v.pop();
    }
    v
}

fn is_gap(line: &str) -> bool {
    line.trim() == "..."
}

/// Text and numbers of a line, in order: numbers are compared by value, the rest as text.
fn tokens(line: &str) -> Vec<(String, Option<f64>)> {
    let b = line.as_bytes();
    let (mut out, mut text, mut i) = (Vec::new(), String::new(), 0);
    while i < b.len() {
        let start = i;
        let mut j = i;
        if b[j] == b'-' || b[j] == b'+' {
            j += 1;
        }
        let digits_from = j;
        while j < b.len() && (b[j].is_ascii_digit() || b[j] == b'.') {
            j += 1;
        }
        if j > digits_from && b[digits_from..j].iter().any(u8::is_ascii_digit) {
            // An exponent only if digits follow it.
            let mut k = j;
            if k < b.len() && (b[k] == b'e' || b[k] == b'E') {
                k += 1;
                if k < b.len() && (b[k] == b'-' || b[k] == b'+') {
                    k += 1;
                }
                let e = k;
                while k < b.len() && b[k].is_ascii_digit() {
                    k += 1;
                }
                if k > e {
                    j = k;
                }
            }
            if let Ok(v) = line[start..j].parse::<f64>() {
                if !text.is_empty() {
                    out.push((std::mem::take(&mut text), None));
                }
                out.push((String::new(), Some(v)));
                i = j;
                continue;
            }
        }
        let c = line[i..].chars().next().unwrap();
        text.push(c);
        i += c.len_utf8();
    }
    if !text.is_empty() {
        out.push((text, None));
    }
    out
}

/// Whether `actual` matches the glob `pattern`, where `...` stands for any text.
fn glob(pattern: &str, actual: &str) -> bool {
    let parts: Vec<&str> = pattern.split("...").collect();
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !actual.starts_with(first) || actual.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &actual[first.len()..];
    for part in &parts[1..parts.len() - 1] {
        match rest.find(part) {
            Some(p) => rest = &rest[p + part.len()..],
            None => return false,
        }
    }
    rest.ends_with(last)
}

fn line_matches(shown: &str, actual: &str, digits: Option<usize>) -> bool {
    if shown.contains("...") {
        return glob(shown, actual);
    }
    let Some(n) = digits else {
        return shown == actual;
    };
    let (s, a) = (tokens(shown), tokens(actual));
    let tol = 0.5 * 10f64.powi(1 - n as i32);
    s.len() == a.len()
        && s.iter().zip(&a).all(|(x, y)| match (x.1, y.1) {
            (Some(u), Some(v)) => u == v || (u - v).abs() <= tol * u.abs().max(v.abs()),
            (None, None) => x.0 == y.0,
            _ => false,
        })
}

/// Whether the shown lines (with `...` gaps) match the actual lines, all of them.
fn output_matches(shown: &[String], actual: &[String], digits: Option<usize>) -> bool {
    let (n, m) = (shown.len(), actual.len());
    // ok[i][j]: shown[i..] matches actual[j..].
    let mut ok = vec![vec![false; m + 1]; n + 1];
    ok[n][m] = true;
    for i in (0..n).rev() {
        for j in (0..=m).rev() {
            ok[i][j] = if is_gap(&shown[i]) {
                ok[i + 1][j] || (j < m && ok[i][j + 1])
            } else {
                j < m && line_matches(&shown[i], &actual[j], digits) && ok[i + 1][j + 1]
            };
        }
    }
    ok[0][0]
}

/// A line diff (longest common subsequence): ` ` both, `-` shown only, `+` printed only.
fn diff(shown: &[String], actual: &[String], digits: Option<usize>) -> String {
    let (n, m) = (shown.len(), actual.len());
    let mut l = vec![vec![0usize; m + 1]; n + 1];
    for i in (0..n).rev() {
        for j in (0..m).rev() {
            l[i][j] = if !is_gap(&shown[i]) && line_matches(&shown[i], &actual[j], digits) {
                l[i + 1][j + 1] + 1
            } else {
                l[i + 1][j].max(l[i][j + 1])
            };
        }
    }
    let (mut out, mut i, mut j) = (String::new(), 0, 0);
    while i < n || j < m {
        if i < n && j < m && !is_gap(&shown[i]) && line_matches(&shown[i], &actual[j], digits) {
            writeln!(out, "      {}", actual[j]).unwrap();
            (i, j) = (i + 1, j + 1);
        } else if i < n && (j == m || l[i + 1][j] >= l[i][j + 1]) {
            writeln!(out, "    - {}", shown[i]).unwrap();
            i += 1;
        } else {
            writeln!(out, "    + {}", actual[j]).unwrap();
            j += 1;
        }
    }
    out
}

/// Runs one step; returns a description of the mismatch, if any.
fn check_step(step: &Step, digits: Option<usize>, dir: &Path) -> Option<String> {
    let words = match split(&step.command) {
        Ok(w) => w,
        Err(e) => return Some(format!("{e}; mark the block `check: skip (reason)`")),
    };
    let shown = normalise(&step.shown);
    match words.first().map(String::as_str) {
        Some("cat") if words.len() == 2 => {
            let path = dir.join(&words[1]);
            stage(&words[1..], dir);
            if !path.exists() {
                std::fs::write(&path, shown.join("\n") + "\n").unwrap();
                return None;
            }
            let actual = normalise(
                &std::fs::read_to_string(&path)
                    .unwrap()
                    .lines()
                    .collect::<Vec<_>>(),
            );
            (!output_matches(&shown, &actual, digits))
                .then(|| format!("the file differs:\n{}", diff(&shown, &actual, digits)))
        }
        Some("tabor") => {
            stage(&words[1..], dir);
            let (code, text) = run_tabor(&words[1..], dir);
            let actual = normalise(&text.lines().collect::<Vec<_>>());
            let status = (code != Some(0)).then(|| format!("exit status {code:?} (0 expected)\n"));
            if status.is_none() && output_matches(&shown, &actual, digits) {
                return None;
            }
            Some(format!(
                "{}{}",
                status.unwrap_or_default(),
                diff(&shown, &actual, digits)
            ))
        }
        _ => Some("no rule runs this command: mark the block `check: skip (reason)`".into()),
    }
}

#[test]
fn documented_commands_print_what_the_documents_show() {
    let (mut failures, mut run, mut files, mut skipped) = (Vec::new(), 0, 0, 0);
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        let name = doc.strip_prefix(repo()).unwrap().display().to_string();
        let dir = tempfile::tempdir().unwrap();
        for s in blocks(&text) {
            for e in &s.marker_errors {
                failures.push(format!("{name}:{}: {e}", s.line));
            }
            for step in &s.steps {
                if s.skip.is_some() && !step.command.starts_with("cat ") {
                    skipped += 1;
                    continue;
                }
                if step.command.starts_with("cat ") {
                    files += 1;
                } else {
                    run += 1;
                }
                if let Some(why) = check_step(step, s.digits, dir.path()) {
                    failures.push(format!("{name}:{}: $ {}\n{why}", step.line, step.command));
                }
            }
        }
    }
    eprintln!("documented commands: {run} run, {files} `cat` files, {skipped} skipped by markers");
    assert!(run > 0, "no documented command found");
    assert!(
        failures.is_empty(),
        "{} documented command(s) differ from the documents ('-' shown, '+' printed):\n\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A `tabor` command quoted in a plain shell block would not be run: every one must be a `$ `
/// example (with a skip marker and its reason where it cannot run here).
#[test]
fn every_quoted_tabor_command_is_an_example() {
    let mut unchecked = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        let name = doc.strip_prefix(repo()).unwrap().display().to_string();
        let mut shell = None;
        for (i, l) in text.lines().enumerate() {
            let t = l.trim_start();
            if let Some(lang) = t.strip_prefix("```") {
                shell = match shell {
                    Some(_) => None,
                    None => Some(matches!(lang.trim(), "sh" | "bash" | "console" | "shell")),
                };
                continue;
            }
            if shell == Some(true) && (t.starts_with("tabor ") || t.contains("-- tabor ")) {
                unchecked.push(format!("{name}:{}: {t}", i + 1));
            }
        }
    }
    assert!(
        unchecked.is_empty(),
        "tabor commands in shell blocks, not run by this test (quote them as `$ ` examples):\n{}",
        unchecked.join("\n")
    );
}

#[test]
fn the_comparison_reads_gaps_elisions_and_digits() {
    let v = |s: &[&str]| s.iter().map(|l| l.to_string()).collect::<Vec<_>>();
    let actual = v(&["head", "a 1", "b 2", "c 3", "tail 1.23456e-7"]);
    assert!(output_matches(
        &v(&["head", "...", "tail 1.23456e-7"]),
        &actual,
        None
    ));
    assert!(output_matches(
        &v(&["head", "a 1", "...", "c 3", "..."]),
        &actual,
        None
    ));
    assert!(!output_matches(
        &v(&["head", "...", "d 4", "..."]),
        &actual,
        None
    ));
    assert!(!output_matches(&v(&["head", "a 1"]), &actual, None));
    assert!(output_matches(
        &v(&["head", "...", "tail ..."]),
        &actual,
        None
    ));
    let shown = v(&["head", "a 1", "b 2", "c 3", "tail 1.23457e-7"]);
    assert!(!output_matches(&shown, &actual, None));
    assert!(output_matches(&shown, &actual, Some(5)));
    assert!(!output_matches(&shown, &actual, Some(6)));
    // Digits compare numbers only: the words around them stay exact.
    assert!(!output_matches(
        &v(&["head", "a 1", "b 2", "c 3", "tails 1.23457e-7"]),
        &actual,
        Some(3)
    ));
    assert_eq!(
        tokens("A 1.5e-3, x-1 e5"),
        vec![
            ("A ".into(), None),
            (String::new(), Some(1.5e-3)),
            (", x".into(), None),
            (String::new(), Some(-1.0)),
            (" e".into(), None),
            (String::new(), Some(5.0)),
        ]
    );
    assert_eq!(
        split("tabor a --b='c d' \"e\"").unwrap(),
        v(&["tabor", "a", "--b=c d", "e"])
    );
    assert!(split("tabor a > out").is_err());
    let doc = "<!-- check: skip (needs a GPU) -->\n```text\n$ tabor x\nout\n\n$ cat f\n1\n```\n";
    let s = blocks(doc);
    assert_eq!(
        (s.len(), s[0].steps.len(), s[0].skip.as_deref()),
        (1, 2, Some("(needs a GPU)"))
    );
    assert_eq!(
        (s[0].steps[0].line, s[0].steps[1].shown.clone()),
        (3, v(&["1"]))
    );
    assert_eq!(
        blocks("<!-- check: digits 9 -->\n```\n$ tabor\n```\n")[0]
            .marker_errors
            .len(),
        1
    );
}
