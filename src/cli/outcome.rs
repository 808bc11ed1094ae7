//! What a subcommand prints (stdout, notes on stderr, a failure), and the
//! output of a motion: its report, CSV and figure.

use std::process::ExitCode;

use stickslip::output::figure::orbit;
use stickslip::output::history::History;
use stickslip::output::report::Report;

use super::args::OutputArgs;
use super::error::CliError;

/// Samples per forcing period in `--csv` and `--plot`.
pub const SAMPLES_PER_PERIOD: usize = 400;

/// What a subcommand prints, notes on stderr, and whether it failed.
pub struct Outcome {
    /// Printed on stdout, ended by a newline.
    pub stdout: String,
    /// One line each on stderr, after the output.
    pub notes: Vec<String>,
    /// A result that is no answer (e.g. Newton did not converge): printed
    /// last as `error: ...`, exit status 1.
    pub failure: Option<String>,
}

impl Outcome {
    /// `stdout`, no notes, success.
    pub fn ok(stdout: String) -> Self {
        Self {
            stdout,
            notes: Vec::new(),
            failure: None,
        }
    }

    /// Print it; the exit status.
    pub fn print(self) -> ExitCode {
        use std::io::Write;
        let mut out = self.stdout;
        if !out.ends_with('\n') {
            out.push('\n');
        }
        // A reader that stops early (`stickslip ... | head`) closes the pipe:
        // that is no error of ours, and no reason to panic.
        let mut stdout = std::io::stdout().lock();
        if let Err(e) = stdout
            .write_all(out.as_bytes())
            .and_then(|()| stdout.flush())
        {
            if e.kind() != std::io::ErrorKind::BrokenPipe {
                eprintln!("error: cannot write the output: {e}");
                return ExitCode::FAILURE;
            }
        }
        for note in &self.notes {
            eprintln!("{note}");
        }
        match self.failure {
            None => ExitCode::SUCCESS,
            Some(reason) => {
                eprintln!("error: {reason}");
                ExitCode::FAILURE
            }
        }
    }

    /// Add `report` (text after what `self` already says, or JSON alone);
    /// for a motion, write its `history` as CSV and figure (titled `title`)
    /// where `output` asks.
    pub fn with_report(
        mut self,
        report: &Report,
        history: impl FnOnce() -> Result<History, CliError>,
        title: String,
        output: &OutputArgs,
    ) -> Result<Self, CliError> {
        self.stdout = if output.json {
            report.to_json()
        } else {
            format!("{}{report}", self.stdout)
        };
        if output.csv.is_some() || output.plot.is_some() {
            if report.is_motion() {
                let history = history()?;
                if let Some(path) = &output.csv {
                    std::fs::write(path, history.to_csv()).map_err(|source| CliError::Write {
                        path: path.clone(),
                        source,
                    })?;
                    self.notes.push(format!("wrote {}", path.display()));
                }
                if let Some(path) = &output.plot {
                    orbit::plot(&history, &title, path).map_err(CliError::Figure)?;
                    self.notes.push(format!("wrote {}", path.display()));
                }
            } else {
                self.notes
                    .push("no CSV or figure written: there is no motion to show".to_string());
            }
        }
        self.failure = report.failure();
        Ok(self)
    }
}
