//! The genus-g row: `conformap global`'s whole computation (read, `global_map`, the seamed
//! write) as a multiple of one factorization of the Laplacian it factors.
//!
//! "One factorization" is the fastest of the run's own symbolic + numeric factorization and
//! [`REFACTOR_RUNS`] more factorizations of the same reduced Laplacian, so a slow first
//! factorization (cold caches, the other tenant of the core) does not flatter the ratio.

use std::path::Path;
use std::time::Instant;

use conformap_global::{global_map, GlobalMapOptions};
use conformap_io::{write_mesh_with_corner_uv, CornerUv};
use conformap_operators::{cotan_laplacian, Cholesky, CholeskyOptions, LaplacianBlocks, Partition};

use crate::row::{row_struct, Row};

/// Extra factorizations of the reduced Laplacian for the yardstick.
pub const REFACTOR_RUNS: usize = 2;

row_struct! {
    /// One measured run.
    #[derive(Debug, Clone)]
    pub struct GlobalRow {
        vertices,
        faces,
        genus,
        read,
        factor,
        map,
        write,
        total,
        reference,
        peak_rss_mib,
        zeros,
        folds_outside,
    }
}

impl Row for GlobalRow {
    /// The whole run over one factorization.
    fn ratio(&self) -> f64 {
        self.total / self.reference
    }
}

impl GlobalRow {
    /// The Markdown header.
    pub fn header() -> String {
        "| mesh | V | F | g | read | factor (in map) | global_map | write | total | one factorization | total / factorization (min–max) | map / factorization | peak RSS MiB | zeros | folds outside zeros |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
            .to_string()
    }

    /// One Markdown row.
    pub fn to_markdown(&self, name: &str, lo: f64, hi: f64) -> String {
        let name = Path::new(name)
            .file_name()
            .map_or(name.to_string(), |n| n.to_string_lossy().to_string());
        format!(
            "| {name} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | **{:.2}** ({:.2}–{:.2}) | {:.2} | {:.0} | {:.0} | {:.0} |",
            self.vertices,
            self.faces,
            self.genus,
            self.read,
            self.factor,
            self.map,
            self.write,
            self.total,
            self.reference,
            self.ratio(),
            lo,
            hi,
            self.map / self.reference,
            self.peak_rss_mib,
            self.zeros,
            self.folds_outside,
        )
    }
}

/// Reads `path`, maps it by `global_map`, writes the seamed OBJ to a temporary file.
pub fn run_once(path: &Path) -> Result<GlobalRow, String> {
    let t_all = Instant::now();
    let t = Instant::now();
    let loaded = conformap_io::read_mesh(path).map_err(|e| e.to_string())?;
    let read = crate::stages::ms(t);
    let mesh = &loaded.mesh;
    let t = Instant::now();
    let map = global_map(mesh, &GlobalMapOptions::DEFAULT).map_err(|e| e.to_string())?;
    let map_ms = crate::stages::ms(t);
    let t = Instant::now();
    // one texture coordinate per corner (the CLI deduplicates by cut vertex; the cost of
    // writing is the same order)
    let uv = CornerUv {
        texcoords: map.input_corner_uv().iter().map(|z| [z.re, z.im]).collect(),
        faces: (0..map.input_faces as u32)
            .map(|f| [3 * f, 3 * f + 1, 3 * f + 2])
            .collect(),
    };
    let dest =
        std::env::temp_dir().join(format!("conformap-bench-global-{}.obj", std::process::id()));
    if map.split_edges == 0 && !map.double_covered {
        write_mesh_with_corner_uv(&dest, mesh, &uv).map_err(|e| e.to_string())?;
        let _ = std::fs::remove_file(&dest);
    }
    let write = crate::stages::ms(t);
    let total = crate::stages::ms(t_all);
    let peak = crate::stages::peak_rss_mib();
    // the yardstick: the same reduced Laplacian factored again (vertex 0 pinned, as the
    // harmonic projection pins its root)
    let l = cotan_laplacian(&map.surface);
    let part = Partition::new(map.surface.num_vertices(), &[0]);
    let blocks = LaplacianBlocks::new(&l, &part);
    let mut reference = map.timings_ms.factor;
    for _ in 0..REFACTOR_RUNS {
        let t = Instant::now();
        Cholesky::factor_with(&blocks.ii, &CholeskyOptions::DEFAULT).map_err(|e| e.to_string())?;
        reference = reference.min(crate::stages::ms(t));
    }
    let (_, outside) = map.input_folds();
    Ok(GlobalRow {
        vertices: mesh.num_vertices() as f64,
        faces: mesh.num_faces() as f64,
        genus: map.genus as f64,
        read,
        factor: map.timings_ms.factor,
        map: map_ms,
        write,
        total,
        reference,
        peak_rss_mib: peak,
        zeros: map.input_zeros().count() as f64,
        folds_outside: outside as f64,
    })
}
