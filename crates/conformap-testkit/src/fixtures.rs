//! Where test meshes live, and a minimal reader for plain `v`/`f` OBJ files.
//!
//! Two places hold real meshes:
//! - `fixtures/` at the workspace root: small committed copies (source and licence beside
//!   them), always present; use [`fixture_path`].
//! - `../shared/meshes/` next to the workspace root: larger meshes shared by the developers,
//!   absent on a fresh clone; use [`shared_mesh_path`] or [`shared_mesh_or_skip`] and skip the
//!   test (saying so) when they are missing.
//!
//! [`read_plain_obj`] reads the subset of OBJ these files use (`v x y z` and `f i j k` lines)
//! so that test code needs no dependency on `conformap-io`.

use std::path::{Path, PathBuf};

use conformap_mesh::{MeshError, TriMesh};

/// The workspace root: two levels above this crate's manifest (`crates/conformap-testkit`).
pub fn workspace_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .nth(2)
        .map_or_else(|| manifest.to_path_buf(), Path::to_path_buf)
}

/// Path of a committed fixture: `<workspace>/fixtures/<name>` (whether or not it exists).
///
/// # Examples
/// ```
/// let p = conformap_testkit::fixture_path("woody.obj");
/// assert!(p.ends_with("fixtures/woody.obj"));
/// ```
pub fn fixture_path(name: &str) -> PathBuf {
    workspace_root().join("fixtures").join(name)
}

/// Class a of `../shared/meshes/` (disk topology: one boundary loop, genus 0), as listed in
/// `shared/meshes/README.md`, smallest first.
pub const CLASS_A: [&str; 9] = [
    "woody.obj",
    "alligator.obj",
    "spothead.obj",
    "maze.obj",
    "camelhead.obj",
    "human_face.obj",
    "chinese_lion.obj",
    "hand.obj",
    "igea_open.obj",
];

/// Class c of `../shared/meshes/` (genus-0 closed surfaces), as listed in
/// `shared/meshes/README.md`.
pub const CLASS_C: [&str; 4] = ["spot.obj", "david_head.obj", "armadillo.obj", "brain.obj"];

/// Path of a shared real mesh, `<workspace>/../shared/meshes/<name>`, or `None` if that file
/// does not exist (fresh clone, CI without the mesh collection).
pub fn shared_mesh_path(name: &str) -> Option<PathBuf> {
    let root = workspace_root();
    let path = root.parent()?.join("shared").join("meshes").join(name);
    path.is_file().then_some(path)
}

/// Like [`shared_mesh_path`], but prints `SKIPPED <test>: <name> not found in ../shared/meshes`
/// to stderr when the mesh is absent, so the skip shows in `cargo test -- --nocapture`
/// output instead of passing silently.
///
/// ```
/// # fn real_mesh_test() {
/// let Some(path) = conformap_testkit::shared_mesh_or_skip("hand.obj", "real_mesh_test") else {
///     return;
/// };
/// # let _ = path;
/// # }
/// ```
pub fn shared_mesh_or_skip(name: &str, test: &str) -> Option<PathBuf> {
    let found = shared_mesh_path(name);
    if found.is_none() {
        eprintln!("SKIPPED {test}: {name} not found in ../shared/meshes");
    }
    found
}

/// A real mesh by file name: the committed fixture if present, else the shared copy, else
/// `None` (with a `SKIPPED <test>` line on stderr).
pub fn real_mesh_or_skip(name: &str, test: &str) -> Option<PathBuf> {
    let fixture = fixture_path(name);
    if fixture.is_file() {
        return Some(fixture);
    }
    shared_mesh_or_skip(name, test)
}

/// Reads the committed fixture `fixtures/<name>` with [`read_plain_obj`].
///
/// # Panics
/// If the fixture is missing or invalid (a broken checkout), naming the file.
///
/// ```
/// let woody = conformap_testkit::fixture_mesh("woody.obj");
/// assert_eq!(woody.num_vertices(), 694);
/// ```
pub fn fixture_mesh(name: &str) -> TriMesh {
    read_or_panic(&fixture_path(name))
}

/// The shared mesh `name` read with [`read_plain_obj`], or `None` with the `SKIPPED` line
/// of [`shared_mesh_or_skip`] when it is absent.
///
/// # Panics
/// If the file is there but invalid, naming it.
pub fn read_shared_mesh_or_skip(name: &str, test: &str) -> Option<TriMesh> {
    shared_mesh_or_skip(name, test).map(|path| read_or_panic(&path))
}

/// The real mesh `name` (as [`real_mesh_or_skip`]: the fixture, else the shared copy) read
/// with [`read_plain_obj`], or `None` with a `SKIPPED` line when neither exists.
///
/// # Panics
/// If the file is there but invalid, naming it.
pub fn read_real_mesh_or_skip(name: &str, test: &str) -> Option<TriMesh> {
    real_mesh_or_skip(name, test).map(|path| read_or_panic(&path))
}

