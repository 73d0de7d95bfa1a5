//! The map-file (`PARAM`) reader of `metrics` and `mobius`: never a panic; an accepted map
//! matches the mesh, a refused one is bad input with a hint.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    conformap_fuzz::param(data);
});
