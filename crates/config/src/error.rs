//! Errors of the configuration: unreadable files, TOML that does not parse, refused values.

use std::fmt;
use std::path::PathBuf;

/// One refused value: which field, what it was, what is allowed.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldError {
    /// Dotted path of the field in the pipeline file, e.g. `material.poisson`.
    pub field: String,
    /// The value as given.
    pub value: String,
    /// What would be accepted, e.g. `0 < poisson < 0.5`.
    pub allowed: String,
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {} is not allowed: {}", self.field, self.value, self.allowed)
    }
}

/// A value accepted that could mislead: which field, its value and why. `check`, `pipeline` and
/// `run` print it, and the report page shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// Dotted path of the field, e.g. `record.interval_s`.
    pub field: String,
    /// The value as given.
    pub value: String,
    /// What it does and what to do instead.
    pub why: String,
}

impl ConfigError {
    /// A TOML error: its message, with the numbers quoted in it (`` invalid type: floating point
    /// `1000…0.0` ``) written short; the file's line it shows is left as written.
    pub fn syntax(e: &toml::de::Error) -> ConfigError {
        let text = e.to_string();
        let mut out = String::with_capacity(text.len());
        let mut parts = text.split('`');
        out += parts.next().unwrap_or("");
        for (i, part) in parts.enumerate() {
            out.push('`');
            match part.parse::<f64>() {
                Ok(v) if i % 2 == 0 && part.len() > 12 => out += &crate::numbers::num(v),
                _ => out += part,
            }
        }
        ConfigError::Syntax(out)
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {}: {}", self.field, self.value, self.why)
    }
}

/// Everything that can go wrong reading a pipeline file.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("{}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The file is not valid TOML, has an unknown key, or a value of the wrong type.
    #[error("{}", .0.trim_end())]
    Syntax(String),
    /// Values that cannot be run; nothing was run.
    #[error("invalid pipeline:\n{}", .0.iter().map(|e| format!("  - {e}")).collect::<Vec<_>>().join("\n"))]
    Invalid(Vec<FieldError>),
    /// A file was refused (the cause says why).
    #[error("{}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// Why.
        source: Box<ConfigError>,
    },
}
