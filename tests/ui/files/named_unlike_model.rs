// The file `misnamed.ssm` holds `model other`: located at the model's name.
stickslip::model!(file = "tests/ui/models/misnamed.ssm");

fn main() {}
