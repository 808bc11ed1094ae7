// Parameters equal after NFC in a model file (the file is not normalised by rustc: the generator normalises it).
stickslip::model!(file = "tests/ui/models/nfc_twins.ssm");

fn main() {}
