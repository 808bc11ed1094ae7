//! `stickslip describe`: a model's domains, boundaries and generated mappings.

use clap::Args;
use stickslip::output::describe::describe;
use stickslip::Model;

use super::args::{with_model, Assignments, ModelArgs, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `describe`.
#[derive(Args)]
pub struct DescribeArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// Parameter values, e.g. `--set W=3.7,Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// The description, as a table or JSON.
pub fn run(args: DescribeArgs) -> Result<Outcome, CliError> {
    let set = Assignments::parse(&args.set)?;
    let json = args.json;
    with_model(&args.model.lookup("paper"), Describe { set, json }).map(Outcome::ok)
}

struct Describe {
    set: Assignments,
    json: bool,
}

impl WithModel for Describe {
    type Output = String;
    fn run<M: Model>(self, base: M::Params) -> Result<String, CliError> {
        let p = self.set.params::<M>(base)?;
        let d = describe::<M>(&p);
        if self.json {
            Ok(serde_json::to_string_pretty(&d)?)
        } else {
            Ok(d.to_string())
        }
    }
}
