//! Bytes → a sequence of public API calls on worlds and simulations with hostile
//! values (the interpreter is shared with `ars-core/tests/random_api_sequences.rs`).
//! Any abort, crash, hang or panic is a bug of the safe API.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../ars-core/tests/api_sequences/mod.rs"]
mod api_sequences;

fuzz_target!(|data: &[u8]| {
    // libFuzzer's panic hook aborts, so hooks that panic (contained by the simulation)
    // are left out here; the seeded test covers them.
    api_sequences::Harness::run(data, 300, false);
});
