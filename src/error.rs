//! Error types of the library, one enum per layer.
//!
//! Input errors always name the place (file, line, column or key) and the offending value, so
//! that the command line can print one clear message and exit non-zero.

use std::fmt;
use std::path::PathBuf;

/// Where in the user's input a problem was found.
#[derive(Debug, Clone, PartialEq)]
pub enum Location {
    /// A file as a whole (missing, unreadable, empty).
    File(PathBuf),
    /// A line of a text file, optionally a named column (1-based line numbers).
    Line {
        /// File path as given by the user (or resolved from the case file).
        file: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Column name as written in the header, if the problem is in one column.
        column: Option<String>,
    },
    /// A key of a TOML case file, e.g. `string[2].od`.
    Key {
        /// Case file path.
        file: PathBuf,
        /// Dotted key path.
        key: String,
    },
    /// An element of an XML file (WITSML), at a line: e.g. element `azi` of the
    /// `trajectoryStation` with uid `S-12`.
    Element {
        /// File path as given by the user (or resolved from the case file).
        file: PathBuf,
        /// 1-based line number where the element (or its parent, when it is missing) starts.
        line: usize,
        /// The element, in words: e.g. ``element `azi` of station `S-12` (MD 150.66 m)``.
        element: String,
    },
    /// A command-line option, e.g. `--to`.
    Option(String),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::File(p) => write!(f, "{}", p.display()),
            Location::Line {
                file,
                line,
                column: Some(c),
            } => {
                write!(f, "{}: line {}, column `{}`", file.display(), line, c)
            }
            Location::Line {
                file,
                line,
                column: None,
            } => write!(f, "{}: line {}", file.display(), line),
            Location::Key { file, key } => write!(f, "{}: key `{}`", file.display(), key),
            Location::Element { file, line, element } => write!(f, "{}: line {}, {}", file.display(), line, element),
            Location::Option(o) => write!(f, "option {o}"),
        }
    }
}

/// A problem with user input: a file, a value, a key. Always carries its [`Location`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{location}: {message}")]
pub struct InputError {
    /// Where the problem is.
    pub location: Location,
    /// What is wrong, in words a user understands.
    pub message: String,
}

impl InputError {
    /// Build an error at `location` with `message`.
    pub fn new(location: Location, message: impl Into<String>) -> Self {
        Self {
            location,
            message: message.into(),
        }
    }
    /// Error about a whole file.
    pub fn file(file: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Self::new(Location::File(file.into()), message)
    }
    /// Error at a key of a case file.
    pub fn key(file: impl Into<PathBuf>, key: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(
            Location::Key {
                file: file.into(),
                key: key.into(),
            },
            message,
        )
    }
    /// Error at a line (and optionally column) of a text file.
    pub fn line(file: impl Into<PathBuf>, line: usize, column: Option<&str>, message: impl Into<String>) -> Self {
        Self::new(
            Location::Line {
                file: file.into(),
                line,
                column: column.map(str::to_string),
            },
            message,
        )
    }
    /// Error at an element of an XML file: `element` describes it in words (see
    /// [`Location::Element`]).
    pub fn element(
        file: impl Into<PathBuf>,
        line: usize,
        element: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Self::new(
            Location::Element {
                file: file.into(),
                line,
                element: element.into(),
            },
            message,
        )
    }
    /// Error in a command-line option.
    pub fn option(option: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(Location::Option(option.into()), message)
    }
}

/// Result alias for input handling.
pub type InputResult<T> = Result<T, InputError>;
