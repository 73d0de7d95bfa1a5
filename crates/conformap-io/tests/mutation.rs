//! Seeded mutation smoke test: thousands of corrupted OBJ and GLB inputs must give `Ok` or
//! `Err`, never a panic (the fuzzer's job in miniature; a fixed seed keeps it reproducible).
//! `CONFORMAP_MUTATIONS=N` multiplies the number of mutants for a longer local run.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::fixture;
use conformap_io::{read_mesh_from_bytes, Format};
// xorshift64*: small, deterministic, good enough to pick mutations
use conformap_testkit::XorShift64Star as Rng;

fn scale() -> usize {
    std::env::var("CONFORMAP_MUTATIONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
}

/// Overwrites, inserts or deletes a few bytes, preferring "interesting" ones.
fn mutate(rng: &mut Rng, input: &[u8], window: usize) -> Vec<u8> {
    const INTERESTING: &[u8] = b"0-1/ \n.ef9vtnx\xff\x00";
    let mut out = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(out.len().min(window));
        let byte = if rng.below(2) == 0 {
            INTERESTING[rng.below(INTERESTING.len())]
        } else {
            rng.next_u64() as u8
        };
        match rng.below(3) {
            0 if at < out.len() => out[at] = byte,
            1 => out.insert(at, byte),
            _ if at < out.len() => {
                out.remove(at);
            }
            _ => out.push(byte),
        }
    }
    out
}

#[test]
fn corrupted_obj_never_panics() {
    let small = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n\
                  f 1/1/1 2/2/1 3/3/1\nf -4/-3 -2/-1 -1/-1\n";
    let mut rng = Rng(0x00c0_ffee_1234_5678);
    let mut ok = 0;
    for _ in 0..3000 * scale() {
        let bytes = mutate(&mut rng, small, usize::MAX);
        ok += usize::from(read_mesh_from_bytes(&bytes, Format::Obj).is_ok());
    }
    assert!(ok > 0, "some mutants should still be valid");
}

#[test]
fn corrupted_glb_never_panics() {
    let glb = std::fs::read(fixture("gltf/woody.glb")).unwrap();
    // the header and JSON chunk are where the structure is; mutate those
    let json_end = 20 + u32::from_le_bytes([glb[12], glb[13], glb[14], glb[15]]) as usize;
    let mut rng = Rng(0x0bad_5eed_8765_4321);
    for _ in 0..400 * scale() {
        let bytes = mutate(&mut rng, &glb, json_end);
        let _ = read_mesh_from_bytes(&bytes, Format::Glb);
    }
}
