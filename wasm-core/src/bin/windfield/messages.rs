//! The command line's own refusals of its flags: clap's errors begin `windfield: error:` like
//! every other, and a number that does not parse is named by its flag in a person's words
//! (`--width: must be a whole number (got "abc")`, not `invalid digit found in string`).
//! Help and version go to stdout as clap writes them.

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::Parser;
use std::process::ExitCode;

/// Parses the command line; on a refusal, prints it and returns the exit status (2, or 0 for
/// help and version).
pub fn parse_args<P: Parser>() -> Result<P, ExitCode> {
    P::try_parse().map_err(|e| {
        if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            eprintln!("windfield: error: a subcommand is needed\n\n{}", e.render());
        } else {
            eprintln!("windfield: error: {}", describe(&e));
        }
        ExitCode::from(2)
    })
}

/// A clap error in the project's words, without clap's leading `error: `.
pub fn describe(e: &clap::Error) -> String {
    if e.kind() == ErrorKind::ValueValidation {
        let text = |kind| match e.get(kind) {
            Some(ContextValue::String(s)) => Some(s.clone()),
            _ => None,
        };
        if let (Some(arg), Some(value)) = (
            text(ContextKind::InvalidArg),
            text(ContextKind::InvalidValue),
        ) {
            let flag = arg.split_whitespace().next().unwrap_or(&arg).to_string();
            let why = std::error::Error::source(e)
                .map(|s| s.to_string())
                .unwrap_or_default();
            return format!("{flag}: {} (got {value:?})", parse_failure(&why));
        }
    }
    let rendered = e.render().to_string();
    let rendered = rendered.trim_end();
    rendered
        .strip_prefix("error: ")
        .unwrap_or(rendered)
        .to_string()
}

/// What a number's parse failure means to the person who typed it.
fn parse_failure(why: &str) -> String {
    match why {
        "invalid digit found in string" | "cannot parse integer from empty string" => {
            "must be a whole number".into()
        }
        "number too large to fit in target type" | "number too small to fit in target type" => {
            "is a whole number too far from 0".into()
        }
        "invalid float literal" => "must be a number".into(),
        other => format!("cannot be read: {other}"),
    }
}
