//! The `stickslip` command-line tool (the subcommands are in `cli/`).
#![forbid(unsafe_code)]

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    match cli::Cli::parse().run() {
        Ok(status) => status,
        Err(e) => {
            // A rejected model file's report is `stickslip check`'s, each
            // error already headed `error:`.
            match e.is_report() {
                true => eprintln!("{e}"),
                false => eprintln!("error: {e}"),
            }
            ExitCode::FAILURE
        }
    }
}
