//! Failures of a command, classified by exit code, and every mapping from a library error
//! to a failure (and so to an exit code and a hint): the one place where that is decided.

use std::fmt;
use std::path::Path;

use conformap_render::RenderError;

/// Why a job failed, and so its exit class: the message names the file and the element
/// (line, vertex, face); [`Failure::hint`] says what to do.
#[derive(Debug, thiserror::Error)]
pub enum Failure {
    /// Bad input: unreadable or invalid file, wrong topology for the command (exit 1). The
    /// second field is the hint.
    #[error("{0}")]
    BadInput(String, Option<String>),
    /// Usage error not caught by the argument parser (exit 2).
    #[error("{0}")]
    Usage(String),
    /// A numerical failure, e.g. a solver that did not converge under `--strict` (exit 3).
    #[error("{0}")]
    Numerical(String),
}

impl Failure {
    /// The process exit code of this failure.
    pub fn exit_code(&self) -> u8 {
        match self {
            Self::BadInput(..) => 1,
            Self::Usage(_) => 2,
            Self::Numerical(_) => 3,
        }
    }

    /// What the user can do, when there is something to say.
    pub fn hint(&self) -> Option<&str> {
        match self {
            Self::BadInput(_, hint) => hint.as_deref(),
            _ => None,
        }
    }

    /// The same failure with its message prefixed by the file it concerns.
    pub fn in_file(self, path: &std::path::Path) -> Self {
        let p = path.display();
        match self {
            Self::BadInput(m, h) => Self::BadInput(format!("{p}: {m}"), h),
            Self::Usage(m) => Self::Usage(format!("{p}: {m}")),
            Self::Numerical(m) => Self::Numerical(format!("{p}: {m}")),
        }
    }

    /// A bad-input failure with a message.
    pub fn input(msg: impl fmt::Display) -> Self {
        Self::BadInput(msg.to_string(), None)
    }
}

impl From<conformap_io::IoError> for Failure {
    fn from(e: conformap_io::IoError) -> Self {
        let hint = io_hint(&e);
        Self::BadInput(e.to_string(), Some(hint.to_string()))
    }
}

/// What the user can do about a read error (the message says what and where): the
/// library's hint ([`conformap_io::IoError::hint`]), except for a mesh that fails validation,
/// where [`mesh_hint`] names the CLI's repair when there is one, and for map files, where the
/// CLI's `metrics` also reads seamed maps.
fn io_hint(e: &conformap_io::IoError) -> &'static str {
    use conformap_io::{IoError as E, UvProblem};
    match e {
        E::InvalidMesh { source, .. } => mesh_hint(source).unwrap_or(e.hint()),
        E::NotPerVertexUv {
            problem: UvProblem::Missing { .. },
            ..
        } => {
            "give every face corner a texture coordinate (f v/vt), or pass the map as a flat \
             mesh without any"
        }
        E::NotPerVertexUv { .. } => {
            "export the map with one texture coordinate per vertex (no seams), or pass it as \
             a flat mesh; `conformap metrics` also judges seamed maps"
        }
        _ => e.hint(),
    }
}

/// What the user can do about a validation error: `--repair` where a safe, standard repair
/// exists, the manual fix otherwise.
pub fn mesh_hint(e: &conformap_mesh::MeshError) -> Option<&'static str> {
    use conformap_mesh::MeshError as E;
    Some(match e {
        E::NoVertices => {
            "the file holds no vertex: check that it is the mesh you meant (an OBJ needs `v` \
             lines, a glTF a triangle primitive with POSITION)"
        }
        E::NoFaces { .. } => "export the surface with its faces, not a point cloud",
        E::TooManyVertices { .. } => "split the mesh into parts of fewer than 2^32 vertices",
        E::NonFiniteCoordinate { .. } => {
            "fix or delete that vertex in the file (NaN or infinity usually comes from a \
             failed export); --repair cannot invent a position"
        }
        E::IndexOutOfRange { .. } => {
            "the face refers to a vertex the file does not have: the file is truncated or \
             its indices are off; re-export it"
        }
        E::RepeatedVertexInFace { .. } | E::ZeroAreaFace { .. } => {
            "delete that face or collapse it in a mesh editor (e.g. Blender: Mesh > Clean Up \
             > Degenerate Dissolve); --repair leaves degenerate faces alone because removing \
             them changes the surface"
        }
        E::DuplicateFace { .. } => {
            "`conformap disk --repair` (or `info --repair`) drops exact duplicate faces (the \
             first copy is kept)"
        }
        E::UnreferencedVertex { .. } => {
            "`conformap disk --repair` (or `info --repair`) drops unreferenced vertices \
             (--vertex-map FILE then relates output vertices to input ones)"
        }
        E::NonManifoldEdge { .. } => {
            "delete the extra faces on that edge or split it apart in a mesh editor (Blender: \
             Select > All by Trait > Non Manifold); no automatic repair is safe, but \
             `conformap atlas` accepts it: it cuts the edge into manifold sheets (its report \
             says where)"
        }
        E::NonManifoldVertex { .. } => {
            "split the vertex into one per fan of faces (Blender: Mesh > Split > Faces by \
             Edges) or delete one fan; no automatic repair is safe, but `conformap atlas` \
             accepts it: it splits the vertex into one per fan (its report says where)"
        }
        E::InconsistentOrientation { .. } => {
            "`conformap disk --repair` (or `info --repair`) re-orients the faces consistently \
             (impossible only on a non-orientable surface such as a Möbius strip)"
        }
        _ => return None,
    })
}

