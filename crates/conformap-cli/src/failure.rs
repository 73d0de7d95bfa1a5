//! Failures of a command, classified by exit code.

use std::fmt;

/// Why a command failed, and so which exit code it returns.
#[derive(Debug)]
pub enum Failure {
    /// Bad input: unreadable or invalid file, wrong topology for the command (exit 1).
    BadInput(String, Option<String>),
    /// Usage error not caught by the argument parser (exit 2).
    Usage(String),
    /// A numerical failure, e.g. a solver that did not converge under `--strict` (exit 3).
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

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadInput(m, _) | Self::Usage(m) | Self::Numerical(m) => f.write_str(m),
        }
    }
}

impl From<conformap_io::IoError> for Failure {
    fn from(e: conformap_io::IoError) -> Self {
        Self::BadInput(e.to_string(), None)
    }
}

impl From<conformap_disk::DiskError> for Failure {
    fn from(e: conformap_disk::DiskError) -> Self {
        use conformap_disk::DiskError as E;
        match e {
            E::WrongTopology { .. } | E::NoInteriorVertex => {
                let hint = match &e {
                    E::WrongTopology { .. } => Some(
                        "`conformap info MESH` shows the topology; a disk map needs one \
                         boundary loop and genus 0"
                            .to_string(),
                    ),
                    _ => None,
                };
                Self::BadInput(e.to_string(), hint)
            }
            other => Self::Numerical(other.to_string()),
        }
    }
}
