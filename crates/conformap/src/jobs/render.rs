//! `conformap render MESH PARAM -o OUT.png [--view …] [--color …] [--size N]`: pictures of
//! any map of a mesh, ours or another tool's (read as `metrics` reads it).

use std::path::PathBuf;
use std::time::Instant;

use conformap_mesh::TriMesh;
use conformap_render::{
    angle_histogram, histogram_svg, render, ColorBy, MapCoords, RenderOptions, UvValues, View,
};
use conformap_sphere::sphere_points_from_corner_uv;
use num_complex::Complex64;

use crate::choice::Choice;
use crate::failure::{render_failure, Failure};
use crate::jobs::param::{on_unit_sphere, read_measured_map, MapFile, MeasuredMap, PlanarMap};
use crate::pipeline::{check_outputs, context, Outcome, Staged};
use crate::report::ms_since;

/// The default of [`RenderJob::size`]: the library's.
pub const DEFAULT_SIZE: u32 = RenderOptions::DEFAULT.size;

crate::choice! {
    /// The picture.
    pub enum RenderView {
        /// The 3D surface, shaded, coloured through its map.
        Surface = "surface",
        /// The flat map (a sphere map seen from outside) with its edges and a colour bar.
        Map = "map",
        /// The histogram of the angle distortion in degrees (PNG, or SVG with -o OUT.svg).
        Histogram = "histogram",
    }
}

crate::choice! {
    /// What colours the faces.
    pub enum RenderColor {
        /// A checkerboard in the map's coordinates.
        Checker = "checker",
        /// Grid lines in the map's coordinates.
        Grid = "grid",
        /// Disks in the map's coordinates (a conformal map keeps them round).
        Circles = "circles",
        /// Per-face angle distortion in degrees.
        Angle = "angle",
        /// Per-face Beltrami coefficient |μ|.
        Beltrami = "beltrami",
        /// Per-face log area ratio (diverging colours around 0).
        Area = "area",
        /// One colour per chart of a seamed map (an atlas, a 1-form layout), neighbouring
        /// charts in different colours.
        Chart = "chart",
    }
}

crate::choice! {
    /// Where the map in PARAM lands.
    pub enum ParamDomain {
        /// Texture coordinates on a mesh with boundary: planar; on a closed genus-0 mesh:
        /// equirectangular (as `sphere -o` writes). No texture coordinates: unit-length
        /// positions are sphere points (`sphere --flat`), others a flat map's (x, y).
        Auto = "auto",
        /// Planar: texture coordinates, else the positions' (x, y).
        Plane = "plane",
        /// The sphere: unit-length positions, else equirectangular texture coordinates.
        Sphere = "sphere",
    }
}

/// Arguments of `conformap render`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct RenderJob {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map: an OBJ/glTF with one texture coordinate per vertex (the -o of disk or
    /// sphere, or another tool's), or a flat mesh (the --flat of disk or sphere).
    pub param: PathBuf,
    /// The picture: .png (or .svg for --view histogram).
    pub output: PathBuf,
    /// Which picture.
    pub view: RenderView,
    /// What colours the faces (default: checker on the surface, angle on the map).
    pub color: Option<RenderColor>,
    /// Width and height in pixels (the histogram is 5/8 as high).
    pub size: u32,
    /// Turn of the camera around the picture's up axis, degrees.
    pub azimuth: f64,
    /// Tilt of the camera over the object, degrees (positive looks down on it).
    pub elevation: f64,
    /// Where the map lands.
    pub domain: ParamDomain,
}

impl RenderJob {
    /// Runs the job.
    ///
    /// # Errors
    /// A [`Failure`] with its exit class and hint; nothing was written.
    pub fn run(&self) -> Result<Outcome, Failure> {
        run(self)
    }
    /// The picture of the map `param` of `mesh` to `output`: the surface view with its
    /// default colouring, the default size, seen from the front.
    pub fn new(
        mesh: impl Into<PathBuf>,
        param: impl Into<PathBuf>,
        output: impl Into<PathBuf>,
    ) -> Self {
        Self {
            mesh: mesh.into(),
            param: param.into(),
            output: output.into(),
            view: RenderView::Surface,
            color: None,
            size: RenderOptions::DEFAULT.size,
            azimuth: 0.0,
            elevation: 0.0,
            domain: ParamDomain::Auto,
        }
    }

    /// With the picture `view`.
    pub fn with_view(mut self, view: RenderView) -> Self {
        self.view = view;
        self
    }

    /// With the faces coloured by `color`.
    pub fn with_color(mut self, color: RenderColor) -> Self {
        self.color = Some(color);
        self
    }

    /// With a `size` × `size` picture.
    pub fn with_size(mut self, size: u32) -> Self {
        self.size = size;
        self
    }
}

