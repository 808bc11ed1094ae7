// A model file with two errors: both are listed, each with `file:line:col`.
stickslip::model!(file = "tests/ui/models/bad_names.ssm");

fn main() {}
