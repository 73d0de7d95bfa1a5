//! `conformap render MESH PARAM -o OUT.png [--view …] [--color …] [--size N]`: pictures of
//! any map of a mesh, ours or another tool's (read as `metrics` reads it).

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use conformap_render::{
    angle_histogram, histogram_svg, render, ColorBy, MapCoords, RenderOptions, UvValues, View,
    SPHERE_RADIUS_TOL,
};
use num_complex::Complex64;

use crate::commands::param::{read_map_file, MapFile, PlanarMap};
use crate::failure::Failure;
use crate::pipeline::pictures::render_failure;
use crate::pipeline::{check_outputs, context, Outcome, Staged};
use crate::report::ms_since;

/// The picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ViewArg {
    /// The 3D surface, shaded, coloured through its map.
    Surface,
    /// The flat map (a sphere map seen from outside) with its edges and a colour bar.
    Map,
    /// The histogram of the angle distortion in degrees (PNG, or SVG with -o OUT.svg).
    Histogram,
}

/// What colours the faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ColorArg {
    /// A checkerboard in the map's coordinates.
    Checker,
    /// Grid lines in the map's coordinates.
    Grid,
    /// Disks in the map's coordinates (a conformal map keeps them round).
    Circles,
    /// Per-face angle distortion in degrees.
    Angle,
    /// Per-face Beltrami coefficient |μ|.
    Beltrami,
    /// Per-face log area ratio (diverging colours around 0).
    Area,
}

/// Where the map in PARAM lands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DomainArg {
    /// Texture coordinates on a mesh with boundary: planar; on a closed genus-0 mesh:
    /// equirectangular (as `sphere -o` writes). No texture coordinates: unit-length
    /// positions are sphere points (`sphere --flat`), others a flat map's (x, y).
    Auto,
    /// Planar: texture coordinates, else the positions' (x, y).
    Plane,
    /// The sphere: unit-length positions, else equirectangular texture coordinates.
    Sphere,
}

/// Arguments of `conformap render`.
#[derive(Debug, Clone, Args)]
pub struct RenderArgs {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map: an OBJ/glTF with one texture coordinate per vertex (the -o of disk or
    /// sphere, or another tool's), or a flat mesh (the --flat of disk or sphere).
    pub param: PathBuf,
    /// The picture: .png (or .svg for --view histogram).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Which picture.
    #[arg(long, value_enum, default_value_t = ViewArg::Surface)]
    pub view: ViewArg,
    /// What colours the faces (default: checker on the surface, angle on the map).
    #[arg(long, value_enum)]
    pub color: Option<ColorArg>,
    /// Width and height in pixels (the histogram is 5/8 as high).
    #[arg(long, default_value_t = RenderOptions::DEFAULT.size,
          value_parser = clap::value_parser!(u32).range(16..=16384))]
    pub size: u32,
    /// Turn of the camera around the picture's up axis, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub azimuth: f64,
    /// Tilt of the camera over the object, degrees (positive looks down on it).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub elevation: f64,
    /// Where the map lands.
    #[arg(long, value_enum, default_value_t = DomainArg::Auto)]
    pub domain: DomainArg,
}

impl RenderArgs {
    /// The arguments of `conformap render MESH PARAM -o OUTPUT` with every option at its
    /// default.
    pub fn new(mesh: impl Into<PathBuf>, param: impl Into<PathBuf>, output: PathBuf) -> Self {
        Self {
            mesh: mesh.into(),
            param: param.into(),
            output,
            view: ViewArg::Surface,
            color: None,
            size: RenderOptions::DEFAULT.size,
            azimuth: 0.0,
            elevation: 0.0,
            domain: DomainArg::Auto,
        }
    }

    fn options(&self) -> RenderOptions {
        let view = match self.view {
            ViewArg::Surface => View::Surface,
            ViewArg::Map => View::Map,
            ViewArg::Histogram => View::Histogram,
        };
        let color = match self.color {
            None if view == View::Map => ColorBy::Angle,
            None | Some(ColorArg::Checker) => ColorBy::Checker,
            Some(ColorArg::Grid) => ColorBy::Grid,
            Some(ColorArg::Circles) => ColorBy::Circles,
            Some(ColorArg::Angle) => ColorBy::Angle,
            Some(ColorArg::Beltrami) => ColorBy::Beltrami,
            Some(ColorArg::Area) => ColorBy::Area,
        };
        RenderOptions::DEFAULT
            .with_size(self.size)
            .with_view(view)
            .with_color(color)
            .with_azimuth_deg(self.azimuth)
            .with_elevation_deg(self.elevation)
    }

