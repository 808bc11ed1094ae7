// Scenes equal after NFC in a model file.
stickslip::model!(file = "tests/ui/models/scene_nfc_twins.ssm");

fn main() {}
