//! The disk pipeline on small meshes: validation (or repair), `DiskProblem`, CEM or the
//! harmonic map, metrics. See `conformap_fuzz::disk` for how the bytes build the mesh.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    conformap_fuzz::disk(data);
});
