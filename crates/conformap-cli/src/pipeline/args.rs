//! The argument groups every map command shares (`#[command(flatten)]`), so that a flag
//! means the same everywhere and a new command gets all of them by one line.

use std::path::PathBuf;

use clap::Args;

/// Where the mesh comes from and how it is prepared: `MESH [--repair [--vertex-map F]]
/// [--max-memory SIZE]`.
#[derive(Debug, Clone, Args)]
pub struct InputArgs {
    /// The mesh (.obj, .gltf, .glb).
    pub mesh: PathBuf,
    /// Repair the input first: drop duplicate faces, keep the largest component, orient the
    /// faces consistently, drop unreferenced vertices. Outputs then hold the repaired mesh
    /// (vt index k belongs to repaired vertex k); the report lists the repairs.
    #[arg(long)]
    pub repair: bool,
    /// With --repair: write the vertex map here, one line per output vertex holding its
    /// 0-based input vertex.
    #[arg(long, requires = "repair")]
    pub vertex_map: Option<PathBuf>,
    /// Refuse (exit 1, nothing computed) if the estimated peak memory exceeds SIZE (bytes,
    /// or with K/M/G/T, e.g. 4G). Default: the memory available (Linux MemAvailable, within
    /// the cgroup limit); no check where that is unknown.
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
}

impl InputArgs {
    /// The arguments for `mesh` with every option at its default.
    pub fn new(mesh: impl Into<PathBuf>) -> Self {
        Self {
            mesh: mesh.into(),
            repair: false,
            vertex_map: None,
            max_memory: None,
        }
    }
}

/// What a map command writes: `-o OUT [--flat FLAT] [--report R.json] [--strict]`.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Output mesh: the input's 3D positions with the map as texture coordinates (.obj,
    /// .gltf, .glb; the command's help says how the map becomes texture coordinates).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the raw map as a mesh: (u, v, 0) for planar maps, the unit-sphere points
    /// for sphere maps.
    #[arg(long)]
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Exit with code 3, writing nothing, if the solver did not converge (or, for sphere
    /// maps, a triangle is inverted).
    #[arg(long)]
    pub strict: bool,
}

impl OutputArgs {
    /// The arguments writing only `output`.
    pub fn new(output: impl Into<PathBuf>) -> Self {
        Self {
            output: output.into(),
            flat: None,
            report: None,
            strict: false,
        }
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
