//! Small meshes for the documentation examples (not part of the API).

/// Faces of a centre vertex with two hexagonal rings (1 + 6 + 12 vertices), vertex 0 the
/// centre, ring r starting at index `1 + 3 r (r − 1)`.
pub fn two_ring_faces() -> Vec<[u32; 3]> {
    let ring = |r: u32, k: u32| -> u32 {
        let start = 1 + 3 * r * (r - 1);
        start + k % (6 * r)
    };
    let mut f = Vec::new();
    for k in 0..6 {
        f.push([0, ring(1, k), ring(1, k + 1)]);
    }
    // ring 1 to ring 2: each of the 6 sides of ring 1 spans 2 segments of ring 2
    for s in 0..6u32 {
        let (a, b) = (ring(1, s), ring(1, s + 1));
        let (p, q, r) = (ring(2, 2 * s), ring(2, 2 * s + 1), ring(2, 2 * s + 2));
        f.push([a, p, q]);
        f.push([a, q, b]);
        f.push([b, q, r]);
    }
    f
}
