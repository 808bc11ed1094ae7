// A model file starting with a UTF-8 byte order mark: columns are not
stickslip::model!(file = "tests/ui/models/bom.ssm");

fn main() {}
