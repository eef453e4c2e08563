//! The renderer's typed errors; each message is one line naming what is wrong and where.

use thiserror::Error;

/// Everything that can go wrong in the renderer.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum Error {
    /// A scene file (Mitsuba XML or OBJ) that is malformed or asks for what is unsupported.
    #[error("{file}:{line}: {message}")]
    Scene {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// What is wrong, naming the element.
        message: String,
    },
    /// A scene file naming a file outside its folder: read only where the caller allows it
    /// ([`crate::mitsuba::Paths::Anywhere`]; each front end names its switch).
    #[error("{file}:{line}: filename {name} {why}")]
    PathOutsideScene {
        /// The scene file.
        file: String,
        /// 1-based line.
        line: usize,
        /// The file named, shortened for display.
        name: String,
        /// How it leads out.
        why: &'static str,
    },
    /// An image that cannot be read, written or compared.
    #[error("{path}: {message}")]
    Image {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// A sampler or warp error from the library.
    #[error(transparent)]
    Samplab(#[from] samplab::Error),
}

/// The renderer's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// The refusal of the render setting `name` = `value` (named as in [`crate::Settings`]).
pub(crate) fn setting(name: &'static str, value: impl ToString, reason: impl Into<String>) -> Error {
    Error::Samplab(samplab::Error::Setting { name, value: value.to_string(), reason: reason.into() })
}
