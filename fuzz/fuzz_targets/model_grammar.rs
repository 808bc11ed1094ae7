//! Models built from the language's grammar (well-formed and slightly
//! mutated, see `fuzz/grammar.rs`) through `check_source`, the entry point of
//! `stickslip check`, `build.rs` and `model!(file = ...)`: a located report or
//! code that parses as Rust, never a panic or a hang.
//!
//! Run with `--no-cfg-fuzzing` (as `model_source`): under `cfg(fuzzing)`
//! proc-macro2 drops span locations.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../harness.rs"]
mod harness;

#[path = "../grammar.rs"]
mod grammar;

fuzz_target!(|data: &[u8]| {
    grammar::model_grammar(data);
    // Each input as in a fresh build script (see `model_source`).
    proc_macro2::extra::invalidate_current_thread_spans();
});
