//! The option groups every map job shares, so that an option means the same everywhere and
//! a new job gets all of them by one field each.

use std::path::PathBuf;

/// Where the mesh comes from and how it is prepared: `MESH [--repair [--vertex-map F]]
/// [--max-memory SIZE]`.
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct InputOptions {
    /// The mesh (.obj, .gltf, .glb).
    pub mesh: PathBuf,
    /// Repair the input first: drop duplicate faces, keep the largest component, orient the
    /// faces consistently, drop unreferenced vertices. Outputs then hold the repaired mesh
    /// (vt index k belongs to repaired vertex k); the report lists the repairs.
    pub repair: bool,
    /// With --repair: write the vertex map here, one line per output vertex holding its
    /// 0-based input vertex.
    pub vertex_map: Option<PathBuf>,
    /// Refuse (exit 1, nothing computed) if the estimated peak memory exceeds SIZE (bytes,
    /// or with K/M/G/T, e.g. 4G). Default: the memory available (Linux MemAvailable, within
    /// the cgroup limit); no check where that is unknown.
    pub max_memory: Option<u64>,
}

impl InputOptions {
    /// The arguments for `mesh` with every option at its default.
    pub fn new(mesh: impl Into<PathBuf>) -> Self {
        Self {
            mesh: mesh.into(),
            repair: false,
            vertex_map: None,
            max_memory: None,
        }
    }

    /// With the repairs of `--repair`.
    pub fn with_repair(mut self, repair: bool) -> Self {
        self.repair = repair;
        self
    }

    /// With a memory limit of `bytes`.
    pub fn with_max_memory(mut self, bytes: Option<u64>) -> Self {
        self.max_memory = bytes;
        self
    }
}

/// What a map command writes: `-o OUT [--flat FLAT] [--report R.json] [--strict]`.
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct OutputOptions {
    /// Output mesh: the input's 3D positions with the map as texture coordinates (.obj,
    /// .gltf, .glb; the command's help says how the map becomes texture coordinates).
    pub output: PathBuf,
    /// Also write the raw map as a mesh: (u, v, 0) for planar maps, the unit-sphere points
    /// for sphere maps.
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    pub report: Option<PathBuf>,
    /// Also write the map's quality at every vertex (angle distortion, area log ratio) as
    /// a GIfTI data file (`.shape.gii`) that loads as an overlay on the input surface
    /// ([`crate::pipeline::quality`]). Default: none.
    pub quality: Option<PathBuf>,
    /// Also write pictures of the result: PREFIX_surface.png (the surface with a
    /// checkerboard through the map) and PREFIX_map.png (the map coloured by angle
    /// distortion), 1024 × 1024.
    pub png: Option<PathBuf>,
    /// Exit with code 3, writing nothing, if the solver did not converge (or, for sphere
    /// maps, a triangle is inverted).
    pub strict: bool,
}

impl OutputOptions {
    /// The arguments writing only `output`.
    pub fn new(output: impl Into<PathBuf>) -> Self {
        Self {
            output: output.into(),
            flat: None,
            report: None,
            quality: None,
            png: None,
            strict: false,
        }
    }

    /// Also writing the raw map as a mesh to `path`.
    pub fn with_flat(mut self, path: impl Into<PathBuf>) -> Self {
        self.flat = Some(path.into());
        self
    }

    /// Also writing the JSON report to `path`.
    pub fn with_report(mut self, path: impl Into<PathBuf>) -> Self {
        self.report = Some(path.into());
        self
    }

    /// Also writing the per-vertex quality overlay to `path` (`.shape.gii`).
    pub fn with_quality(mut self, path: impl Into<PathBuf>) -> Self {
        self.quality = Some(path.into());
        self
    }

    /// Also writing the pictures `PREFIX_surface.png` and `PREFIX_map.png`.
    pub fn with_png(mut self, prefix: impl Into<PathBuf>) -> Self {
        self.png = Some(prefix.into());
        self
    }

    /// Refusing (exit class numerical, nothing written) a result the solver did not
    /// converge to.
    pub fn with_strict(mut self, strict: bool) -> Self {
        self.strict = strict;
        self
    }
}

/// Parses `4G`, `512M`, `1.5GiB`, `100000` (bytes; K, M, G, T are powers of 1024).
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let lower = t.to_ascii_lowercase();
    let body = lower
        .strip_suffix("ib")
        .or_else(|| lower.strip_suffix('b'))
        .unwrap_or(&lower);
    let (num, shift) = match body.chars().last() {
        Some('k') => (&body[..body.len() - 1], 10),
        Some('m') => (&body[..body.len() - 1], 20),
        Some('g') => (&body[..body.len() - 1], 30),
        Some('t') => (&body[..body.len() - 1], 40),
        _ => (body, 0),
    };
    let value: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("`{t}` is not a size (e.g. 4G, 512M, 1000000)"))?;
    let bytes = value * 2f64.powi(shift);
    if !(bytes.is_finite() && bytes >= 1.0) || bytes > u64::MAX as f64 {
        return Err(format!("`{t}` is not a positive size"));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_parse_in_powers_of_1024() {
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("512MiB"), Ok(512 << 20));
        assert_eq!(parse_size("1.5k"), Ok(1536));
        assert_eq!(parse_size("100000"), Ok(100000));
        assert!(parse_size("lots").is_err());
        assert!(parse_size("0").is_err());
    }
}
