//! Arbitrary bytes as a model file: tokenizer, parser, checker and generator
//! must answer (generated code or a located report), never panic or hang.
//!
//! Run with `--no-cfg-fuzzing`: under `cfg(fuzzing)` proc-macro2 drops span
//! locations, so the reports (and their rendering) would not be those of a
//! real build.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../harness.rs"]
mod harness;

fuzz_target!(|data: &[u8]| {
    harness::model_source(data);
    // Each input as in a fresh build script: proc-macro2's source map (which
    // gives spans their lines) would otherwise keep every input ever parsed.
    proc_macro2::extra::invalidate_current_thread_spans();
});
