//! One module per subcommand.

pub mod disk;
pub mod disk_holes;
pub mod info;
pub mod metrics;
pub mod mobius;
pub mod sphere;

use std::path::Path;

use crate::failure::Failure;

/// Prints `text` and a newline to stdout; a closed pipe (`conformap info m.obj | head`) is
/// not an error worth a panic, so write errors are ignored.
pub fn say(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{text}");
}

/// Writes `value` as pretty JSON to `path` atomically (temporary sibling, then rename).
pub fn write_json(path: &Path, value: &serde_json::Value) -> Result<(), Failure> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Failure::Numerical(format!("cannot serialize the report: {e}")))?;
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    let result = std::fs::write(&tmp, text + "\n").and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Failure::input(format!(
            "cannot write {}: {e}",
            path.display()
        )));
    }
    Ok(())
}