impl RenderJob {
    fn options(&self) -> RenderOptions {
        let view = match self.view {
            RenderView::Surface => View::Surface,
            RenderView::Map => View::Map,
            RenderView::Histogram => View::Histogram,
        };
        let color = match self.color {
            None if view == View::Map => ColorBy::Angle,
            None | Some(RenderColor::Checker) => ColorBy::Checker,
            Some(RenderColor::Grid) => ColorBy::Grid,
            Some(RenderColor::Circles) => ColorBy::Circles,
            Some(RenderColor::Angle) => ColorBy::Angle,
            Some(RenderColor::Beltrami) => ColorBy::Beltrami,
            Some(RenderColor::Area) => ColorBy::Area,
            Some(RenderColor::Chart) => ColorBy::Chart,
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
            Some("svg") if self.view == RenderView::Histogram => Ok(true),
            Some("svg") => Err(Failure::Usage(format!(
                "-o {}: only --view histogram is drawn as SVG; name the output .png",
                self.output.display()
            ))),
            _ => Err(Failure::Usage(format!(
                "-o {}: pictures are written as PNG; name the output .png{}",
                self.output.display(),
                if self.view == RenderView::Histogram {
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
    /// The sphere points read back from an equirectangular texture per corner (`sphere -o`).
    SphereFromCorners(Vec<[f64; 3]>),
}

impl Coords {
    fn view(&self) -> MapCoords<'_> {
        match self {
            Self::Planar(z) => MapCoords::Planar(UvValues::PerVertex(z)),
            Self::PlanarCorners(z) => MapCoords::Planar(UvValues::PerCorner(z)),
            Self::Equirectangular(z) => MapCoords::Equirectangular(UvValues::PerVertex(z)),
            Self::Sphere(p) | Self::SphereFromCorners(p) => MapCoords::Sphere(p),
        }
    }

    /// The map in `file` for `domain`; `closed_genus0` (the mesh, when it is closed and
    /// genus 0) says how `auto` reads texture coordinates: per vertex as equirectangular,
    /// per corner as equirectangular when every vertex's corners name one sphere point
    /// (as `sphere -o` writes them), else as a seamed planar map (an atlas).
    fn from_file(file: MapFile, domain: ParamDomain, closed_genus0: Option<&TriMesh>) -> Self {
        let on_sphere = file.positions.iter().all(on_unit_sphere);
        let corner_points = match (closed_genus0, &file.corner_uv) {
            (Some(mesh), Some(c)) if domain != ParamDomain::Plane && !on_sphere => {
                sphere_points_from_corner_uv(mesh, &c.texcoords, &c.faces)
            }
            _ => None,
        };
        if let Some(points) = corner_points {
            return Self::SphereFromCorners(points);
        }
        let sphere = match domain {
            ParamDomain::Plane => false,
            ParamDomain::Sphere => true,
            ParamDomain::Auto => match (&file.uv, &file.corner_uv) {
                (Some(_), _) => closed_genus0.is_some(),
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
            Some(_) if on_sphere && domain == ParamDomain::Sphere => Self::Sphere(file.positions),
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
            Self::SphereFromCorners(_) => {
                "sphere map (equirectangular texture coordinates per corner)"
            }
        }
    }
}

/// Runs `conformap render`: checks the output, reads the mesh and the map, draws the
/// picture and writes it (nothing is written when any step fails).
///
/// # Errors
/// Usage (2): an output that is not .png (.svg for the histogram) or names an input.
/// Bad input (1): unreadable files, a map that does not fit the mesh or cannot be drawn.
fn run(args: &RenderJob) -> Result<Outcome, Failure> {
    let t_all = Instant::now();
    let svg = args.svg_output()?;
    if let Some(c) = args
        .color
        .filter(|&c| args.view == RenderView::Histogram && c != RenderColor::Angle)
    {
        return Err(Failure::Usage(format!(
            "--color {} does not apply to --view histogram: the histogram is of the angle \
             distortion; drop --color (or pass --color angle)",
            c.name()
        )));
    }
    check_outputs(&[("-o", &args.output, false)], &[&args.mesh, &args.param])?;
    context::stage(format!("reading {}", args.mesh.display()));
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    // a map carrying its own mesh (global's refinement at split chords) is drawn on it
    let MeasuredMap { file, own_mesh } = read_measured_map(&args.param, &args.mesh, &loaded.mesh)?;
    let mesh = own_mesh.as_ref().unwrap_or(&loaded.mesh);
    let closed_genus0 = mesh.boundary_loops().is_empty() && mesh.genus() == Some(0);
    let coords = Coords::from_file(file, args.domain, closed_genus0.then_some(mesh));
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
                RenderView::Surface => "surface",
                RenderView::Map => "map",
                RenderView::Histogram => "histogram",
            },
            coords.name(),
            args.param.display(),
            mesh.num_faces(),
            ms_since(t_all)
        )],
        ..Outcome::default()
    })
}
