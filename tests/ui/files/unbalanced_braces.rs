// Model file: the oscillator's brace is never closed, so the file
// cannot even be tokenized.
stickslip::model!(file = "tests/ui/models/unbalanced_braces.ssm");

fn main() {}
