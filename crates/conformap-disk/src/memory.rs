//! Peak-memory estimates of the disk methods, before anything is assembled: the
//! factorization model of [`conformap_operators::PeakMemory`] plus what each method keeps.

use conformap_mesh::TriMesh;
use conformap_operators::PeakMemory;

use crate::DiskMethod;

/// What CEM keeps beyond CCEM and the harmonic map, per vertex, including the repair of a
/// folded CEM map (measured: 490 on spothead.obj, 520 on hand.obj, 680 on igea_open.obj;
/// maze.obj, whose CEM map folds and is repaired, needed 720).
pub const CEM_EXTRA_BYTES_PER_VERTEX: f64 = 1000.0;

impl DiskMethod {
    /// Estimated peak resident memory (bytes) of this method on `mesh` (one boundary
    /// loop): the Laplacian and the factor of its interior block, and for CCEM (which may
    /// form it) the dense Schur complement of the boundary, `8 n_B²` bytes capped at
    /// [`conformap_operators::memory::DENSE_MAX_BYTES`].
    ///
    /// # Examples
    /// ```
    /// use conformap_disk::DiskMethod;
    /// # let mesh = conformap_testkit::flat_disk(10, 40);
    /// let ccem = DiskMethod::CcemQn.peak_bytes(&mesh);
    /// let harmonic = DiskMethod::Harmonic.peak_bytes(&mesh);
    /// assert!(ccem > harmonic && harmonic > 10 << 20);
    /// ```
    pub fn peak_bytes(self, mesh: &TriMesh) -> u64 {
        let boundary = longest_loop(mesh);
        let base = PeakMemory::laplacian(
            mesh.num_vertices(),
            mesh.num_edges(),
            mesh.num_vertices().saturating_sub(boundary),
        );
        match self {
            Self::Ccem | Self::CcemQn => base.with_dense_block(boundary),
            Self::Cem => base.with_per_vertex(mesh.num_vertices(), CEM_EXTRA_BYTES_PER_VERTEX),
            _ => base,
        }
        .bytes()
    }
}

/// Estimated peak resident memory (bytes) of [`crate::koebe`] on `mesh` (several boundary
/// loops): the first CEM map as [`DiskMethod::Cem`] estimates it, and the circle-domain
/// polish's dense Schur complement of every boundary vertex.
pub fn koebe_peak_bytes(mesh: &TriMesh) -> u64 {
    let boundary: usize = mesh.boundary_loops().iter().map(Vec::len).sum();
    let cem = DiskMethod::Cem.peak_bytes(mesh);
    let dense = PeakMemory::laplacian(
        mesh.num_vertices(),
        mesh.num_edges(),
        mesh.num_vertices().saturating_sub(boundary),
    )
    .with_dense_block(boundary)
    .bytes();
    cem.max(dense)
}

fn longest_loop(mesh: &TriMesh) -> usize {
    mesh.boundary_loops()
        .iter()
        .map(Vec::len)
        .max()
        .unwrap_or(0)
}
