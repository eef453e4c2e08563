//! Point sets and pixels: the registries, pixel samplers, warps, and point files.

use crate::errors::err;
use crate::interrupt::interruptible;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use samplab::progress::Progress;
use samplab::registry::{Entry, Registry};
use samplab::spec::{Default, Kind};
use samplab::{PointSet, Seed};

/// The seed the CLI uses when none is given.
#[pyfunction]
pub(crate) fn default_seed() -> u64 {
    Seed::DEFAULT.0
}

/// One registry's entries as dictionaries: name, aliases, summary, parameters (name, kind,
/// default, range, doc), references, and the kind-specific details `samplab list` prints.
pub(crate) fn entries<'py, E: Entry>(py: Python<'py>, registry: &Registry<E>) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for e in registry.iter() {
        let a = e.about();
        let d = PyDict::new(py);
        d.set_item("name", a.name)?;
        d.set_item("aliases", a.aliases.to_vec())?;
        d.set_item("summary", a.summary)?;
        d.set_item("references", a.references.to_vec())?;
        d.set_item("details", e.details())?;
        let params = PyList::empty(py);
        for p in a.params {
            let q = PyDict::new(py);
            q.set_item("name", p.name)?;
            q.set_item("doc", p.doc)?;
            q.set_item("range", p.range_text())?;
            q.set_item("kind", p.kind.name())?;
            match p.kind {
                Kind::Real { min, max } | Kind::Reals { min, max } => {
                    q.set_item("min", min)?;
                    q.set_item("max", max)?;
                }
                Kind::Int { min, max } => {
                    q.set_item("min", min)?;
                    q.set_item("max", max)?;
                }
                Kind::Choice(c) => q.set_item("choices", c.to_vec())?,
                _ => {}
            }
            match p.default {
                Default::Number(x) => q.set_item("default", x)?,
                Default::Int(x) => q.set_item("default", x)?,
                _ => q.set_item("default", p.default_text())?,
            }
            params.append(q)?;
        }
        d.set_item("params", params)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The entries of one registry: samplers, metrics, warps, integrands, formats or scenes.
#[pyfunction]
pub(crate) fn registry<'py>(py: Python<'py>, kind: &str) -> PyResult<Bound<'py, PyList>> {
    match kind {
        "samplers" => entries(py, &samplab::sampler::SAMPLERS),
        "metrics" => entries(py, &samplab::discrepancy::METRICS),
        "warps" => entries(py, &samplab::warp::WARPS),
        "integrands" => entries(py, &samplab::integrand::INTEGRANDS),
        "formats" => entries(py, &samplab::io::FORMATS),
        "scenes" => entries(py, &samplab_render::scenes::SCENES),
        "pixels" => entries(py, &samplab::pixel::PIXEL_SAMPLERS),
        _ => Err(err(format!(
            "unknown registry '{kind}' (samplers, metrics, warps, integrands, formats, scenes, pixels)"
        ))),
    }
}

/// A flat vector as an array of `shape`.
pub(crate) fn shaped<'py>(py: Python<'py>, data: Vec<f64>, shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
}

/// Every value of `frames` frames of a film (width, height, spp, dims) from the pixel
/// sampler `spec` (with `per_pixel`, the point-set sequence `spec` served per pixel, even
/// where a pixel sampler has its name), as an array (frames, height, width, spp, dims): the
/// bytes of `samplab pixels`.
#[pyfunction]
#[pyo3(signature = (spec, film, frames, seed, per_pixel=false))]
pub(crate) fn pixels<'py>(
    py: Python<'py>,
    spec: &str,
    film: (u32, u32, u32, u32),
    frames: u32,
    seed: u64,
    per_pixel: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if frames == 0 {
        return Err(err("frames = 0: at least one frame"));
    }
    let (width, height, spp, dims) = film;
    let film = samplab::pixel::Film { width, height, spp, dims };
    let data = interruptible(py, usize::MAX, |stop| {
        let stop = Progress::until(stop);
        let pixels = if per_pixel {
            samplab::pixel::per_pixel(spec, film, Seed(seed))?
        } else {
            samplab::pixel::prepare_with(spec, film, Seed(seed), &stop)?
        };
        pixels.fill_with(frames, &stop)
    })?;
    shaped(py, data, &[frames, height, width, spp, dims].map(|k| k as usize))
}

/// The CUDA source of `samplab.gpu`'s kernels, one text that NVRTC compiles (CuPy's
/// RawModule): the header-only samplers' tables and header, then the kernels of
/// `crates/samplab-c/examples/cuda/fill.cu`, each file in the place of its `#include`.
#[pyfunction]
pub(crate) fn cuda_source() -> String {
    const TABLES: &str = include_str!("../../samplab-c/include/samplab/tables.hpp");
    const SAMPLERS: &str = include_str!("../../samplab-c/include/samplab/samplers.hpp");
    const KERNELS: &str = include_str!("../../samplab-c/examples/cuda/fill.cu");
    KERNELS.replace("#include <samplab/samplers.hpp>", &SAMPLERS.replace("#include \"tables.hpp\"", TABLES))
}

