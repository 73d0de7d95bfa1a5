//! [`planar_map_metrics`]: every metric of a planar map in two linear passes over the faces.

use conformap_mesh::{triangle_area, TriMesh};
use conformap_operators::{face_points, triangle_angles, triangle_cotangents, Circle};
use num_complex::Complex64;
use rayon::prelude::*;

use crate::circles::{fit_circle, relative_residual, unit_circle_residual};
use crate::energy::{corners, face_dirichlet, image_area_unchecked, twice_signed_area};
use crate::error::{check_map, MetricsError};
use crate::face::{image_angles, Chart};
use crate::options::{MetricsOptions, OuterCircle};
use crate::report::{Histogram, LoopCircle, MapMetrics};
use crate::stats::{angle_bin, p95, Running, ANGLE_HISTOGRAM_EDGES_DEG};
use crate::summary::{AngleStats, LogRatioStats, SummaryStats};

/// Whether twice the signed area of an image face marks it degenerate: exactly zero or not
/// finite. Tiny areas (1e-20 and below) are *not* degenerate: conformal maps crowd
/// exponentially on thin limbs and long corridors, and those faces are valid.
#[inline]
fn is_degenerate(twice_area: f64) -> bool {
    !(twice_area.abs() > 0.0 && twice_area.is_finite())
}

/// Judges a planar map `f = u + iv` (one value per vertex, in vertex order) of `mesh`:
/// conformal and Dirichlet energy, image area, angle distortion, Beltrami coefficient, area
/// distortion, flipped and degenerate faces, and how well each boundary loop lies on a circle.
/// Works for any planar map — conformap's or another tool's — and solves nothing.
///
/// Conventions (all numbers in the result are finite):
/// - **Energies** (CEM Eq. 5–8): `E_D = ½ fᴴ L f` with the mesh's cotangent weights (see
///   [`crate::dirichlet_energy`]), `A` the signed boundary area (see [`crate::image_area`]),
///   `E_C = E_D − A`.
/// - **Orientation**: if `A < 0` the map is mirrored (e.g. another tool's `v ↦ −v`); with
///   [`MetricsOptions::fix_orientation`] (the default) `orientation_reversed` is set and the
///   conjugate map `f̄` is scored instead, so a mirrored perfect map still has `E_C ≈ 0`.
///   Energies, `A`, flips and `|μ|` are those of the fixed map; angles and circle residuals
///   do not depend on it.
/// - **Faces**: an image face is *flipped* if its signed area is negative and *degenerate*
///   if it is exactly zero (or not finite). Degenerate faces have no image shape: they are
///   counted and left out of the angle, Beltrami and area statistics, which run over the
///   `measured_faces` others. Tiny but nonzero areas (1e-20 and below: conformal maps crowd
///   exponentially on thin limbs) are valid faces, not degenerate ones.
/// - **Angle distortion**: `|θ_mesh − θ_image|` in degrees at every corner of the measured
///   faces, with unsigned image angles in `[0°, 180°]` (a flipped face is counted in
///   `flipped_faces`, not here); mean, population sd, max, p95 (nearest rank) and a
///   histogram over [`crate::ANGLE_HISTOGRAM_EDGES_DEG`].
/// - **Beltrami coefficient** `μ = f_z̄ / f_z` of the affine map from an isometric chart of
///   each 3D face to its image: 0 for a conformal face, `< 1` orientation-preserving, `> 1`
///   flipped, capped at [`crate::BELTRAMI_ABS_CAP`] when `f_z = 0`.
/// - **Area distortion**: per measured face
///   `log((image area / Σ image area) / (mesh area / Σ mesh area))`, both sums over the
///   measured faces and the image area unsigned; reports the mean of its absolute value and
///   its sd.
/// - **Circles**: the outer loop ([`MetricsOptions::outer_loop`], by default the longest) is
///   compared with the unit circle, `max ||f| − 1|` (or with its own best-fit circle, see
///   [`OuterCircle`]); every other loop with its least-squares circle (Kåsa fit refined by
///   Gauss–Newton on the geometric distances), residual `max ||f − c| − r| / r`. Centres are
///   in the coordinates of the map as given. `circle_residual_max` is the largest residual
///   (0 for a closed mesh).
///
/// Linear time and memory: two passes over the faces, one `f64` buffer of the corner
/// distortions for the percentile (linear selection, no sort), no allocation per face.
///
/// # Errors
/// - [`MetricsError::LengthMismatch`], [`MetricsError::NonFiniteValue`],
///   [`MetricsError::ValueTooLarge`]: `map` is not one finite, moderate value per vertex
///   (the error names the first bad vertex).
/// - [`MetricsError::OuterLoopOutOfRange`]: the requested outer loop does not exist.
///
/// # Examples
/// ```
/// use conformap_metrics::{planar_map_metrics, MetricsOptions};
/// use num_complex::Complex64;
/// // a square and a shear of it
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let shear: Vec<Complex64> = mesh.positions().iter()
///     .map(|p| Complex64::new(p[0] + 0.5 * p[1], p[1]))
///     .collect();
/// let m = planar_map_metrics(&mesh, &shear, &MetricsOptions::DEFAULT)?;
/// // f = a z + b z̄ with a = 1 − i/4, b = i/4: E_C = 2|b|² · area = 1/8
/// assert!((m.conformal_energy - 0.125).abs() < 1e-14);
/// assert!((m.beltrami_abs.max - 0.25 / (1.0f64 + 1.0 / 16.0).sqrt()).abs() < 1e-14);
/// assert_eq!((m.flipped_faces, m.degenerate_faces), (0, 0));
/// assert!(!m.orientation_reversed);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn planar_map_metrics(
    mesh: &TriMesh,
    map: &[Complex64],
    options: &MetricsOptions,
) -> Result<MapMetrics, MetricsError> {
    check_map(mesh.num_vertices(), map)?;
    let loops = mesh.boundary_loops();
    let outer_loop = match options.outer_loop {
        Some(index) if index >= loops.len() => {
            return Err(MetricsError::OuterLoopOutOfRange {
                index,
                loops: loops.len(),
            })
        }
        Some(index) => Some(index),
        None => mesh.longest_boundary_loop(),
    };

    let signed_area = image_area_unchecked(mesh, map);
    let mut metrics = face_passes(mesh, signed_area, options.fix_orientation, |f| {
        corners(map, mesh.faces()[f])
    });
    metrics.boundary_circles = boundary_circles(mesh, map, outer_loop, options.outer_circle);
    metrics.circle_residual_max = metrics
        .boundary_circles
        .iter()
        .map(|c| c.residual_max)
        .fold(0.0, f64::max);
    metrics.outer_loop = outer_loop;
    Ok(metrics)
}

