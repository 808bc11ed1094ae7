// Model file: the laws meet at Sigma2 only at the default `k = 0.1`
// (`10 k^2 = k`), not for other values of `k`.
stickslip::model!(file = "tests/ui/models/continuity_at_defaults.ssm");

fn main() {}
