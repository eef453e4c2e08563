//! `--integrand` beyond the registry: a formula in x0 .. x(d-1) (`expr:...`) or an image
//! (`image:PATH`, bilinear lookups; `image.box:PATH`, the texel under the point), EXR or PNG,
//! its Rec. 709 luminance in linear values.

use std::path::Path;

use samplab::integrand::{Expr, Integrand, Lookup, Texture};

/// The formats, for the commands' help.
pub const HELP: &str = "Your own integrand: 'expr:exp(-x0*x0-x1*x1)' (a formula in x0 .. x(d-1): + - * / ^, exp log \
     sqrt sin cos tan asin acos atan sinh cosh tanh abs floor ceil step min max pow atan2, pi, e), image:sky.exr or \
     image.box:mask.png (the image's linear luminance over the unit square, row 0 at x1 = 0; bilinear or box lookups; \
     its integral is the mean texel).";

/// The integrand `text` names when it is not a registered family, with its exact integral
/// where `exact` states it (an image's is its mean texel); a formula's otherwise computed
/// when `reference` asks ([`samplab::cubature::reference`]), or unknown.
///
/// # Errors
/// A malformed formula (with the column), an unreadable image, a reference that did not
/// reach its accuracy.
pub fn parse(text: &str, exact: Option<f64>, reference: bool) -> anyhow::Result<Option<Box<dyn Integrand>>> {
    if let Some(e) = exact.filter(|e| !e.is_finite()) {
        anyhow::bail!("--exact {e}: the integral must be a finite number");
    }
    if let Some(formula) = text.strip_prefix("expr:") {
        let f = Expr::parse(formula, None)?;
        let exact = match exact {
            Some(exact) => exact,
            None if reference => samplab::cubature::reference(&f, &samplab::progress::Progress::SILENT)?,
            None => f64::NAN,
        };
        return Ok(Some(Box::new(f.with_exact(exact))));
    }
    let (path, lookup) = match (text.strip_prefix("image:"), text.strip_prefix("image.box:")) {
        (Some(path), _) => (path, Lookup::Bilinear),
        (_, Some(path)) => (path, Lookup::Box),
        _ => return Ok(None),
    };
    if exact.is_some() {
        anyhow::bail!("--exact: an image's integral is known (its mean texel); leave --exact out");
    }
    let image = samplab_render::image::Image::read(Path::new(path))?;
    Ok(Some(Box::new(Texture::new(image.width, image.height, image.luminance(), lookup)?)))
}