fn read_or_panic(path: &Path) -> TriMesh {
    match read_plain_obj(path) {
        Ok(mesh) => mesh,
        Err(e) => panic!("{e}"),
    }
}

/// Why [`read_plain_obj`] failed.
#[derive(Debug)]
#[non_exhaustive]
pub enum FixtureError {
    /// The file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A `v` or `f` line could not be parsed (1-based line number).
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
    },
    /// The positions and faces do not form a valid [`TriMesh`].
    Mesh {
        /// The file.
        path: PathBuf,
        /// The validation error.
        source: MeshError,
    },
}

impl std::fmt::Display for FixtureError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Parse { path, line } => {
                write!(f, "{}:{line}: malformed v or f line", path.display())
            }
            Self::Mesh { path, source } => write!(f, "{}: {source}", path.display()),
        }
    }
}

impl std::error::Error for FixtureError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            Self::Mesh { source, .. } => Some(source),
            Self::Parse { .. } => None,
        }
    }
}

/// Reads a plain OBJ: `v x y z` lines and `f a b c ...` lines (1-based or negative indices;
/// `a/b/c` tokens use their first number; polygons are fan-triangulated). Every other line
/// is ignored. Test support only: real input goes through `conformap-io`.
///
/// # Errors
/// [`FixtureError`] naming the file (and line) when it cannot be read, parsed or validated.
pub fn read_plain_obj(path: &Path) -> Result<TriMesh, FixtureError> {
    let text = std::fs::read_to_string(path).map_err(|source| FixtureError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<[u32; 3]> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let bad = || FixtureError::Parse {
            path: path.to_path_buf(),
            line: i + 1,
        };
        let mut tokens = line.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    *c = tokens.next().and_then(|t| t.parse().ok()).ok_or_else(bad)?;
                }
                positions.push(p);
            }
            Some("f") => {
                corners.clear();
                for t in tokens {
                    let first = t.split('/').next().unwrap_or(t);
                    let k: i64 = first.parse().map_err(|_| bad())?;
                    let n = positions.len() as i64;
                    let index = if k < 0 { n + k } else { k - 1 };
                    let index = u32::try_from(index).map_err(|_| bad())?;
                    corners.push(index);
                }
                if corners.len() < 3 {
                    return Err(bad());
                }
                for w in 1..corners.len() - 1 {
                    faces.push([corners[0], corners[w], corners[w + 1]]);
                }
            }
            _ => {}
        }
    }
    TriMesh::try_new(positions, faces).map_err(|source| FixtureError::Mesh {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn root_holds_the_workspace_manifest() {
        assert!(workspace_root().join("Cargo.toml").is_file());
        assert!(workspace_root().join("crates").is_dir());
    }

    #[test]
    fn missing_shared_mesh_is_none() {
        assert!(shared_mesh_path("no-such-mesh-3f1a.obj").is_none());
        assert!(
            real_mesh_or_skip("no-such-mesh-3f1a.obj", "missing_shared_mesh_is_none").is_none()
        );
    }

    #[test]
    fn reads_a_plain_obj_with_a_quad() -> Result<(), FixtureError> {
        let dir = std::env::temp_dir().join(format!("conformap-testkit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|source| FixtureError::Io {
            path: dir.clone(),
            source,
        })?;
        let path = dir.join("quad.obj");
        let text = "# a unit square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 -1//1\n";
        std::fs::write(&path, text).map_err(|source| FixtureError::Io {
            path: path.clone(),
            source,
        })?;
        let mesh = read_plain_obj(&path)?;
        assert_eq!(mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.boundary_loops().len(), 1);
        let _ = std::fs::remove_file(&path);
        Ok(())
    }

    #[test]
    fn parse_error_names_the_line() {
        let dir = std::env::temp_dir().join(format!("conformap-testkit-e{}", std::process::id()));
        let _ = std::fs::create_dir_all(&dir);
        let path = dir.join("bad.obj");
        let _ = std::fs::write(&path, "v 0 0 0\nv 1 zero 0\n");
        let err = read_plain_obj(&path).err().map(|e| e.to_string());
        assert!(err.is_some_and(|e| e.ends_with("bad.obj:2: malformed v or f line")));
        let _ = std::fs::remove_file(&path);
    }

    #[test]
    fn woody_reads_when_present() {
        let Some(path) = real_mesh_or_skip("woody.obj", "woody_reads_when_present") else {
            return;
        };
        let mesh = read_plain_obj(&path).map_err(|e| e.to_string());
        let mesh = match mesh {
            Ok(m) => m,
            Err(e) => panic!("{e}"),
        };
        assert_eq!((mesh.num_vertices(), mesh.num_faces()), (694, 1267));
        assert_eq!(mesh.boundary_loops().len(), 1);
    }
}
