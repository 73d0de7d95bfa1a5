//! The GIfTI reader: `read_mesh_from_bytes` and `read_raw_mesh_from_bytes` agree, and a
//! raw read repairs without breaking the repair's promises.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    conformap_fuzz::read(data, conformap_io::Format::Gifti);
});