impl From<conformap_disk::DiskError> for Failure {
    fn from(e: conformap_disk::DiskError) -> Self {
        use conformap_disk::DiskError as E;
        match e {
            E::WrongTopology { .. } | E::NoInteriorVertex => {
                let hint = match &e {
                    E::WrongTopology { found } => topology_hint(found),
                    _ => "refine the mesh (subdivide) so that some vertex lies off the \
                          boundary"
                        .to_string(),
                };
                Self::BadInput(e.to_string(), Some(hint))
            }
            E::NotGenusZero { .. } => Self::BadInput(
                e.to_string(),
                Some(
                    "a disk map needs genus 0 and at least one boundary loop: `conformap \
                     global` maps surfaces with handles, `conformap sphere` closed genus-0 \
                     ones; `conformap info MESH` shows the topology"
                        .to_string(),
                ),
            ),
            E::InvalidOption { name, reason } => {
                Self::Usage(format!("invalid option {}: {reason}", option_flag(name)))
            }
            E::OuterLoopOutOfRange { .. } => Self::Usage(e.to_string()),
            E::UnknownBoundary { .. } => Self::Usage(e.to_string()),
            E::Fill(_)
            | E::VertexOutOfRange { .. }
            | E::NotOnBoundary { .. }
            | E::MissingBoundaryValue { .. }
            | E::NonFiniteBoundaryValue { .. }
            | E::BadCorners { .. }
            | E::TurningSum { .. }
            | E::BoundaryFile { .. } => {
                let text = e.to_string();
                // these messages carry their hint inline: it goes on its own `hint:` line
                match text.split_once("; hint: ") {
                    Some((what, hint)) => Self::BadInput(what.to_string(), Some(hint.to_string())),
                    None => Self::BadInput(text, None),
                }
            }
            other => Self::Numerical(other.to_string()),
        }
    }
}

/// The failure for a mesh [`conformap_mesh::repair`] could not repair, naming the file
/// place of the element (the repair reports input numbering).
pub fn repair_failure(raw: &conformap_io::RawMesh, e: conformap_mesh::MeshError) -> Failure {
    use conformap_mesh::MeshError;
    match e {
        MeshError::NonOrientable { .. } => {
            let place = match raw.origin_of(&e) {
                Some(conformap_io::Origin::Line(l)) => format!(":{l}"),
                Some(o) => format!(" ({o})"),
                None => String::new(),
            };
            Failure::BadInput(
                format!("{}{place}: {e}", raw.source.path.display()),
                Some(
                    "a non-orientable surface has no conformal map to the disk; cut it open \
                     along a seam through that edge first"
                        .to_string(),
                ),
            )
        }
        other => raw.invalid_mesh(other).into(),
    }
}

