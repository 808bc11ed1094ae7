// A model file with CRLF line ends and a tab: lines and columns hold
stickslip::model!(file = "tests/ui/models/crlf_tabs.ssm");

fn main() {}
