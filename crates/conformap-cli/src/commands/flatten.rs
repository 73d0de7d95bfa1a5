//! `conformap flatten`: boundary first flattening (free boundary, circle, rectangles,
//! polygons, given boundary scale or angles). The clap arguments and their job; the job
//! (crate `conformap`) does the work.

use clap::Args;
use conformap::jobs::flatten::{FlattenJob, Interior};
use conformap_disk::BoundarySpec;

use crate::args::{choice, InputArgs, OutputArgs};

/// Arguments of `conformap flatten`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): one `vt` per vertex, the layout's bounding box scaled uniformly into the unit square (aspect kept); `--flat`: the raw layout (u, v, 0), lengths as on the surface."
)]
pub struct FlattenArgs {
    /// The mesh (connected, genus 0, with a boundary; holes are filled and left free).
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` holds one texture coordinate per vertex, the layout's bounding
    /// box scaled uniformly into the unit square (aspect kept); `--flat` the raw layout (u, v, 0).
    #[command(flatten)]
    pub output: OutputArgs,
    /// The boundary: `free` (lengths kept: the least area distortion), `circle`,
    /// `rectangle`, `scale:FILE` (`<vertex> <u>` per boundary vertex), `angles:FILE`
    /// (`<vertex> <exterior angle, degrees>` per boundary vertex, summing to 360) or
    /// `polygon:FILE` (`<vertex> <exterior angle, degrees>` per corner, in boundary order).
    /// Vertices are 0-based.
    #[arg(long, default_value = "free", value_parser = parse_boundary)]
    pub boundary: BoundarySpec,
    /// The rectangle's corners `V1,V2,V3,V4` in boundary order (V1→V2 is the width);
    /// default: the four sharpest boundary vertices (see the report's `flatten.corners`).
    #[arg(long, value_parser = parse_corners)]
    pub corners: Option<[u32; 4]>,
    /// The rectangle's aspect, width/height (`16/9` or `1.5`); default: the conformal
    /// modulus (the report says what another aspect costs).
    #[arg(long, value_parser = parse_aspect)]
    pub aspect: Option<f64>,
    /// The interior: `harmonic` (x and y harmonic, the curve met exactly) or `conjugate`
    /// (y the conjugate of x).
    #[arg(long, value_parser = choice::<Interior>(), default_value_t = Interior::Harmonic)]
    pub interior: Interior,
}

impl FlattenArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> FlattenJob {
        let mut job = FlattenJob::new(self.input.to_options(), self.output.to_options())
            .with_boundary(self.boundary.clone())
            .with_interior(self.interior);
        job.corners = self.corners;
        job.aspect = self.aspect;
        job
    }
}

fn parse_boundary(s: &str) -> Result<BoundarySpec, String> {
    BoundarySpec::parse(s).map_err(|e| e.to_string())
}

fn parse_corners(s: &str) -> Result<[u32; 4], String> {
    let v: Vec<u32> = s
        .split(',')
        .map(|t| t.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            format!("corners must be four 0-based vertex indices V1,V2,V3,V4, got {s:?}")
        })?;
    v.try_into()
        .map_err(|_| format!("corners must be four 0-based vertex indices V1,V2,V3,V4, got {s:?}"))
}

fn parse_aspect(s: &str) -> Result<f64, String> {
    let value = match s.split_once('/') {
        Some((w, h)) => {
            let (w, h): (f64, f64) = (
                w.trim()
                    .parse()
                    .map_err(|_| format!("bad width in {s:?}"))?,
                h.trim()
                    .parse()
                    .map_err(|_| format!("bad height in {s:?}"))?,
            );
            w / h
        }
        None => s
            .trim()
            .parse()
            .map_err(|_| format!("aspect must be W/H or a number, got {s:?}"))?,
    };
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(format!("aspect must be positive and finite, got {s:?}"))
    }
}
