// Model file: the path does not exist.
stickslip::model!(file = "tests/ui/models/no_such_model.ssm");

fn main() {}
