//! The inputs of `conformap batch`: meshes named on the command line or in manifests (one
//! path per line, or CSV with a `path` column), and the output names they get.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::failure::Failure;

/// One input of a batch and the stem of its outputs.
#[derive(Debug, Clone)]
pub struct BatchInput {
    /// The mesh, as given (manifest entries relative to the manifest's directory).
    pub mesh: PathBuf,
    /// The file stem: outputs are `DIR/<stem>.<ext>` and `DIR/<stem>.json`.
    pub stem: String,
}

/// Whether `path` names a manifest rather than a mesh: anything without a mesh extension
/// (`.obj`, `.gltf`, `.glb`, `.ply`, `.stl`, `.off`, `.gii`, FreeSurfer surface names).
pub fn is_manifest(path: &Path) -> bool {
    conformap_io::Format::from_path(path).is_err()
}

/// The inputs named by `args` (meshes and manifests, in order), with their stems.
///
/// # Errors
/// Bad input (1) for a manifest that cannot be read or has a CSV header without a `path`
/// column; usage (2) for no input at all, or two inputs with the same stem (their outputs
/// would overwrite each other).
pub fn collect_inputs(args: &[PathBuf]) -> Result<Vec<BatchInput>, Failure> {
    let mut meshes = Vec::new();
    for arg in args {
        if is_manifest(arg) {
            meshes.extend(read_manifest(arg)?);
        } else {
            meshes.push(arg.clone());
        }
    }
    if meshes.is_empty() {
        return Err(Failure::Usage(
            "no input: name meshes or a manifest with one path per line".to_string(),
        ));
    }
    let mut seen: HashMap<String, &Path> = HashMap::new();
    let mut inputs = Vec::with_capacity(meshes.len());
    for mesh in &meshes {
        let stem = mesh
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if let Some(other) = seen.insert(stem.clone(), mesh) {
            if same_file(other, mesh) {
                return Err(Failure::Usage(format!(
                    "{} is listed twice: each input once, please (its outputs DIR/{stem}.* \
                     would be written twice)",
                    mesh.display()
                )));
            }
            return Err(Failure::Usage(format!(
                "{} and {} have the same stem `{stem}`: their outputs DIR/{stem}.* would \
                 overwrite each other; rename one or run them in two batches",
                other.display(),
                mesh.display()
            )));
        }
        inputs.push(BatchInput {
            mesh: mesh.clone(),
            stem,
        });
    }
    Ok(inputs)
}

/// The meshes of a manifest: one path per line (blank lines and `#` comments skipped), or
/// CSV whose header has a `path` column (any case). Relative paths are relative to the
/// manifest's directory.
fn read_manifest(path: &Path) -> Result<Vec<PathBuf>, Failure> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Failure::BadInput(
            format!("cannot read the manifest {}: {e}", path.display()),
            Some(
                "a manifest is a text file with one mesh path per line (or CSV with a path \
                 column); meshes are .obj, .gltf or .glb"
                    .to_string(),
            ),
        )
    })?;
    let base = path.parent().unwrap_or(Path::new(""));
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .peekable();
    let csv = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
        || lines.peek().is_some_and(|l| l.contains(','));
    let column = if csv {
        let header = lines.next().unwrap_or_default();
        let k = split_csv(header)
            .iter()
            .position(|c| c.eq_ignore_ascii_case("path"));
        Some(k.ok_or_else(|| {
            Failure::BadInput(
                format!(
                    "{}: the CSV header `{header}` has no `path` column",
                    path.display()
                ),
                Some("name the column of mesh paths `path` in the first line".to_string()),
            )
        })?)
    } else {
        None
    };
    let mut meshes = Vec::new();
    for line in lines {
        let entry = match column {
            Some(k) => split_csv(line).get(k).cloned().unwrap_or_default(),
            None => line.to_string(),
        };
        if entry.is_empty() {
            continue;
        }
        let p = PathBuf::from(entry);
        meshes.push(if p.is_absolute() { p } else { base.join(p) });
    }
    Ok(meshes)
}

/// The fields of a CSV line (commas inside double quotes kept, quotes removed).
fn split_csv(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut quoted = false;
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => fields.push(String::new()),
            _ => fields.last_mut().map_or((), |f| f.push(c)),
        }
    }
    fields.iter().map(|f| f.trim().to_string()).collect()
}

/// Whether `a` and `b` name the same file (the same path, or both resolve to one).
fn same_file(a: &Path, b: &Path) -> bool {
    a == b
        || matches!(
            (a.canonicalize(), b.canonicalize()),
            (Ok(x), Ok(y)) if x == y
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_keep_quoted_commas() {
        assert_eq!(split_csv(r#"a, "b,c" ,d"#), vec!["a", "b,c", "d"]);
    }

    #[test]
    fn manifests_resolve_relative_paths_and_csv_columns() {
        let dir = std::env::temp_dir().join(format!("conformap-manifest-{}", std::process::id()));
        std::fs::create_dir_all(&dir).ok();
        let list = dir.join("list.txt");
        std::fs::write(&list, "# scans\na.obj\n\n/abs/b.glb\n").ok();
        let csv = dir.join("list.csv");
        std::fs::write(&csv, "id,Path\n1,c.obj\n2,\"d,e.obj\"\n").ok();
        let inputs = collect_inputs(&[list, csv]).ok().unwrap_or_default();
        let paths: Vec<PathBuf> = inputs.iter().map(|i| i.mesh.clone()).collect();
        assert_eq!(
            paths,
            vec![
                dir.join("a.obj"),
                PathBuf::from("/abs/b.glb"),
                dir.join("c.obj"),
                dir.join("d,e.obj")
            ]
        );
        assert_eq!(inputs[3].stem, "d,e");
        let same = collect_inputs(&[PathBuf::from("x/a.obj"), PathBuf::from("y/a.glb")]);
        assert!(matches!(same, Err(Failure::Usage(m)) if m.contains("same stem `a`")));
        std::fs::remove_dir_all(&dir).ok();
    }
}
