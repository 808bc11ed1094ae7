// A model file with a friction jump at a non-stick boundary: the error is at
// the path literal and its message names `file:line:col` in the model file.
stickslip::model!(file = "tests/ui/models/bad_jump.ssm");

fn main() {}
