// Model file: syntax errors in three items; all are reported.
stickslip::model!(file = "tests/ui/models/syntax_errors.ssm");

fn main() {}
