//! The argument groups every map command shares (`#[command(flatten)]`), so that a flag
//! means the same everywhere and a new command gets all of them by one line, and the parser
//! of every named choice.

use std::path::PathBuf;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::Args;
use conformap::{Choice, InputOptions, OutputOptions};

/// Parses `4G`, `512M`, `1.5GiB`, `100000` (bytes; K, M, G, T are powers of 1024).
pub use conformap::pipeline::parse_size;

/// The parser of a [`Choice`]: its names, with their help, as clap's possible values.
pub fn choice<T: Choice + Send + Sync + Clone>() -> impl TypedValueParser<Value = T> {
    let values = T::ALL.iter().map(|v| {
        let help = v.help().split_whitespace().collect::<Vec<_>>().join(" ");
        PossibleValue::new(v.name()).help(help)
    });
    PossibleValuesParser::new(values).try_map(|name| T::parse_name(&name))
}

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
    /// With --repair (or with `atlas`, which splits non-manifold vertices and edges): write
    /// the vertex map here, one line per output vertex holding its 0-based input vertex.
    #[arg(long)]
    pub vertex_map: Option<PathBuf>,
    /// Refuse (exit 1, nothing computed) if the estimated peak memory exceeds SIZE (bytes,
    /// or with K/M/G/T, e.g. 4G). Default: the memory available (Linux MemAvailable, within
    /// the cgroup limit); no check where that is unknown.
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
}

impl InputArgs {
    /// The job's input options.
    pub fn to_options(&self) -> InputOptions {
        let mut options = InputOptions::new(&self.mesh)
            .with_repair(self.repair)
            .with_max_memory(self.max_memory);
        options.vertex_map = self.vertex_map.clone();
        options
    }
}

/// What a map command writes: `-o OUT [--flat FLAT] [--report R.json] [--strict]`.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Output mesh: the input's 3D positions with the map as texture coordinates (.obj,
    /// .gltf, .glb; "Texture coordinates" at the end of this help says how).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the raw map as a mesh: (u, v, 0) for planar maps, the unit-sphere points
    /// for sphere maps (.surf.gii and FreeSurfer surfaces: at radius 100, keeping the
    /// coordinate system or volume geometry of an input of the same format).
    #[arg(long)]
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Also write the map's quality at every vertex (angle_distortion_deg,
    /// area_log_ratio) as a GIfTI data file that loads as an overlay on the input surface.
    #[arg(long, value_name = "FILE.shape.gii")]
    pub quality_overlay: Option<PathBuf>,
    /// Also write pictures of the result: PREFIX_surface.png (the surface with a
    /// checkerboard through the map) and PREFIX_map.png (the map coloured by angle
    /// distortion), 1024 × 1024.
    #[arg(long, value_name = "PREFIX")]
    pub png: Option<PathBuf>,
    /// Exit with code 3, writing nothing, if the solver did not converge (or, for sphere
    /// maps, a triangle is inverted).
    #[arg(long)]
    pub strict: bool,
}

impl OutputArgs {
    /// The job's output options.
    pub fn to_options(&self) -> OutputOptions {
        let mut options = OutputOptions::new(&self.output).with_strict(self.strict);
        options.flat = self.flat.clone();
        options.report = self.report.clone();
        options.quality = self.quality_overlay.clone();
        options.png = self.png.clone();
        options
    }
}
