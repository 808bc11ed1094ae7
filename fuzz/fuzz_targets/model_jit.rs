//! Models built from the language's grammar (`fuzz/grammar.rs`, as
//! `model_grammar`) loaded through the run-time back end, as `--model-file`
//! and `Model.from_source` load them: checked, compiled to machine code by
//! Cranelift, their functions called at points the input chooses (NaN and
//! infinities included). It must accept exactly what `check_source`
//! accepts, report the same errors, and never crash or hang.
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
    grammar::model_jit(data);
    // Each input as in a fresh process (see `model_source`).
    proc_macro2::extra::invalidate_current_thread_spans();
});
