//! `stickslip reference` (hidden): the command-line reference of the guide,
//! in Markdown, generated from the parser's own definitions — each
//! subcommand's `--help` text as clap renders it, under its own heading.
//! `tests/cli_reference.rs` keeps `docs/guide/src/reference/cli.md` equal to
//! it.

use clap::{Command, CommandFactory};

use super::outcome::Outcome;
use super::Cli;

/// The reference as Markdown.
pub fn run() -> Outcome {
    Outcome::ok(markdown(Cli::command()))
}

fn markdown(mut cli: Command) -> String {
    let name = cli.get_name().to_string();
    let mut out = format!(
        "# Command-line reference\n\n\
         Generated from the command line's definitions by `{name} reference`\n\
         (`STICKSLIP_BLESS=1 cargo test --test cli_reference` rewrites this\n\
         page; a test fails when it differs from what the code prints).\n\
         Every subcommand also prints its page with `--help`.\n\n"
    );
    out.push_str(&format!("## `{name}`\n\n```text\n"));
    out.push_str(cli.render_long_help().to_string().trim_end());
    out.push_str("\n```\n");
    for sub in cli.get_subcommands_mut() {
        if sub.is_hide_set() || sub.get_name() == "help" {
            continue;
        }
        let title = format!("{name} {}", sub.get_name());
        let mut sub = sub.clone().bin_name(title.clone());
        out.push_str(&format!("\n## `{title}`\n\n```text\n"));
        out.push_str(sub.render_long_help().to_string().trim_end());
        out.push_str("\n```\n");
    }
    out
}