/// Judges a seamed planar map: `corner_map[3 f + k]` is the image of corner `k` of face `f`,
/// so a vertex may have different images in different faces (a map cut open along seams, as
/// `conformap global` writes, or another tool's atlas). Every metric of
/// [`planar_map_metrics`] with the same conventions, except that the image area is the sum
/// of the faces' signed areas and no boundary loop is compared with a circle
/// (`boundary_circles` empty, `circle_residual_max` 0, `outer_loop` `None`); for a map
/// without seams the two functions agree.
///
/// # Errors
/// [`MetricsError::LengthMismatch`] unless `corner_map` has `3 · faces` values (the error
/// counts corners); [`MetricsError::NonFiniteValue`], [`MetricsError::ValueTooLarge`]
/// naming the first bad corner.
///
/// # Examples
/// ```
/// use conformap_metrics::{corner_map_metrics, planar_map_metrics, MetricsOptions};
/// use num_complex::Complex64;
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let z = |x: f64, y: f64| Complex64::new(x, y);
/// // the second face translated by 5: a seam along edge 0–2, each face still isometric
/// let corners = [z(0., 0.), z(1., 0.), z(1., 1.), z(5., 0.), z(6., 1.), z(5., 1.)];
/// let m = corner_map_metrics(&mesh, &corners, &MetricsOptions::DEFAULT)?;
/// assert!(m.conformal_energy.abs() < 1e-14 && m.angle_distortion_deg.max < 1e-12);
/// assert_eq!(m.flipped_faces, 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn corner_map_metrics(
    mesh: &TriMesh,
    corner_map: &[Complex64],
    options: &MetricsOptions,
) -> Result<MapMetrics, MetricsError> {
    check_map(3 * mesh.num_faces(), corner_map)?;
    let image = |f: usize| {
        [
            corner_map[3 * f],
            corner_map[3 * f + 1],
            corner_map[3 * f + 2],
        ]
    };
    let twice: f64 = (0..mesh.num_faces())
        .map(|f| twice_signed_area(image(f)))
        .sum();
    Ok(face_passes(
        mesh,
        0.5 * twice,
        options.fix_orientation,
        image,
    ))
}

