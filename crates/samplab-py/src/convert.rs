//! Values between Python and the library's serde types, without JSON text between them:
//! keywords read as `serde_json::Value`, results returned as Python objects (dicts, lists,
//! numbers, strings) built directly from the library's values.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString};
use serde_json::Value;

use crate::errors::err;

/// A keyword's value as JSON: None, a bool, a whole number, a finite float (NaN and the
/// infinities are refused: JSON has none), a string, or a list, tuple or dict (of string
/// keys) of them; a refusal names the keyword `name`.
pub(crate) fn json_of(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Value> {
    Ok(if value.is_none() {
        Value::Null
    } else if value.is_instance_of::<PyBool>() {
        Value::Bool(value.extract()?)
    } else if let Ok(i) = value.extract::<i64>() {
        Value::from(i)
    } else if let Ok(u) = value.extract::<u64>() {
        Value::from(u)
    } else if value.is_instance_of::<PyFloat>() {
        let x: f64 = value.extract()?;
        Value::Number(
            serde_json::Number::from_f64(x).ok_or_else(|| err(format!("{name}: {x} is not a finite number")))?,
        )
    } else if value.is_instance_of::<PyString>() {
        Value::String(value.extract()?)
    } else if let Ok(d) = value.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            map.insert(k.extract()?, json_of(name, &v)?);
        }
        Value::Object(map)
    } else if let Ok(items) = value.try_iter() {
        Value::Array(items.map(|v| json_of(name, &v?)).collect::<PyResult<_>>()?)
    } else {
        return Err(err(format!("{name}: {} is not a number, a string, or a list or dict of them", value.repr()?)));
    })
}

/// A JSON value as the Python object `json.loads` would make of its text.
pub(crate) fn py_of<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (_, Some(i)) => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Array(items) => {
            PyList::new(py, items.iter().map(|v| py_of(py, v)).collect::<PyResult<Vec<_>>>()?)?.into_any()
        }
        Value::Object(map) => {
            let d = PyDict::new(py);
            for (k, v) in map {
                d.set_item(k, py_of(py, v)?)?;
            }
            d.into_any()
        }
    })
}

/// A library value as a Python object, through its serde form.
pub(crate) fn py_from<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    py_of(py, &serde_json::to_value(value).map_err(err)?)
}

/// The library's JSON text (what the CLI prints) as a Python object.
pub(crate) fn py_from_text<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py_of(py, &serde_json::from_str(text).map_err(err)?)
}
