//! samplab's errors as Python exceptions: `samplab.Error` and its typed subclasses, with
//! the hints that name Python's keywords.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

// named in the package it is raised from, so that it pickles (Dask sends it between processes)
create_exception!(samplab, Error, PyValueError, "Every samplab error: its message names what is wrong and where.");

/// An error as `samplab.Error`, or as the subclass of it (defined in the package) that also
/// derives from the matching built-in for the library's unknown names (`LookupError`),
/// memory refusals (`MemoryError`), file failures (`OSError`) and work limits, with the
/// failure's fields as attributes.
pub(crate) fn err<E: std::fmt::Display + 'static>(e: E) -> PyErr {
    let any = &e as &dyn std::any::Any;
    let library = any.downcast_ref::<samplab::Error>().or_else(|| match any.downcast_ref::<samplab_render::Error>() {
        Some(samplab_render::Error::Samplab(e)) => Some(e),
        _ => match any.downcast_ref::<samplab_report::Error>() {
            Some(samplab_report::Error::Samplab(e)) => Some(e),
            _ => None,
        },
    });
    let (file, message) = match any.downcast_ref::<samplab_render::Error>() {
        Some(samplab_render::Error::Image { path, .. }) => (Some(path.clone()), e.to_string()),
        Some(e @ samplab_render::Error::PathOutsideScene { .. }) => {
            (None, format!("{e}; allow it with allow_paths_outside_scene=True"))
        }
        _ => (None, library.map_or_else(|| e.to_string(), in_keywords)),
    };
    typed(library.map(samplab::Error::innermost), file, &message).unwrap_or_else(|| Error::new_err(message))
}

/// A library error's message, with the hints that name Python's keywords.
pub(crate) fn in_keywords(e: &samplab::Error) -> String {
    match e {
        samplab::Error::WorkLimit { .. } => format!("{e}; raise it with max_work"),
        samplab::Error::InSet { set, error } => format!("set {set}: {}", in_keywords(error)),
        samplab::Error::ForeignEntry { folder, entry } => {
            format!(
                "{folder}: holds '{entry}', which samplab did not write; name a new folder, or pass force=True to replace it"
            )
        }
        e => e.to_string(),
    }
}

/// The typed exception for a library failure, when it has one.
pub(crate) fn typed(library: Option<&samplab::Error>, file: Option<String>, message: &str) -> Option<PyErr> {
    use samplab::Error as E;
    Python::attach(|py| -> PyResult<Option<PyErr>> {
        let make = |class: &str| py.import("samplab")?.getattr(class)?.call1((message,));
        let instance = match (library, file.as_ref()) {
            (Some(E::UnknownName { kind, name, suggestions }), _) => {
                let e = make("UnknownNameError")?;
                e.setattr("kind", *kind)?;
                e.setattr("name", name)?;
                e.setattr("suggestions", suggestions.clone())?;
                e
            }
            (Some(E::Memory { need, available, .. }), _) => {
                let e = make("MemoryLimitError")?;
                e.setattr("need", *need)?;
                e.setattr("available", *available)?;
                e
            }
            (Some(E::WorkLimit { work, limit, .. }), _) => {
                let e = make("WorkLimitError")?;
                e.setattr("work", *work)?;
                e.setattr("limit", *limit)?;
                e
            }
            (Some(E::Io { path, .. }), _) | (None, Some(path)) => {
                let e = make("FileError")?;
                e.setattr("path", path)?;
                e
            }
            _ => return Ok(None),
        };
        Ok(Some(PyErr::from_value(instance)))
    })
    .ok()
    .flatten()
}
