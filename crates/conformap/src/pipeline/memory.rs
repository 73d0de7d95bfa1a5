//! The memory check of a run: refuse, before reading and before solving, what the
//! library's peak-memory models say would not fit (the models live with the solvers:
//! `conformap_operators::PeakMemory`, `conformap_disk::DiskMethod::peak_bytes`, …).

use std::path::Path;

use conformap_operators::{available_memory, peak_rss_bytes};

use crate::failure::Failure;
use crate::report::MemoryReport;

/// The estimates of a run and the limit they were held against.
#[derive(Debug, Clone, Copy)]
pub struct MemoryCheck {
    /// Peak of reading the file ([`conformap_io::READ_PEAK_BYTES_PER_FILE_BYTE`] × size).
    pub read_estimate: u64,
    /// Peak of the whole run (at least `read_estimate`).
    pub estimate: u64,
    /// The input file's size: an OBJ's text stays in memory until the write, which copies
    /// the vertices' numbers from it (`conformap_io::VertexText`).
    pub file_bytes: u64,
    /// The limit, and where it came from; `None` when unknown (no check).
    pub limit: Option<(u64, &'static str)>,
}

impl MemoryCheck {
    /// Checks that reading `path` fits in `max_memory` or (without it) the memory
    /// available now, before anything is read.
    pub fn before_reading(path: &Path, max_memory: Option<u64>) -> Result<Self, Failure> {
        Self::before_reading_all(&[path], max_memory)
    }

    /// Checks that reading every file of `paths` (all kept in memory together, as `morph`
    /// keeps its key surfaces) fits in `max_memory` or the memory available now, before
    /// anything is read.
    pub fn before_reading_all(paths: &[&Path], max_memory: Option<u64>) -> Result<Self, Failure> {
        let limit = match max_memory {
            Some(m) => Some((m, "--max-memory")),
            None => available_memory(),
        };
        let (mut size, mut file_bytes) = (0u64, 0u64);
        for path in paths {
            let bytes = std::fs::metadata(path).map_or(0, |m| m.len());
            size = size.saturating_add(bytes);
            if let Ok(conformap_io::Format::Obj) = conformap_io::Format::from_path(path) {
                file_bytes = file_bytes.saturating_add(bytes);
            }
        }
        let read_estimate = conformap_io::READ_PEAK_BYTES_PER_FILE_BYTE.saturating_mul(size);
        let check = Self {
            read_estimate,
            estimate: read_estimate,
            file_bytes,
            limit,
        };
        let what = match paths.len() {
            1 => format!("reading this {} file", human_bytes(size)),
            n => format!("reading these {n} files ({} in all)", human_bytes(size)),
        };
        check.refuse_above(read_estimate, &what)?;
        Ok(check)
    }

    /// Refuses the run, before anything is assembled or factored, if `solve_estimate`
    /// (bytes, from the command's model) plus the file kept for the write is above the
    /// limit; `what` names the work.
    pub fn before_solving(mut self, solve_estimate: u64, what: &str) -> Result<Self, Failure> {
        self.estimate = solve_estimate
            .saturating_add(self.file_bytes)
            .max(self.read_estimate);
        self.refuse_above(self.estimate, what)?;
        Ok(self)
    }

    fn refuse_above(&self, estimate: u64, what: &str) -> Result<(), Failure> {
        match self.limit {
            Some((limit, from)) if estimate > limit => Err(Failure::BadInput(
                format!(
                    "{what} needs an estimated {} at peak, more than the {} allowed \
                     ({from}); nothing was computed",
                    human_bytes(estimate),
                    human_bytes(limit)
                ),
                Some(
                    "free memory or use a larger machine, or decimate the mesh; if the \
                     estimate is too cautious, --max-memory SIZE raises the limit"
                        .to_string(),
                ),
            )),
            _ => Ok(()),
        }
    }

    /// The `memory` object of a report, with the peak measured now.
    pub fn report(&self) -> MemoryReport {
        MemoryReport {
            estimated_peak_bytes: self.estimate,
            limit_bytes: self.limit.map(|l| l.0),
            limit_source: self.limit.map(|l| l.1),
            peak_rss_bytes: peak_rss_bytes(),
        }
    }
}

/// `1.23 GiB`, `45.6 MiB`, `789 KiB`, `12 B` (below a KiB: never `0 KiB`).
pub fn human_bytes(b: u64) -> String {
    let b = b as f64;
    if b >= 1073741824.0 {
        format!("{:.2} GiB", b / 1073741824.0)
    } else if b >= 1048576.0 {
        format!("{:.1} MiB", b / 1048576.0)
    } else if b >= 1024.0 {
        format!("{:.0} KiB", b / 1024.0)
    } else {
        format!("{b} B")
    }
}