    /// `.png`, or `.svg` for the histogram; anything else is a usage error.
    fn svg_output(&self) -> Result<bool, Failure> {
        let ext = self
            .output
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("png") => Ok(false),
            Some("svg") if self.view == ViewArg::Histogram => Ok(true),
            Some("svg") => Err(Failure::Usage(format!(
                "-o {}: only --view histogram is drawn as SVG; name the output .png",
                self.output.display()
            ))),
            _ => Err(Failure::Usage(format!(
                "-o {}: pictures are written as PNG; name the output .png{}",
                self.output.display(),
                if self.view == ViewArg::Histogram {
                    " (or .svg)"
                } else {
                    ""
                }
            ))),
        }
    }
}

/// A map as the renderer takes it, owning its values.
enum Coords {
    Planar(Vec<Complex64>),
    /// A seamed planar map: the image of every face's corners.
    PlanarCorners(Vec<[Complex64; 3]>),
    Equirectangular(Vec<Complex64>),
    Sphere(Vec<[f64; 3]>),
}

impl Coords {
    fn view(&self) -> MapCoords<'_> {
        match self {
            Self::Planar(z) => MapCoords::Planar(UvValues::PerVertex(z)),
            Self::PlanarCorners(z) => MapCoords::Planar(UvValues::PerCorner(z)),
            Self::Equirectangular(z) => MapCoords::Equirectangular(UvValues::PerVertex(z)),
            Self::Sphere(p) => MapCoords::Sphere(p),
        }
    }

    /// The map in `file` for `domain`; `closed_genus0` says how `auto` reads texture
    /// coordinates.
    fn from_file(file: MapFile, domain: DomainArg, closed_genus0: bool) -> Self {
        let on_sphere = file.positions.iter().all(|p| {
            ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() <= SPHERE_RADIUS_TOL
        });
        let sphere = match domain {
            DomainArg::Plane => false,
            DomainArg::Sphere => true,
            DomainArg::Auto => match (&file.uv, &file.corner_uv) {
                (Some(_), _) => closed_genus0,
                (None, Some(_)) => false,
                (None, None) => on_sphere,
            },
        };
        if !sphere {
            return match file.planar_map().0 {
                PlanarMap::PerVertex(z) => Self::Planar(z),
                PlanarMap::PerCorner(z) => {
                    Self::PlanarCorners(z.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
                }
            };
        }
        match file.uv {
            None => Self::Sphere(file.positions),
            Some(_) if on_sphere && domain == DomainArg::Sphere => Self::Sphere(file.positions),
            Some(uv) => {
                Self::Equirectangular(uv.iter().map(|t| Complex64::new(t[0], t[1])).collect())
            }
        }
    }

    fn name(&self) -> &'static str {
        match self {
            Self::Planar(_) => "planar map",
            Self::PlanarCorners(_) => "seamed planar map",
            Self::Equirectangular(_) => "sphere map (equirectangular texture coordinates)",
            Self::Sphere(_) => "sphere map (unit-sphere points)",
        }
    }
}

/// Runs `conformap render`: checks the output, reads the mesh and the map, draws the
/// picture and writes it (nothing is written when any step fails).
///
/// # Errors
/// Usage (2): an output that is not .png (.svg for the histogram) or names an input.
/// Bad input (1): unreadable files, a map that does not fit the mesh or cannot be drawn.
pub fn run(args: &RenderArgs) -> Result<Outcome, Failure> {
    let t_all = Instant::now();
    let svg = args.svg_output()?;
    check_outputs(&[("-o", &args.output, false)], &[&args.mesh, &args.param])?;
    context::stage(format!("reading {}", args.mesh.display()));
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    let file = read_map_file(&args.param, &args.mesh, mesh)?;
    let closed_genus0 = mesh.boundary_loops().is_empty() && mesh.genus() == Some(0);
    let coords = Coords::from_file(file, args.domain, closed_genus0);
    let options = args.options();
    context::stage(format!("drawing {}", args.output.display()));
    let mut staged = Staged::new();
    let fail = |e| render_failure(e, &args.output).in_file(&args.param);
    if svg {
        let hist = angle_histogram(mesh, &coords.view(), options.histogram_bins).map_err(fail)?;
        staged.text(&args.output, &histogram_svg(&hist, args.size))?;
    } else {
        let image = render(mesh, &coords.view(), &options).map_err(fail)?;
        staged.png(&args.output, &image)?;
    }
    staged.commit()?;
    Ok(Outcome {
        messages: vec![format!(
            "{}: {} of the {} in {} ({} faces); {:.0} ms",
            args.output.display(),
            match args.view {
                ViewArg::Surface => "surface",
                ViewArg::Map => "map",
                ViewArg::Histogram => "histogram",
            },
            coords.name(),
            args.param.display(),
            mesh.num_faces(),
            ms_since(t_all)
        )],
        ..Outcome::default()
    })
}
