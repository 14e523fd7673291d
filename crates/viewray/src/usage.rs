//! What is typed before clap reads it, and how a usage error reads: several values after
//! one option, numbers separated by spaces where commas are wanted, and the one `error:`
//! line that ends by pointing to the command's help.

use std::ffi::OsString;
use std::fmt::Display;
use std::process::ExitCode;

/// Exit code for bad input or usage.
pub(crate) const EXIT_BAD_INPUT: u8 = 2;

/// Options that take one value each time and may be followed by several:
/// `--point 1,2,3 -4,5,6` means `--point 1,2,3 --point -4,5,6`.
const REPEATABLE: [&str; 2] = ["--point", "--pixel"];

/// Rewrites `--point A B` as `--point A --point B`, so that several values may follow one
/// option while values starting with `-` (negative coordinates) are still values.
pub(crate) fn expand_repeated_values(args: impl IntoIterator<Item = OsString>) -> Vec<OsString> {
    let mut out = Vec::new();
    let mut repeating: Option<OsString> = None;
    let mut just_saw_option = false;
    for arg in args {
        let text = arg.to_str().unwrap_or_default();
        let looks_like_value = !text.is_empty()
            && text.contains(',')
            && text
                .chars()
                .all(|c| c.is_ascii_digit() || ".,-+eE ".contains(c));
        if REPEATABLE.contains(&text) {
            repeating = Some(arg.clone());
            just_saw_option = true;
            out.push(arg);
            continue;
        }
        if let Some(option) = &repeating {
            if looks_like_value {
                if !just_saw_option {
                    out.push(option.clone());
                }
                just_saw_option = false;
                out.push(arg);
                continue;
            }
            repeating = None;
        }
        just_saw_option = false;
        out.push(arg);
    }
    out
}

/// The options whose value is several numbers joined by commas, the format each takes
/// and how many numbers that is.
const NUMBER_LIST_OPTIONS: [(&str, &str, usize); 8] = [
    ("--eye", "X,Y,Z", 3),
    ("--view", "X,Y,Z", 3),
    ("--look-at", "X,Y,Z", 3),
    ("--up", "X,Y,Z", 3),
    ("--point", "X,Y,Z", 3),
    ("--pixel", "ROW,COL", 2),
    ("--sample", "OX,OY", 2),
    ("--lens", "LX,LY", 2),
];

/// The options of `viewray frame` that describe a camera by hand.
const FRAME_OPTIONS: [&str; 4] = ["--eye", "--view", "--look-at", "--up"];

/// `(see `viewray COMMAND --help`)`, the pointer every usage error ends with.
pub(crate) fn see_help(command: Option<&str>) -> String {
    match command {
        Some(command) => format!("(see `viewray {command} --help`)"),
        None => "(see `viewray --help`)".to_owned(),
    }
}

/// A usage error of `viewray COMMAND`: the message and where the help is.
pub(crate) fn usage_error(command: &str, message: impl Display) -> anyhow::Error {
    anyhow::anyhow!("{message} {}", see_help(Some(command)))
}

/// Finds numbers separated by spaces where an option wants them joined by commas
/// (`--eye 1 2 3`, `--pixel 1 1`), which clap would report as "unexpected argument
/// '2'". Returns the message that says the format and what to write instead.
pub(crate) fn spaced_number_list(args: &[OsString]) -> Option<String> {
    let texts: Vec<&str> = args.iter().map(|a| a.to_str().unwrap_or("")).collect();
    for (index, &arg) in texts.iter().enumerate() {
        let Some(&(option, format, count)) = NUMBER_LIST_OPTIONS.iter().find(|o| o.0 == arg) else {
            continue;
        };
        // Take the arguments after the option while they are numbers (or pieces of a
        // list, like `1,`) and fewer than the option needs.
        let mut numbers: Vec<&str> = Vec::new();
        let mut taken = 0;
        for next in &texts[index + 1..] {
            let pieces: Vec<&str> = next.split(',').filter(|p| !p.trim().is_empty()).collect();
            let numeric =
                !pieces.is_empty() && pieces.iter().all(|p| p.trim().parse::<f64>().is_ok());
            if !numeric || numbers.len() + pieces.len() > count {
                break;
            }
            numbers.extend(pieces);
            taken += 1;
            if numbers.len() == count {
                break;
            }
        }
        if taken > 1 {
            let typed = texts[index + 1..=index + taken].join(" ");
            return Some(format!(
                "{option} takes {format}, {count} numbers joined by commas without spaces: \
                 write `{option} {}`, not `{option} {typed}`",
                numbers.join(",")
            ));
        }
    }
    None
}