/// The hint for a mesh of the wrong topology, for every command that refuses one: the
/// command that maps a mesh of topology `found`, then where to see the topology.
///
/// # Examples
/// ```
/// use conformap_mesh::Topology;
/// let hint = conformap::failure::topology_hint(&Topology::ClosedHigherGenus { genus: 1 });
/// assert!(hint.contains("`conformap global`"));
/// ```
pub fn topology_hint(found: &conformap_mesh::Topology) -> String {
    use conformap_mesh::Topology as T;
    let which = match found {
        T::Disk => "`conformap disk` maps a disk onto the unit disk (`conformap flatten` \
                    flattens it with a free or prescribed boundary)"
            .to_string(),
        T::Sphere => "`conformap sphere` maps a closed genus-0 surface onto the unit sphere \
                      (`conformap atlas` charts it flat through cuts)"
            .to_string(),
        T::MultiplyConnected { .. } => "`conformap disk` maps a genus-0 surface with several \
                                        boundary loops onto a disk with circular holes \
                                        (`conformap flatten` flattens it, `conformap global` \
                                        maps it by double covering)"
            .to_string(),
        T::ClosedHigherGenus { genus } => format!(
            "`conformap global` maps a closed surface of genus {genus} (a holomorphic 1-form, \
             seamed); `conformap atlas` charts it flat through cuts"
        ),
        T::OpenHigherGenus { genus, .. } => format!(
            "`conformap global` maps a surface of genus {genus} with boundary (by double \
             covering); `conformap atlas` charts it flat through cuts"
        ),
        T::SeveralComponents { components } => format!(
            "`conformap atlas` charts all {components} components; or rerun with --repair to \
             keep the largest component (by face count) and map it alone"
        ),
        _ => "`conformap atlas` charts any mesh".to_string(),
    };
    format!("{which}; `conformap info MESH` shows the topology")
}

impl From<conformap_sphere::SphereError> for Failure {
    /// Wrong topology, bad options and bad given maps or regions are bad input (exit 1),
    /// everything else numerical (exit 3).
    fn from(e: conformap_sphere::SphereError) -> Self {
        use conformap_sphere::SphereError as E;
        match e {
            E::WrongTopology { found, .. } => {
                let hint = topology_hint(&found);
                Self::BadInput(e.to_string(), Some(hint))
            }
            E::MapLength { .. }
            | E::NonFiniteMap { .. }
            | E::NotOnSphere { .. }
            | E::NotInDisk { .. }
            | E::RegionFaceOutOfRange { .. }
            | E::DegenerateRegion { .. }
            | E::InvalidOption { .. } => Self::BadInput(e.to_string(), None),
            other => Self::Numerical(other.to_string()),
        }
    }
}

impl From<conformap_global::GlobalError> for Failure {
    /// Wrong topology, bad options and bad zero targets are bad input (exit 1), a genus-0
    /// step's failure as [`conformap_sphere::SphereError`] says, everything else numerical
    /// (exit 3).
    fn from(e: conformap_global::GlobalError) -> Self {
        use conformap_global::GlobalError as E;
        match e {
            E::Sphere(inner) => inner.into(),
            E::WrongTopology { found, .. } => {
                let hint = topology_hint(&found);
                Self::BadInput(e.to_string(), Some(hint))
            }
            E::InvalidOption { .. } | E::ZeroTargetOutOfRange { .. } => {
                Self::BadInput(e.to_string(), None)
            }
            other => Self::Numerical(other.to_string()),
        }
    }
}

impl From<conformap_metrics::MetricsError> for Failure {
    /// The metrics of a map the solver computed cannot fail on good input: numerical.
    fn from(e: conformap_metrics::MetricsError) -> Self {
        Self::Numerical(e.to_string())
    }
}

/// The failure of a render error for output `path`: options are usage errors (2), a map
/// that cannot be drawn is bad input (1).
pub fn render_failure(e: RenderError, path: &Path) -> Failure {
    let hint = match &e {
        RenderError::NotOnSphere { .. } => {
            "pass a sphere map (the --flat output of `sphere`), or --domain plane for a \
             planar map"
        }
        RenderError::Collapsed => "check the map: every vertex has the same image",
        RenderError::NonFiniteValue { .. } => "recompute the map: it holds NaN or infinity",
        RenderError::InvalidOption { name, reason } => {
            return Failure::Usage(format!("invalid option {}: {reason}", option_flag(name)))
        }
        _ => "check that the output's directory is writable",
    };
    Failure::BadInput(
        format!("cannot draw {}: {e}", path.display()),
        Some(hint.to_string()),
    )
}

/// The command-line flag of a library option field (`max_sweeps` → `--max-iter`,
/// `azimuth_deg` → `--azimuth`), so that messages name what the user typed.
pub fn option_flag(name: &str) -> String {
    match name {
        "max_sweeps" | "max_iter" => "--max-iter".to_string(),
        other => format!("--{}", other.trim_end_matches("_deg").replace('_', "-")),
    }
}
