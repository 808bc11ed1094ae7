// A model file with a Latin-1 byte (0xE9) in a comment: located at its
stickslip::model!(file = "tests/ui/models/not_utf8.ssm");

fn main() {}
