// Model file: nothing covers v > Sigma2; no boundary lies above the gap,
// so the error points at the model's name.
stickslip::model!(file = "tests/ui/models/gap_above.ssm");

fn main() {}
