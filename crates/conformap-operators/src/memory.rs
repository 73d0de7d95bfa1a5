//! Peak-memory model of a map that factors a Laplacian block, and the machine's memory.
//!
//! The solvers of conformap (disk maps, holes, sphere maps, 1-forms) are dominated by one
//! sparse Cholesky factor of a Laplacian block, the Laplacian itself, and (for CCEM and the
//! circle-domain polish) a dense boundary-sized Schur complement. [`PeakMemory`] adds these
//! up from the mesh's sizes, so that a caller can refuse a run that would not fit *before*
//! anything is assembled; the disk crate adds its methods' own terms on top.
//!
//! Calibration (release and debug binaries, `VmHWM`): the estimate is 1.3× to 1.5× the
//! measured peak of CCEM-QN and the harmonic map on the disk meshes of `../shared/meshes`
//! (4.5k to 130k vertices) and on a generated 2M-face grid (peak 1.42 GiB);
//! `memory_estimate_bounds_the_measured_peak` in the CLI's `tests/resources.rs`
//! re-measures it.

/// Fixed cost of the process (binary, allocator, threads). Measured: 5.4 MiB in all for
/// woody.obj (694 vertices) with the release binary; a debug binary's code pages and the
/// two rayon workers' stacks add about 2 MiB (spothead.obj: 13.8–14.5 MiB peak in debug
/// runs), so 10 MiB.
pub const BASE_BYTES: f64 = 10.0 * 1048576.0;

/// Bytes per vertex for everything but the factor and the Laplacian's entries: mesh,
/// half-edges, assembly, intrinsic Delaunay triangulation, blocks, maps, metrics.
pub const BYTES_PER_VERTEX: f64 = 500.0;

/// Bytes per `n log₂ n` (n = factored vertices) for the Cholesky factor under AMD
/// (measured nnz(L) = 3.4 n log₂ n on hand.obj, 4.1 on igea_open.obj; 8-byte values plus
/// structure and workspace) and what grows with it.
pub const FACTOR_BYTES_PER_NLOGN: f64 = 60.0;

/// At most this much for a dense boundary-sized block (CCEM's Schur complement is formed
/// only below this size; above it the solvers work with products).
pub const DENSE_MAX_BYTES: f64 = 512.0 * 1048576.0;

/// The peak resident memory of a solve, built from the mesh's sizes.
///
/// # Examples
/// ```
/// use conformap_operators::PeakMemory;
/// // a 100k-vertex disk with 1,000 boundary vertices, with and without a dense Schur block
/// let sparse = PeakMemory::laplacian(100_000, 300_000, 99_000);
/// let dense = sparse.with_dense_block(1_000);
/// assert!(dense.bytes() > sparse.bytes());
/// assert!(sparse.bytes() > 100 * 1048576 && sparse.bytes() < 1024 * 1048576);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeakMemory {
    linear: f64,
    factor: f64,
    dense: f64,
    extra: f64,
}

impl PeakMemory {
    /// A solve on a mesh with `vertices` vertices and `edges` edges that factors a
    /// Laplacian block of `factored` vertices: the process, [`BYTES_PER_VERTEX`] per
    /// vertex, the Laplacian's `vertices + 2 edges` entries (16 bytes each, and as many
    /// again for the analysed pattern held beside the assembly), and the factor's fill,
    /// which grows like `n log n` on surface meshes ([`FACTOR_BYTES_PER_NLOGN`]).
    pub fn laplacian(vertices: usize, edges: usize, factored: usize) -> Self {
        let n = vertices as f64;
        let laplacian_nnz = n + 2.0 * edges as f64;
        let interior = factored.max(2) as f64;
        Self {
            linear: BASE_BYTES + BYTES_PER_VERTEX * n + 2.0 * 16.0 * laplacian_nnz,
            factor: FACTOR_BYTES_PER_NLOGN * interior * interior.log2(),
            dense: 0.0,
            extra: 0.0,
        }
    }

    /// Adds a dense `n × n` block of f64 (at most [`DENSE_MAX_BYTES`]).
    pub fn with_dense_block(mut self, n: usize) -> Self {
        self.dense = (8.0 * (n as f64).powi(2)).min(DENSE_MAX_BYTES);
        self
    }

    /// Adds `bytes` per vertex of `vertices` (a method's own arrays).
    pub fn with_per_vertex(mut self, vertices: usize, bytes: f64) -> Self {
        self.extra += bytes * vertices as f64;
        self
    }

    /// The estimate, in bytes.
    pub fn bytes(&self) -> u64 {
        (self.linear + self.factor + self.dense + self.extra) as u64
    }
}

/// The memory this process may still use: `MemAvailable` of `/proc/meminfo`, lowered to
/// what the cgroup (v2) limit leaves, if there is one, with the name of the source.
/// `None` where unknown (no check is then possible).
pub fn available_memory() -> Option<(u64, &'static str)> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let avail = kib_field(&meminfo, "MemAvailable:")?.saturating_mul(1024);
    let read = |p: &str| -> Option<u64> { std::fs::read_to_string(p).ok()?.trim().parse().ok() };
    match (
        read("/sys/fs/cgroup/memory.max"),
        read("/sys/fs/cgroup/memory.current"),
    ) {
        (Some(max), Some(current)) if max.saturating_sub(current) < avail => {
            Some((max.saturating_sub(current), "cgroup memory.max"))
        }
        _ => Some((avail, "MemAvailable")),
    }
}

/// Peak resident set size of this process so far (Linux `VmHWM`), `None` where unknown.
pub fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    Some(kib_field(&status, "VmHWM:")?.saturating_mul(1024))
}

/// The number of KiB after `key` in a `/proc` status-style text.
fn kib_field(text: &str, key: &str) -> Option<u64> {
    text.lines()
        .find_map(|l| l.strip_prefix(key))?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_matches_its_terms() {
        let m = PeakMemory::laplacian(1000, 3000, 900);
        let expected = BASE_BYTES
            + BYTES_PER_VERTEX * 1000.0
            + 32.0 * 7000.0
            + FACTOR_BYTES_PER_NLOGN * 900.0 * 900f64.log2();
        assert_eq!(m.bytes(), expected as u64);
        let capped = m.with_dense_block(1 << 20);
        assert_eq!(capped.bytes(), (expected + DENSE_MAX_BYTES) as u64);
        let extra = m.with_per_vertex(1000, 1000.0);
        assert_eq!(extra.bytes(), (expected + 1e6) as u64);
    }

    #[test]
    fn proc_fields_parse() {
        assert_eq!(kib_field("A: 1\nVmHWM:\t  2048 kB\n", "VmHWM:"), Some(2048));
        assert_eq!(kib_field("A: 1\n", "VmHWM:"), None);
        if cfg!(target_os = "linux") {
            assert!(peak_rss_bytes().is_some_and(|b| b > 0));
            assert!(available_memory().is_some_and(|(b, _)| b > 0));
        }
    }
}
