//! The `stickslip` command-line tool.
#![forbid(unsafe_code)]

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use stickslip::{describe, models, Model, ModelVisitor, ParamSet};

/// Exact periodic motions of friction oscillators, from model files.
#[derive(Parser)]
#[command(name = "stickslip", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the compiled-in models and their scenes.
    Models,
    /// Print a model's domains, boundaries and generated mappings.
    Describe {
        /// Model name (`paper`), or `model::scene`.
        #[arg(long, default_value = "paper")]
        model: String,
        /// Parameter values, e.g. `--set W=3.7,Q0=70`.
        #[arg(long, value_delimiter = ',')]
        set: Vec<String>,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

/// Parse `NAME=VALUE` pairs.
fn parse_assignments(items: &[String]) -> Result<Vec<(String, f64)>, String> {
    items
        .iter()
        .map(|item| {
            let (name, value) = item
                .split_once('=')
                .ok_or_else(|| format!("`{item}`: expected NAME=VALUE"))?;
            let v: f64 = value
                .trim()
                .parse()
                .map_err(|_| format!("`{item}`: `{value}` is not a number"))?;
            Ok((name.trim().to_string(), v))
        })
        .collect()
}

struct Describe {
    set: Vec<(String, f64)>,
    json: bool,
}

impl ModelVisitor for Describe {
    type Output = Result<String, String>;
    fn visit<M: Model>(self) -> Self::Output {
        let pairs: Vec<(&str, f64)> = self.set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let p = M::Params::from_pairs(M::INFO, &pairs).map_err(|e| e.to_string())?;
        let d = describe::describe::<M>(&p);
        if self.json {
            serde_json::to_string_pretty(&d).map_err(|e| e.to_string())
        } else {
            Ok(d.to_string())
        }
    }
}

fn run(cli: Cli) -> Result<String, String> {
    match cli.command {
        Command::Models => {
            let mut out = String::new();
            for info in models::ALL {
                let free: Vec<&str> = info.free.iter().map(|&i| info.params[i].name).collect();
                let first_doc = info.doc.lines().next().unwrap_or("");
                out.push_str(&format!(
                    "{:<20} {} domains, {} boundaries, {} mappings; free: {}\n",
                    info.name,
                    info.domains.len(),
                    info.boundaries.len(),
                    info.mapping_names().len(),
                    free.join(", ")
                ));
                if info.scene.is_none() && !first_doc.is_empty() {
                    out.push_str(&format!("{:<20} {}\n", "", first_doc));
                }
            }
            Ok(out)
        }
        Command::Describe { model, set, json } => {
            let set = parse_assignments(&set)?;
            models::visit(&model, Describe { set, json }).unwrap_or_else(|| {
                let names: Vec<&str> = models::ALL.iter().map(|i| i.name).collect();
                Err(format!(
                    "unknown model `{model}`; compiled-in: {}",
                    names.join(", ")
                ))
            })
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(out) => {
            print!("{out}");
            if !out.ends_with('\n') {
                println!();
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
