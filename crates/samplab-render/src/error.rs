//! The renderer's typed errors; each message is one line naming what is wrong and where.

use thiserror::Error;

/// Everything that can go wrong in the renderer.
#[derive(Debug, Error)]
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
    /// An option or value out of range.
    #[error("{0}")]
    Invalid(String),
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