/// The seed of pixel (x, y) in `frame` under `seed`, under which a point-set sequence
/// served per pixel draws its points.
#[pyfunction]
pub(crate) fn pixel_seed(seed: u64, x: u32, y: u32, frame: u32) -> u64 {
    samplab::pixel::pixel_seed(Seed(seed), [x, y], frame).0
}

/// A tileable blue-noise mask by void-and-cluster, (size, size, channels): the bytes of
/// `samplab mask -o FILE.npy`.
#[pyfunction]
pub(crate) fn blue_noise_mask<'py>(
    py: Python<'py>,
    size: usize,
    channels: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let mask = py.detach(|| samplab::pixel::mask::Mask::void_and_cluster(size, channels, Seed(seed))).map_err(err)?;
    shaped(py, mask.values().to_vec(), &[size, size, channels])
}

/// Point sets from a C-contiguous float64 array of shape (sets, n, d), every coordinate
/// finite (the Python side makes the array contiguous).
pub(crate) fn point_sets(points: &PyReadonlyArray3<f64>) -> PyResult<Vec<PointSet>> {
    let shape = points.shape();
    let (sets, n, d) = (shape[0], shape[1], shape[2]);
    let data = points.as_slice().map_err(|_| err("points: the array must be C-contiguous"))?;
    if d == 0 {
        return Err(err("points: d must be at least 1"));
    }
    if let Some(i) = data.iter().position(|x| !x.is_finite()) {
        return Err(err(format!(
            "set {} point {} coordinate {} is {} (not finite)",
            i / (n * d),
            i / d % n,
            i % d,
            data[i]
        )));
    }
    (0..sets).map(|k| PointSet::new(d, data[k * n * d..(k + 1) * n * d].to_vec()).map_err(err)).collect()
}

/// The format `name` (a registry name or extension), or the one `path`'s extension implies.
pub(crate) fn format_of(path: &str, name: Option<&str>) -> PyResult<samplab::io::Format> {
    match name {
        Some(n) => samplab::io::Format::from_name(n).map_err(err),
        None => Ok(samplab::io::Format::from_path(std::path::Path::new(path))),
    }
}

/// `data` written to `path` atomically (a temporary file renamed over it: the old file or the
/// new one, never part of one), as every samplab output is.
#[pyfunction]
pub(crate) fn write_file(path: &str, data: &[u8]) -> PyResult<()> {
    samplab::io::write_atomic(std::path::Path::new(path), data).map_err(err)
}

/// Write a (sets, n, d) stack to `path` in `format` (text, csv, npy, json; by default
/// from the extension), atomically, as `samplab generate -o` writes files.
#[pyfunction]
#[pyo3(signature = (path, points, format=None, header=None))]
pub(crate) fn save(
    path: &str,
    points: PyReadonlyArray3<f64>,
    format: Option<&str>,
    header: Option<Vec<String>>,
) -> PyResult<()> {
    let sets = point_sets(&points)?;
    let bytes = samplab::io::encode(&sets, format_of(path, format)?, &header.unwrap_or_default()).map_err(err)?;
    samplab::io::write_atomic(std::path::Path::new(path), &bytes).map_err(err)
}

/// Read every set of a point file (text, csv, npy, json; by default from the extension)
/// as a list of (n, d) arrays; malformed or non-finite data is an error naming the line.
#[pyfunction]
#[pyo3(signature = (path, format=None))]
pub(crate) fn load<'py>(py: Python<'py>, path: &str, format: Option<&str>) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let sets = samplab::io::read(std::path::Path::new(path), Some(format_of(path, format)?)).map_err(err)?;
    sets.into_iter()
        .map(|s| {
            let (n, d) = (s.len(), s.dims());
            shaped(py, s.into_vec(), &[n, d])
        })
        .collect()
}

/// Warp an (n, d) array of points (rejection warps drop points).
#[pyfunction]
pub(crate) fn warp<'py>(py: Python<'py>, name: &str, points: PyReadonlyArray2<f64>) -> PyResult<Bound<'py, PyAny>> {
    let w = samplab::warp::lookup(name).map_err(err)?;
    let (n, d) = (points.shape()[0], points.shape()[1]);
    let data = points.as_slice().map_err(|_| err("points: the array must be C-contiguous"))?.to_vec();
    let set = PointSet::new(d, data).map_err(err)?;
    debug_assert_eq!(set.len(), n);
    let out = py.detach(|| samplab::warp::apply(w, &set)).map_err(err)?;
    let (m, e) = (out.len(), out.dims());
    shaped(py, out.into_vec(), &[m, e])
}
