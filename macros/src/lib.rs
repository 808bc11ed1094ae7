//! `stickslip::model!`: a thin proc-macro over `stickslip-codegen`.
