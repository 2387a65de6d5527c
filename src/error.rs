//! Errors about what a caller gave, with the quantities they name kept apart from their words.
//!
//! The library names a quantity by its own key: a scene's or a spec's field (`lambda_min`,
//! `humidity.relative_humidity`), or a choice (`load_axis=linear`, said "the linear load axis").
//! The command line calls it `--lambda-min`, Python `lambda_min`. An error that names quantities
//! implements [`Named`]: each front end renders it with its own names, and `Display` gives the
//! library's. Nothing rewrites a message's text.

use std::borrow::Cow;
use std::fmt;

/// A front end's names for the library's keys; `None` keeps the library's words.
pub type Names<'a> = &'a dyn Fn(&str) -> Option<&'static str>;

/// The library's own words for every key.
pub fn library_names(_: &str) -> Option<&'static str> {
    None
}

/// An error (or message) that names quantities a caller gave.
pub trait Named {
    /// The text, each quantity called by `names` where it has a name for its key.
    fn named(&self, names: Names) -> String;
}

#[derive(Clone, Debug, PartialEq)]
enum Part {
    Text(Cow<'static, str>),
    /// A key and the library's words for it.
    Key(&'static str, &'static str),
}

/// A message whose named quantities are parts of their own, built as
/// `Message::new().key("lambda_min").text(" must be below ").key("lambda_max")`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Message(Vec<Part>);

impl Message {
    /// An empty message.
    pub fn new() -> Message {
        Message(Vec::new())
    }

    /// Words.
    pub fn text(mut self, s: impl Into<Cow<'static, str>>) -> Message {
        self.0.push(Part::Text(s.into()));
        self
    }

    /// A quantity, said by its key (`lambda_min`).
    pub fn key(mut self, key: &'static str) -> Message {
        self.0.push(Part::Key(key, key));
        self
    }

    /// A choice or quantity that the library says in words (`load_axis=linear`, "the linear
    /// load axis").
    pub fn phrase(mut self, key: &'static str, words: &'static str) -> Message {
        self.0.push(Part::Key(key, words));
        self
    }

    /// This message followed by `more`.
    pub fn then(mut self, more: Message) -> Message {
        self.0.extend(more.0);
        self
    }

    /// The same message with the quantity `from` called `to` (a sweep's `rh_max` for the
    /// humidity it tries).
    pub fn rekey(mut self, from: &str, to: &'static str) -> Message {
        for p in &mut self.0 {
            if matches!(p, Part::Key(k, _) if *k == from) {
                *p = Part::Key(to, to);
            }
        }
        self
    }

    /// The keys it names, in order.
    pub fn keys(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.0.iter().filter_map(|p| match p {
            Part::Key(k, _) => Some(*k),
            Part::Text(_) => None,
        })
    }
}

impl Named for Message {
    fn named(&self, names: Names) -> String {
        self.0
            .iter()
            .map(|p| match p {
                Part::Text(t) => t.as_ref(),
                Part::Key(k, words) => names(k).unwrap_or(words),
            })
            .collect()
    }
}

impl fmt::Display for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.named(&library_names))
    }
}

impl std::error::Error for Message {}

/// In a result (a warning), as the library's words; a front end renders its own before writing.
impl serde::Serialize for Message {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl From<&'static str> for Message {
    fn from(s: &'static str) -> Message {
        Message::new().text(s)
    }
}

impl From<String> for Message {
    fn from(s: String) -> Message {
        Message::new().text(s)
    }
}

/// A number for a message: plain where short, else in e-notation with at most 6 digits (never a
/// 301-digit decimal).
pub fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let trim = |m: &str| -> String {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m.to_string()
        }
    };
    if (1e-4..1e7).contains(&x.abs()) {
        // Six significant digits, plain.
        let decimals = (5 - x.abs().log10().floor() as i32).max(0) as usize;
        return trim(&format!("{x:.decimals$}"));
    }
    let e = format!("{x:.5e}");
    match e.split_once('e') {
        Some((m, p)) => format!("{}e{p}", trim(m)),
        None => e,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_takes_each_front_ends_names_for_its_keys_alone() {
        let m = Message::new()
            .key("nx")
            .text(" and nx_min; ")
            .phrase("load_axis=linear", "the linear load axis");
        assert_eq!(m.to_string(), "nx and nx_min; the linear load axis");
        let flags = |k: &str| match k {
            "nx" => Some("--nx"),
            "load_axis=linear" => Some("--load-axis linear"),
            _ => None,
        };
        assert_eq!(m.named(&flags), "--nx and nx_min; --load-axis linear");
        assert_eq!(m.keys().collect::<Vec<_>>(), ["nx", "load_axis=linear"]);
    }
}
