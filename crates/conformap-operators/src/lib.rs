//! Discrete operators for conformap: cotangent Laplacian, its interior/boundary blocks, areas, angles, and the sparse Cholesky facade.
