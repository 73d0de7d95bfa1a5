//! The layout of a [`GlobalMap`] as a file writes it: one texture coordinate per corner class
//! (cut vertex) of the input's faces, the layout scaled uniformly into the unit square (which
//! changes neither angles nor the seams' translations), and the mesh those coordinates
//! belong to (the input, or its refinement when the double covering split boundary chords).

use conformap_mesh::TriMesh;
use num_complex::Complex64;

use crate::forms::global_map::GlobalMap;
use crate::GlobalError;

/// A seamed layout ready to be written: `texcoords[tex_faces[f][k]]` is the texture
/// coordinate of corner `k` of face `f` of [`Self::mesh`] (or of the input when that is
/// `None`).
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct SeamedLayout {
    /// One texture coordinate per cut vertex used by the input's faces, numbered by first
    /// use in face order: `(layout − offset) · scale`, inside the unit square.
    pub texcoords: Vec<[f64; 2]>,
    /// Per face, the texture coordinate of each corner.
    pub tex_faces: Vec<[u32; 3]>,
    /// The raw layout (area equal to the surface's) of each texture coordinate.
    pub layout: Vec<Complex64>,
    /// The layout's lower-left corner: `texcoord = (layout − offset) · scale`.
    pub offset: [f64; 2],
    /// `1 / max(width, height)` of the layout.
    pub scale: f64,
    /// The mesh the coordinates belong to when it is not the input: the first copy of a
    /// double covering that had to split boundary chords (its first vertices are the
    /// input's, in the input's order).
    pub mesh: Option<TriMesh>,
}

impl SeamedLayout {
    /// The texture coordinate of every corner (`3 f + k`), as a reader of the file sees it.
    pub fn corner_values(&self) -> Vec<Complex64> {
        self.tex_faces
            .iter()
            .flat_map(|t| t.map(|i| self.texcoords[i as usize]))
            .map(|t| Complex64::new(t[0], t[1]))
            .collect()
    }
}

impl GlobalMap {
    /// The seamed layout of the input's faces (see [`SeamedLayout`]); `input` is the mesh
    /// given to [`crate::global_map`].
    ///
    /// # Errors
    /// [`GlobalError::DegenerateFormBasis`] if the layout has no extent;
    /// [`GlobalError::Mesh`] if the refined first copy is not a valid mesh.
    pub fn seamed_layout(&self, input: &TriMesh) -> Result<SeamedLayout, GlobalError> {
        let nf = self.input_faces;
        let corner = self.input_corner_uv();
        let mut index = vec![u32::MAX; self.cut.mesh.num_vertices()];
        let mut layout: Vec<Complex64> = Vec::new();
        let tex_faces: Vec<[u32; 3]> = self.cut.mesh.faces()[..nf]
            .iter()
            .enumerate()
            .map(|(f, t)| {
                std::array::from_fn(|k| {
                    let c = t[k] as usize;
                    if index[c] == u32::MAX {
                        index[c] = layout.len() as u32;
                        layout.push(corner[3 * f + k]);
                    }
                    index[c]
                })
            })
            .collect();
        let (lo, hi) = layout.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), z| {
                (
                    [lo[0].min(z.re), lo[1].min(z.im)],
                    [hi[0].max(z.re), hi[1].max(z.im)],
                )
            },
        );
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if !(extent > 0.0 && extent.is_finite()) {
            return Err(GlobalError::DegenerateFormBasis {
                reason: "the layout has no extent",
            });
        }
        let scale = 1.0 / extent;
        let texcoords = layout
            .iter()
            .map(|z| [(z.re - lo[0]) * scale, (z.im - lo[1]) * scale])
            .collect();
        let surface_faces = &self.surface.faces()[..nf];
        let same = self.split_edges == 0
            && self.input_vertices == input.num_vertices()
            && surface_faces == input.faces();
        let mesh = if same {
            None
        } else {
            Some(TriMesh::try_new(
                self.surface.positions()[..self.input_vertices].to_vec(),
                surface_faces.to_vec(),
            )?)
        };
        Ok(SeamedLayout {
            texcoords,
            tex_faces,
            layout,
            offset: lo,
            scale,
            mesh,
        })
    }
}
