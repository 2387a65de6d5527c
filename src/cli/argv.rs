//! The command line as clap reads it: signed numbers joined to their options, and help texts
//! that depend on the command.
//!
//! clap takes `-1e-3` after `--min-separation` for short flags (`-1`, `-e`, ...): its test of a
//! negative number (`allow_negative_numbers`) accepts digits, one dot and an unsigned exponent,
//! so `-1e-3` and `-.5` fail it. `allow_hyphen_values` would take them, but also takes a
//! following `--json` as the value of an option whose value was left out, and every later flag
//! as a value of an option with several. A token that reads as a negative number can never be a
//! flag (no flag is named by a digit), so the one fix for every command is here: after an option
//! that takes a value, such a token is given to it as `--option=VALUE`, which clap always reads
//! as a value.

use clap::Command;
use std::ffi::OsString;

/// Whether `s` is a negative number, or a comma-separated list starting with one: `-1e-3`,
/// `-.5`, `-2,3` (not `-inf`, `-nan`: names are not numbers here).
fn is_negative_number(s: &str) -> bool {
    let Some(rest) = s.strip_prefix('-') else {
        return false;
    };
    let first = rest.split(',').next().unwrap_or_default();
    first.starts_with(|c: char| c.is_ascii_digit() || c == '.') && first.parse::<f64>().is_ok()
}

/// The long option `token` names in `cmd` (`--name`, no `=VALUE`), if it takes a value; and
/// whether it takes several.
fn valued_option(cmd: &Command, token: &str) -> Option<bool> {
    let name = token.strip_prefix("--").filter(|n| !n.contains('='))?;
    let arg = cmd.get_arguments().find(|a| {
        a.get_long() == Some(name) || a.get_all_aliases().is_some_and(|v| v.contains(&name))
    })?;
    let takes =
        arg.get_num_args().is_some_and(|n| n.takes_values()) || arg.get_action().takes_values();
    takes.then(|| arg.get_num_args().is_some_and(|n| n.max_values() > 1))
}

/// `args` (the program's name first) with each negative number that follows an option taking
/// a value joined to it: `--load -1e-3` becomes `--load=-1e-3`; for an option of several
/// values, `--lambda 1 -1e-3 2` becomes `--lambda 1 --lambda=-1e-3 --lambda=2`.
pub(crate) fn join_negative_values(cmd: &Command, args: Vec<OsString>) -> Vec<OsString> {
    let mut out: Vec<OsString> = Vec::with_capacity(args.len());
    let mut sub: Option<&Command> = None;
    // The option awaiting values: its token, whether it takes several, and whether its
    // values are now given as `--option=VALUE` each.
    let mut pending: Option<(String, bool, bool)> = None;
    let mut rest = args.into_iter();
    for a in rest.by_ref() {
        let Some(s) = a.to_str().map(str::to_owned) else {
            pending = None;
            out.push(a);
            continue;
        };
        if s == "--" {
            out.push(a);
            break;
        }
        let Some(c) = sub else {
            if !out.is_empty() {
                sub = cmd.find_subcommand(&s);
            }
            out.push(a);
            continue;
        };
        match pending.take() {
            Some((flag, several, joined))
                if is_negative_number(&s) || (joined && !s.starts_with('-')) =>
            {
                let value: OsString = format!("{flag}={s}").into();
                let first = out
                    .last()
                    .is_some_and(|l| l.to_str() == Some(flag.as_str()));
                if first {
                    *out.last_mut().expect("the option") = value;
                } else {
                    out.push(value);
                }
                pending = several.then_some((flag, true, true));
                continue;
            }
            Some((flag, true, false)) if !s.starts_with('-') => {
                pending = Some((flag, true, false));
            }
            _ => {
                if let Some(several) = valued_option(c, &s) {
                    pending = Some((s.clone(), several, false));
                }
            }
        }
        out.push(a);
    }
    out.extend(rest);
    out
}

/// The commands whose figure is two journal columns wide by default (the rough cycle: two
/// panels side by side); every other figure is one column.
const WIDE_FIGURES: &[&str] = &["rough"];

/// The printed width of `command`'s figure where neither `--width-mm` nor `--double-column` is
/// given.
pub(crate) fn figure_width_mm(command: &str) -> f64 {
    if WIDE_FIGURES.contains(&command) {
        crate::render::DOUBLE_COLUMN_MM
    } else {
        crate::render::SINGLE_COLUMN_MM
    }
}

/// The command line's definition, each command's `--width-mm` help naming its own default.
pub(crate) fn command() -> Command {
    let cmd = <super::Cli as clap::CommandFactory>::command();
    let figures: Vec<String> = cmd
        .get_subcommands()
        .filter(|s| s.get_arguments().any(|a| a.get_id() == "width_mm"))
        .map(|s| s.get_name().to_string())
        .collect();
    figures.iter().fold(cmd, |cmd, name| {
        let mm = figure_width_mm(name);
        let columns = if mm == crate::render::SINGLE_COLUMN_MM {
            "one journal column"
        } else {
            "two journal columns"
        };
        let help = format!(
            "Printed width in millimetres; fonts are 7-9.5 pt at this width [default: {}, {columns}]",
            crate::physics::domain::short(mm)
        );
        cmd.mut_subcommand(name, |s| s.mut_arg("width_mm", |a| a.help(help)))
    })
}
