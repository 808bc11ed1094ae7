// `r#self` is not an identifier: the model file does not tokenize.
stickslip::model!(file = "tests/ui/models/raw_self.ssm");

fn main() {}