/// Prints a clap error: help and version as clap formats them, usage errors as one line
/// `error: ...` pointing to the help of `command` (the subcommand named, if any), exit
/// code 2.
pub(crate) fn report_usage_error(error: &clap::Error, command: Option<&str>) -> ExitCode {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let _ = error.print();
        return if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            ExitCode::from(EXIT_BAD_INPUT)
        } else {
            ExitCode::SUCCESS
        };
    }
    let help = see_help(command);
    let invalid = match error.get(ContextKind::InvalidArg) {
        Some(ContextValue::String(arg)) => Some(arg.as_str()),
        _ => None,
    };
    // `viewray rays --eye ..`: the camera comes from the scene; clap's tip ("use '--
    // --eye'") would send a student the wrong way.
    if error.kind() == ErrorKind::UnknownArgument
        && let (Some(command @ ("rays" | "project" | "trace")), Some(arg)) = (command, invalid)
        && let Some(option) = FRAME_OPTIONS.iter().find(|o| arg.starts_with(**o))
    {
        crate::style::error(format_args!(
            "`viewray {command}` takes its camera from a SCENE file, not from {option}; \
             `viewray frame --eye X,Y,Z --look-at X,Y,Z` prints the frame of eye, view and \
             up {help}"
        ));
        return ExitCode::from(EXIT_BAD_INPUT);
    }
    let text = error.render().to_string();
    let line: Vec<&str> = text
        .lines()
        .map(str::trim)
        .take_while(|line| !line.starts_with("Usage:") && !line.starts_with("For more information"))
        // clap suggests `-- --option` to pass an unknown option as a value: never what a
        // viewray user means.
        .filter(|line| !line.is_empty() && !line.starts_with("tip: to pass '"))
        .collect();
    let line = line.join(" ");
    let line = line.strip_prefix("error: ").unwrap_or(&line);
    crate::style::error(format_args!("{line} {help}"));
    ExitCode::from(EXIT_BAD_INPUT)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn os(args: &[&str]) -> Vec<OsString> {
        args.iter().map(OsString::from).collect()
    }

    fn expand(args: &[&str]) -> Vec<String> {
        expand_repeated_values(os(args))
            .into_iter()
            .map(|a| a.into_string().unwrap())
            .collect()
    }

    #[test]
    fn several_values_after_one_option_become_repeated_options() {
        assert_eq!(
            expand(&[
                "viewray",
                "project",
                "s.ron",
                "--point",
                "1,2,3",
                "-4,5,6",
                "--one-based"
            ]),
            [
                "viewray",
                "project",
                "s.ron",
                "--point",
                "1,2,3",
                "--point",
                "-4,5,6",
                "--one-based"
            ]
        );
        assert_eq!(
            expand(&["viewray", "rays", "--pixel", "0,0", "s.ron"]),
            ["viewray", "rays", "--pixel", "0,0", "s.ron"]
        );
    }

    #[track_caller]
    fn check_spaced(args: &[&str], expected: Option<&str>) {
        assert_eq!(spaced_number_list(&os(args)).as_deref(), expected);
    }

    #[test]
    fn numbers_separated_by_spaces_are_caught_with_the_fix() {
        check_spaced(
            &[
                "viewray", "frame", "--eye", "1", "2", "3", "--view", "0,0,-1",
            ],
            Some(
                "--eye takes X,Y,Z, 3 numbers joined by commas without spaces: write \
                 `--eye 1,2,3`, not `--eye 1 2 3`",
            ),
        );
        check_spaced(
            &["viewray", "rays", "s.ron", "--pixel", "1", "1"],
            Some(
                "--pixel takes ROW,COL, 2 numbers joined by commas without spaces: write \
                 `--pixel 1,1`, not `--pixel 1 1`",
            ),
        );
        check_spaced(
            &["viewray", "frame", "--eye", "1,", "-2,", "3"],
            Some(
                "--eye takes X,Y,Z, 3 numbers joined by commas without spaces: write \
                 `--eye 1,-2,3`, not `--eye 1, -2, 3`",
            ),
        );
        // Correct lists, several values after one option, and a lone wrong value (which
        // the option's own parser explains) are left alone.
        check_spaced(
            &["viewray", "project", "s", "--point", "1,2,3", "4,5,6"],
            None,
        );
        check_spaced(&["viewray", "rays", "s", "--pixel", "1,1", "2,2"], None);
        check_spaced(&["viewray", "frame", "--eye", "1", "--view", "0,0,1"], None);
        check_spaced(&["viewray", "rays", "--pixel", "1", "s.ron"], None);
    }
}