/// The face-by-face metrics (two passes) of the map whose face `f` has image
/// `image(f)` and whose total signed image area is `signed_area`; boundary fields empty.
fn face_passes(
    mesh: &TriMesh,
    signed_area: f64,
    fix_orientation: bool,
    image: impl Fn(usize) -> [Complex64; 3] + Sync,
) -> MapMetrics {
    let reversed = fix_orientation && signed_area < 0.0;
    let fixed = |f: usize| {
        let g = image(f);
        if reversed {
            g.map(|z| z.conj())
        } else {
            g
        }
    };

    // pass 1: the area totals over the measured faces
    let (mut image_total, mut mesh_total) = (0.0, 0.0);
    for f in 0..mesh.num_faces() {
        let twice = twice_signed_area(image(f));
        if !is_degenerate(twice) {
            image_total += 0.5 * twice.abs();
            let p = face_points(mesh, f);
            mesh_total += triangle_area(p[0], p[1], p[2]);
        }
    }
    let log_totals = mesh_total.ln() - image_total.ln();

    // pass 2: everything else, in blocks of faces on both cores, merged in face order (the
    // result does not depend on the number of threads)
    let blocks: Vec<Pass2> = (0..mesh.num_faces().div_ceil(FACE_BLOCK))
        .into_par_iter()
        .map(|b| {
            let range = b * FACE_BLOCK..((b + 1) * FACE_BLOCK).min(mesh.num_faces());
            let mut s = Pass2::new(range.len());
            for f in range {
                let p = face_points(mesh, f);
                let g = fixed(f);
                s.dirichlet += face_dirichlet(triangle_cotangents(p), g);
                let twice = twice_signed_area(g);
                if is_degenerate(twice) {
                    s.degenerate += 1;
                    continue;
                }
                if twice < 0.0 {
                    s.flipped += 1;
                }
                let mesh_angles = triangle_angles(p);
                let img_angles = image_angles(g);
                for k in 0..3 {
                    let d = (mesh_angles[k] - img_angles[k]).abs().to_degrees();
                    s.angle.push(d);
                    s.corners.push(d);
                    s.counts[angle_bin(d)] += 1;
                }
                s.beltrami.push(Chart::new(p).beltrami_abs(g));
                let log_ratio =
                    (0.5 * twice.abs()).ln() - triangle_area(p[0], p[1], p[2]).ln() + log_totals;
                s.area.push(log_ratio);
                s.area_abs.push(log_ratio.abs());
            }
            s
        })
        .collect();
    let mut all = Pass2::new(3 * mesh.num_faces());
    for b in &blocks {
        all.merge(b);
    }
    let Pass2 {
        dirichlet,
        flipped,
        degenerate,
        angle,
        beltrami,
        area,
        area_abs,
        corners: mut corner_distortion,
        counts,
    } = all;
    let image_area = if reversed { -signed_area } else { signed_area };

    MapMetrics {
        conformal_energy: dirichlet - image_area,
        dirichlet_energy: dirichlet,
        image_area,
        angle_distortion_deg: AngleStats {
            mean: angle.mean(),
            sd: angle.sd(),
            max: angle.max(),
            p95: p95(&mut corner_distortion),
        },
        beltrami_abs: SummaryStats {
            mean: beltrami.mean(),
            sd: beltrami.sd(),
            max: beltrami.max(),
        },
        area_distortion_log: LogRatioStats {
            mean_abs: area_abs.mean(),
            sd: area.sd(),
        },
        flipped_faces: flipped,
        degenerate_faces: degenerate,
        circle_residual_max: 0.0,
        orientation_reversed: reversed,
        measured_faces: mesh.num_faces() - degenerate,
        angle_histogram: Histogram {
            edges_deg: ANGLE_HISTOGRAM_EDGES_DEG.to_vec(),
            counts,
        },
        outer_loop: None,
        boundary_circles: Vec::new(),
    }
}

/// Faces per parallel block of the second pass: ~1 ms of work, far more than a task
/// hand-off.
const FACE_BLOCK: usize = 1 << 13;

/// The second pass's sums over a block of faces.
struct Pass2 {
    dirichlet: f64,
    flipped: usize,
    degenerate: usize,
    angle: Running,
    beltrami: Running,
    area: Running,
    area_abs: Running,
    corners: Vec<f64>,
    counts: Vec<u64>,
}

impl Pass2 {
    fn new(capacity: usize) -> Self {
        Self {
            dirichlet: 0.0,
            flipped: 0,
            degenerate: 0,
            angle: Running::default(),
            beltrami: Running::default(),
            area: Running::default(),
            area_abs: Running::default(),
            corners: Vec::with_capacity(capacity),
            counts: vec![0; ANGLE_HISTOGRAM_EDGES_DEG.len() - 1],
        }
    }

    /// Adds the block after this one.
    fn merge(&mut self, o: &Self) {
        self.dirichlet += o.dirichlet;
        self.flipped += o.flipped;
        self.degenerate += o.degenerate;
        self.angle.merge(&o.angle);
        self.beltrami.merge(&o.beltrami);
        self.area.merge(&o.area);
        self.area_abs.merge(&o.area_abs);
        self.corners.extend_from_slice(&o.corners);
        for (c, d) in self.counts.iter_mut().zip(&o.counts) {
            *c += d;
        }
    }
}

/// The circle of every boundary loop, in loop order.
fn boundary_circles(
    mesh: &TriMesh,
    map: &[Complex64],
    outer_loop: Option<usize>,
    outer_circle: OuterCircle,
) -> Vec<LoopCircle> {
    mesh.boundary_loops()
        .iter()
        .enumerate()
        .map(|(loop_index, lp)| {
            let outer = outer_loop == Some(loop_index);
            let (circle, residual_max) = if outer && outer_circle == OuterCircle::Unit {
                (Circle::UNIT, unit_circle_residual(lp, map))
            } else {
                let fit = fit_circle(lp, map);
                (fit, relative_residual(lp, map, fit))
            };
            LoopCircle::new(loop_index, lp.len(), outer, circle, residual_max)
        })
        .collect()
}
