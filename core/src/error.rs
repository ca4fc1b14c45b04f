//! Typed errors: every rejection names the parameter, its value and the allowed range.

use thiserror::Error;

/// Why a job cannot be planned.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum JobError {
    /// A parameter is outside its allowed range.
    #[error("invalid {name} = {value}: must be {allowed}")]
    OutOfRange {
        /// Parameter name as used in job files and on the command line.
        name: &'static str,
        /// The rejected value, as given.
        value: String,
        /// The allowed range, in words, with the limits computed for this job.
        allowed: String,
    },
    /// A job file could not be read as a job.
    #[error("job file: {0}")]
    File(String),
}

impl JobError {
    /// Shorthand for [`JobError::OutOfRange`].
    pub fn range(name: &'static str, value: impl ToString, allowed: impl Into<String>) -> JobError {
        JobError::OutOfRange { name, value: value.to_string(), allowed: allowed.into() }
    }

    /// The parameter this error is about, if any.
    pub fn parameter(&self) -> Option<&'static str> {
        match self {
            JobError::OutOfRange { name, .. } => Some(name),
            JobError::File(_) => None,
        }
    }
}
