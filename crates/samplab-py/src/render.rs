//! The renderer: render settings from keywords, images and their errors.

use crate::errors::err;
use crate::interrupt::interruptible;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use samplab::progress::Progress;

/// Every render setting with its CLI flag, default (None where it has none) and help, in
/// declaration order ([`samplab_render::settings::table`]): what `samplab.render`'s
/// docstring lists.
#[pyfunction]
pub(crate) fn render_settings(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let list = PyList::empty(py);
    for d in samplab_render::settings::table() {
        let item = PyDict::new(py);
        item.set_item("name", d.name)?;
        item.set_item("flag", d.flag)?;
        item.set_item("default", d.default)?;
        item.set_item("help", d.help)?;
        list.append(item)?;
    }
    Ok(list)
}

/// Render settings from Python keywords, over the defaults of [`Settings`] (the CLI's).
pub(crate) fn settings(given: Option<&Bound<'_, PyDict>>) -> PyResult<samplab_render::Settings> {
    let mut named = serde_json::Map::new();
    for (key, value) in given.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        let value = crate::convert::json_of(&key, &value)?;
        named.insert(key, value);
    }
    samplab_render::settings::from_named(named).map_err(err)
}

/// An image as a dictionary: rgb (h, w, 3) and visibility (h, w) float32 arrays.
pub(crate) fn image_dict<'py>(py: Python<'py>, image: samplab_render::Image) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let (w, h) = (image.width, image.height);
    out.set_item("rgb", PyArray1::from_vec(py, image.rgb).reshape([h, w, 3])?)?;
    match image.visibility {
        Some(v) => out.set_item("visibility", PyArray1::from_vec(py, v).reshape([h, w])?)?,
        None => out.set_item("visibility", py.None())?,
    }
    Ok(out)
}

/// Render `scene` (a built-in name or a Mitsuba XML file, lit by `light` if given) with the
/// settings given (the CLI's defaults otherwise); `reference_samples` renders the reference
/// `samplab render` would (converged, Owen-scrambled Sobol') instead.
#[pyfunction]
#[pyo3(signature = (scene, light=None, settings=None, reference_samples=None, allow_paths_outside_scene=false))]
pub(crate) fn render<'py>(
    py: Python<'py>,
    scene: &str,
    light: Option<&str>,
    settings: Option<&Bound<'py, PyDict>>,
    reference_samples: Option<usize>,
    allow_paths_outside_scene: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let s = self::settings(settings)?;
    let paths = if allow_paths_outside_scene {
        samplab_render::mitsuba::Paths::Anywhere
    } else {
        samplab_render::mitsuba::Paths::InsideScene
    };
    let scene = samplab_render::settings::load_scene(scene, light, paths).map_err(err)?;
    let mut options = s.options(&scene).map_err(err)?;
    if let Some(samples) = reference_samples {
        options = options.reference(&scene, samples).map_err(err)?;
    }
    let rendered =
        interruptible(py, usize::MAX, |stop| samplab_render::render(&scene, &options, &Progress::until(stop)))?;
    let out = image_dict(py, rendered.image)?;
    out.set_item("camera_rays", rendered.camera_rays)?;
    out.set_item("shadow_rays", rendered.shadow_rays)?;
    Ok(out)
}

/// An image from float32 arrays rgb (h, w, 3) and, optionally, visibility (h, w).
pub(crate) fn image_of(
    rgb: &PyReadonlyArray3<f32>,
    visibility: Option<&PyReadonlyArray2<f32>>,
) -> PyResult<samplab_render::Image> {
    let shape = rgb.shape();
    if shape[2] != 3 {
        return Err(err(format!("rgb: expected shape (h, w, 3), got {shape:?}")));
    }
    let (h, w) = (shape[0], shape[1]);
    let contiguous = |_| err("the array must be C-contiguous");
    let visibility = match visibility {
        Some(v) if v.shape() != [h, w] => {
            return Err(err(format!("visibility: expected shape ({h}, {w}), got {:?}", v.shape())));
        }
        Some(v) => Some(v.as_slice().map_err(contiguous)?.to_vec()),
        None => None,
    };
    Ok(samplab_render::Image { width: w, height: h, rgb: rgb.as_slice().map_err(contiguous)?.to_vec(), visibility })
}

/// Error metrics of an image against a reference (luminance, Rec. 709), as `samplab render
/// --json` reports them; `penumbra` restricts them to the reference's 0 < V < 1.
#[pyfunction]
#[pyo3(signature = (rgb, reference_rgb, reference_visibility=None, penumbra=false))]
pub(crate) fn image_errors<'py>(
    rgb: PyReadonlyArray3<'py, f32>,
    reference_rgb: PyReadonlyArray3<f32>,
    reference_visibility: Option<PyReadonlyArray2<f32>>,
    penumbra: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let image = image_of(&rgb, None)?;
    let reference = image_of(&reference_rgb, reference_visibility.as_ref())?;
    crate::convert::py_from(rgb.py(), &image.errors(&reference, penumbra).map_err(err)?)
}

/// The screen measures of error images (frames, height, width) (`samplab image-metrics
/// --json`'s objects, one per frame), with the flicker over the frames when there are two or
/// more, or with `spp` (one count per image) their convergence.
#[pyfunction]
#[pyo3(signature = (errors, sigmas, spp=None))]
pub(crate) fn image_metrics<'py>(
    py: Python<'py>,
    errors: PyReadonlyArray3<f64>,
    sigmas: Vec<f64>,
    spp: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyAny>> {
    let [frames, h, w] = [0, 1, 2].map(|k| errors.shape()[k]);
    if w == 0 || h == 0 {
        return Err(err(format!("an empty image, {w}x{h} pixels")));
    }
    let values = errors.as_slice().map_err(|_| err("the array must be C-contiguous"))?;
    let planes = values
        .chunks(w * h.max(1))
        .take(frames)
        .map(|f| samplab::screen::Plane::new(w, h, f.to_vec()))
        .collect::<samplab::Result<Vec<_>>>()
        .map_err(err)?;
    if planes.is_empty() {
        return Err(err("no image: the array has 0 frames"));
    }
    let result = py
        .detach(|| {
            let m = planes.iter().map(|p| p.metrics(&sigmas)).collect::<samplab::Result<Vec<_>>>()?;
            Ok::<_, samplab::Error>(match &spp {
                Some(spp) => serde_json::json!({
                    "frames": m, "convergence": samplab::screen::convergence(&planes, spp, &sigmas)?,
                }),
                None if planes.len() > 1 => {
                    serde_json::json!({ "frames": m, "flicker": samplab::screen::flicker(&planes)? })
                }
                None => serde_json::json!({ "frames": m }),
            })
        })
        .map_err(err)?;
    crate::convert::py_from(py, &result)
}

/// Read an OpenEXR image (as `samplab render` writes them).
#[pyfunction]
pub(crate) fn read_exr<'py>(py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyDict>> {
    image_dict(py, samplab_render::Image::read_exr(std::path::Path::new(path)).map_err(err)?)
}
