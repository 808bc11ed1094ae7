// Model file: Rust source rather than a model.
stickslip::model!(file = "tests/ui/models/not_a_model.ssm");

fn main() {}
