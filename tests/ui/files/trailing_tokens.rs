// Model file: tokens after the model's closing brace.
stickslip::model!(file = "tests/ui/models/trailing_tokens.ssm");

fn main() {}
