// Model file: a boundary velocity that depends on `v`.
stickslip::model!(file = "tests/ui/models/v_in_boundary.ssm");

fn main() {}
