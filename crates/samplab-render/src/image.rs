//! Linear float images: OpenEXR in and out (RGB plus an optional visibility channel `V`),
//! sRGB PNG in and out, error metrics against a reference and signed error images; and
//! [`Srgb8`], the 8-bit pictures every PNG of samplab is written from.

use std::io::Cursor;
use std::path::Path;

use samplab::io::Staged;

use crate::error::{Error, Result};

/// A linear RGB image, row-major from the top left.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// R, G, B per pixel.
    pub rgb: Vec<f32>,
    /// The emission-weighted visible fraction of the lights per pixel, when known: it
    /// marks the penumbra (0 < V < 1) for error metrics restricted to it.
    pub visibility: Option<Vec<f32>>,
}

/// Errors of an image against a reference, on luminance (Rec. 709 weights).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Errors {
    /// Pixels compared.
    pub pixels: usize,
    /// Mean squared error.
    pub mse: f64,
    /// Root mean squared error.
    pub rmse: f64,
    /// RMSE divided by the reference's mean luminance over the same pixels (the papers'
    /// "fractional error").
    pub relative: f64,
    /// Mean absolute error (Shirley 1991, Tables 1-4: ave(|E|)).
    pub mean_abs: f64,
    /// Standard deviation of the absolute error (SD(|E|)).
    pub sd_abs: f64,
    /// Largest absolute error (max(|E|)).
    pub max_abs: f64,
    /// Mean signed error (bias).
    pub mean_signed: f64,
}

/// Rec. 709 luminance.
fn luminance(rgb: &[f32]) -> f64 {
    0.2126 * f64::from(rgb[0]) + 0.7152 * f64::from(rgb[1]) + 0.0722 * f64::from(rgb[2])
}

/// The sRGB transfer function's inverse (IEC 61966-2-1): an encoded value in [0, 1] to
/// linear.
pub fn srgb_to_linear(v: f64) -> f64 {
    if v <= 0.04045 { v / 12.92 } else { ((v + 0.055) / 1.055).powf(2.4) }
}

fn srgb8(linear: f64) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
}

/// Bounds of the penumbra: pixels whose reference visible fraction lies strictly inside.
const PENUMBRA: (f32, f32) = (1e-3, 1.0 - 1e-3);

impl Image {
    /// The image as bytes: width and height (little-endian u64), 1 or 0 for a visibility
    /// channel, then R, G, B per pixel and the visibility (little-endian f32).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(17 + 4 * (self.rgb.len() + self.width * self.height));
        out.extend((self.width as u64).to_le_bytes());
        out.extend((self.height as u64).to_le_bytes());
        out.push(u8::from(self.visibility.is_some()));
        for v in self.rgb.iter().chain(self.visibility.iter().flatten()) {
            out.extend(v.to_le_bytes());
        }
        out
    }

    /// The inverse of [`Image::to_bytes`].
    ///
    /// # Errors
    /// Bytes of another length or layout.
    ///
    /// # Panics
    /// Never: every slice is of the length read.
    pub fn from_bytes(bytes: &[u8]) -> Result<Image> {
        let bad = || {
            let reason = format!("{} bytes are not an image's", bytes.len());
            Error::Samplab(samplab::Error::Parse { location: "an image".into(), reason })
        };
        let word = |k: usize| bytes.get(8 * k..8 * k + 8).map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")));
        let (width, height) = (word(0).ok_or_else(bad)? as usize, word(1).ok_or_else(bad)? as usize);
        let has_visibility = *bytes.get(16).ok_or_else(bad)? == 1;
        let pixels = width.checked_mul(height).ok_or_else(bad)?;
        let floats = pixels.checked_mul(3 + usize::from(has_visibility)).ok_or_else(bad)?;
        if bytes.len() != 17 + 4 * floats {
            return Err(bad());
        }
        let values: Vec<f32> =
            bytes[17..].chunks_exact(4).map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes"))).collect();
        let (rgb, visibility) = values.split_at(3 * pixels);
        Ok(Image { width, height, rgb: rgb.to_vec(), visibility: has_visibility.then(|| visibility.to_vec()) })
    }

    /// Luminance of every pixel.
    pub fn luminance(&self) -> Vec<f64> {
        self.rgb.chunks_exact(3).map(luminance).collect()
    }

    /// The image as a display shows it: every channel clamped to [0, 1] (Shirley 1991's
    /// luminance errors are of displayed images, so one bright highlight cannot dominate
    /// max |E|).
    pub fn clamped(&self) -> Image {
        Image { rgb: self.rgb.iter().map(|v| v.clamp(0.0, 1.0)).collect(), ..self.clone() }
    }

    /// Errors of `self` against `reference`, over all pixels or only the reference's
    /// penumbra.
    ///
    /// # Errors
    /// Different sizes, a penumbra asked of a reference without a visibility channel, or
    /// no pixel to compare.
    pub fn errors(&self, reference: &Image, penumbra: bool) -> Result<Errors> {
        if (self.width, self.height) != (reference.width, reference.height) {
            return Err(Error::Samplab(samplab::Error::Mismatch {
                what: "the image".into(),
                expected: format!("{}x{}, as the reference", reference.width, reference.height),
                got: format!("{}x{}", self.width, self.height),
            }));
        }
        let mask: Vec<bool> = match (&reference.visibility, penumbra) {
            (_, false) => vec![true; self.width * self.height],
            (Some(v), true) => v.iter().map(|&v| v > PENUMBRA.0 && v < PENUMBRA.1).collect(),
            (None, true) => {
                let reason = "the reference has no visibility channel V to find the penumbra";
                return Err(crate::error::setting("penumbra", true, reason));
            }
        };
        let (a, b) = (self.luminance(), reference.luminance());
        let diffs: Vec<(f64, f64)> =
            a.iter().zip(&b).zip(&mask).filter(|(_, m)| **m).map(|((x, r), _)| (x - r, *r)).collect();
        if diffs.is_empty() {
            return Err(samplab::Error::TooFew {
                what: "the error in the penumbra (the reference has none)".into(),
                least: 1,
                of: "pixel",
                got: 0,
            }
            .into());
        }
        let count = diffs.len() as f64;
        let mse = diffs.iter().map(|(d, _)| d * d).sum::<f64>() / count;
        let mean_abs = diffs.iter().map(|(d, _)| d.abs()).sum::<f64>() / count;
        let sd_abs = (diffs.iter().map(|(d, _)| (d.abs() - mean_abs).powi(2)).sum::<f64>() / count).sqrt();
        let reference_mean = diffs.iter().map(|(_, r)| r).sum::<f64>() / count;
        Ok(Errors {
            pixels: diffs.len(),
            mse,
            rmse: mse.sqrt(),
            relative: mse.sqrt() / reference_mean,
            mean_abs,
            sd_abs,
            max_abs: diffs.iter().map(|(d, _)| d.abs()).fold(0.0, f64::max),
            mean_signed: diffs.iter().map(|(d, _)| d).sum::<f64>() / count,
        })
    }

    /// The signed luminance error as an 8-bit RGB image: red where `self` is brighter than
    /// the reference, green where darker, times `scale` (Ramamoorthi et al. 2012, Figs. 8
    /// and 13 use 10).
    ///
    /// # Errors
    /// Different sizes.
    pub fn error_image(&self, reference: &Image, scale: f64) -> Result<Srgb8> {
        self.errors(reference, false)?;
        let (a, b) = (self.luminance(), reference.luminance());
        let to8 = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        let bytes = a.iter().zip(&b).flat_map(|(a, b)| [to8((a - b) * scale), to8((b - a) * scale), 0]).collect();
        Ok(Srgb8 { width: self.width as u32, height: self.height as u32, bytes })
    }

    /// The image as 8-bit sRGB (clamped to [0, 1]).
    pub fn to_srgb(&self) -> Srgb8 {
        let bytes = self.rgb.iter().map(|&c| srgb8(f64::from(c))).collect();
        Srgb8 { width: self.width as u32, height: self.height as u32, bytes }
    }

    /// Stage an OpenEXR file (32-bit float R, G, B and V when known) for `path`.
    ///
    /// # Errors
    /// The file cannot be written.
    pub fn stage_exr(&self, out: &mut Staged, path: &Path) -> Result<()> {
        use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Layer, LayerAttributes, WritableImage};
        let fail = |m: String| Error::Image { path: path.display().to_string(), message: m };
        let w = self.width;
        // an image samplab could not read back is not written
        if let Some(i) = self.rgb.iter().position(|v| !v.is_finite()) {
            let pixel = non_finite(i / 3 % w, i / 3 / w, i % 3, self.rgb[i]);
            return Err(fail(format!("{pixel}: beyond 32-bit floats (a light too bright?); not written")));
        }
        let channel = |name: &str, data: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(data));
        let plane = |k: usize| self.rgb.iter().skip(k).step_by(3).copied().collect::<Vec<f32>>();
        let mut list = vec![channel("B", plane(2)), channel("G", plane(1)), channel("R", plane(0))];
        if let Some(v) = &self.visibility {
            list.push(channel("V", v.clone()));
        }
        let channels = AnyChannels::sort(list.into());
        let layer = Layer::new((w, self.height), LayerAttributes::default(), Encoding::SMALL_LOSSLESS, channels);
        let mut bytes = Cursor::new(Vec::new());
        exr::image::Image::from_layer(layer).write().to_buffered(&mut bytes).map_err(|e| fail(e.to_string()))?;
        out.file(path, bytes.get_ref()).map_err(|e| fail(e.to_string()))
    }

    /// Read an image by its extension: OpenEXR ([`Image::read_exr`]) or PNG (8- or 16-bit,
    /// grey or colour, decoded from sRGB to linear values; alpha ignored).
    ///
    /// # Errors
    /// Another extension, an unreadable or malformed file.
    pub fn read(path: &Path) -> Result<Image> {
        let fail = |m: String| Error::Image { path: path.display().to_string(), message: m };
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("exr") => Image::read_exr(path),
            Some("png") => {
                let (width, height, encoded) = read_png(path)?;
                let rgb = encoded.into_iter().map(|v| srgb_to_linear(f64::from(v)) as f32).collect();
                Ok(Image { width, height, rgb, visibility: None })
            }
            _ => Err(fail("unknown image format (use .exr or .png)".into())),
        }
    }

    /// Read an OpenEXR file's first layer: R, G, B (Y alone is read as grey) and V if there.
    ///
    /// # Errors
    /// Not an EXR file, no R/G/B or Y channel, or a non-finite pixel.
    pub fn read_exr(path: &Path) -> Result<Image> {
        let fail = |m: String| Error::Image { path: path.display().to_string(), message: m };
        let image = exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| fail(e.to_string()))?;
        let layer = image.layer_data.first().ok_or_else(|| fail("no layer".into()))?;
        let (w, h) = (layer.size.width(), layer.size.height());
        let find = |name: &str| -> Option<Vec<f32>> {
            let c = layer.channel_data.list.iter().find(|c| c.name.eq_case_insensitive(name))?;
            Some(c.sample_data.values_as_f32().collect())
        };
        let planes = match (find("R"), find("G"), find("B"), find("Y")) {
            (Some(r), Some(g), Some(b), _) => [r, g, b],
            (_, _, _, Some(y)) => [y.clone(), y.clone(), y],
            _ => return Err(fail("no R, G, B or Y channel".into())),
        };
        let mut rgb = Vec::with_capacity(3 * w * h);
        for i in 0..w * h {
            for (k, p) in planes.iter().enumerate() {
                if !p[i].is_finite() {
                    return Err(fail(non_finite(i % w, i / w, k, p[i])));
                }
                rgb.push(p[i]);
            }
        }
        Ok(Image { width: w, height: h, rgb, visibility: find("V") })
    }

    /// Write the image in the format its extension names (.exr, or .png as sRGB), atomically.
    ///
    /// # Errors
    /// Another extension, or the file cannot be written.
    pub fn write(&self, path: &Path) -> Result<()> {
        let mut out = Staged::new();
        self.stage(&mut out, path)?;
        out.commit().map_err(|e| Error::Image { path: path.display().to_string(), message: e.to_string() })
    }

    /// Stage the image for `path` as [`Image::write`] writes it, to appear with the other
    /// outputs of `out`.
    ///
    /// # Errors
    /// As [`Image::write`].
    pub fn stage(&self, out: &mut Staged, path: &Path) -> Result<()> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("exr") => self.stage_exr(out, path),
            Some("png") => stage_png(&self.to_srgb(), out, path),
            _ => Err(Error::Image {
                path: path.display().to_string(),
                message: "unknown image format (use .exr or .png)".into(),
            }),
        }
    }
}

/// Where a value that is not finite is: pixel (x, y), channel k of R, G, B.
fn non_finite(x: usize, y: usize, k: usize, value: f32) -> String {
    format!("pixel ({x}, {y}) channel {} is {value}", ["R", "G", "B"][k])
}

/// Stage an 8-bit RGB picture as PNG for `path`.
///
/// # Errors
/// The file cannot be written.
pub fn stage_png(img: &Srgb8, out: &mut Staged, path: &Path) -> Result<()> {
    let fail = |m: String| Error::Image { path: path.display().to_string(), message: m };
    out.file(path, &img.png().map_err(|e| fail(e.to_string()))?).map_err(|e| fail(e.to_string()))
}

/// An 8-bit sRGB picture: R, G, B per pixel, row-major from the top left.
#[derive(Debug, Clone, PartialEq)]
pub struct Srgb8 {
    width: u32,
    height: u32,
    bytes: Vec<u8>,
}

impl Srgb8 {
    /// A `width` x `height` picture of one colour.
    pub fn filled(width: u32, height: u32, colour: [u8; 3]) -> Srgb8 {
        Srgb8 { width, height, bytes: colour.repeat(width as usize * height as usize) }
    }

    /// The picture whose pixels are `bytes` (R, G, B each); `None` unless they are three
    /// per pixel.
    pub fn from_raw(width: u32, height: u32, bytes: Vec<u8>) -> Option<Srgb8> {
        (bytes.len() as u128 == 3 * u128::from(width) * u128::from(height)).then_some(Srgb8 { width, height, bytes })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    fn at(&self, x: u32, y: u32) -> usize {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside {}x{}", self.width, self.height);
        3 * (y as usize * self.width as usize + x as usize)
    }

    /// The pixel at column `x`, row `y`.
    ///
    /// # Panics
    /// Outside the picture.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = self.at(x, y);
        [self.bytes[i], self.bytes[i + 1], self.bytes[i + 2]]
    }

    /// Set the pixel at column `x`, row `y`.
    ///
    /// # Panics
    /// Outside the picture.
    pub fn set(&mut self, x: u32, y: u32, rgb: [u8; 3]) {
        let i = self.at(x, y);
        self.bytes[i..i + 3].copy_from_slice(&rgb);
    }

    /// The picture as a PNG file's bytes: 8-bit RGB, the png crate's fast deflate, each
    /// row's filter chosen adaptively (the bytes the `image` crate wrote before, 2026-11-30).
    ///
    /// # Errors
    /// The encoder fails.
    pub fn png(&self) -> std::result::Result<Vec<u8>, png::EncodingError> {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        encoder.set_filter(png::Filter::Adaptive);
        encoder.write_header()?.write_image_data(&self.bytes)?;
        Ok(bytes)
    }
}

/// A PNG file's pixels as stored (sRGB-encoded), scaled to [0, 1]: R, G, B per pixel,
/// row-major from the top, with the width and height. Palettes and bit depths under 8 are
/// expanded, grey is repeated in R, G and B, 16-bit values are divided by 65535, and alpha
/// is ignored.
///
/// # Errors
/// An unreadable or malformed file, or one too large for the memory.
pub fn read_png(path: &Path) -> Result<(usize, usize, Vec<f32>)> {
    let fail = |m: String| Error::Image { path: path.display().to_string(), message: m };
    let file = std::fs::File::open(path).map_err(|e| fail(e.to_string()))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
    let size = reader.output_buffer_size().ok_or_else(|| fail("too large to decode".into()))?;
    let pixels = u128::from(reader.info().width) * u128::from(reader.info().height);
    // the decoded bytes, then three f32 per pixel
    samplab::memory::check(|| format!("{}'s pixels", path.display()), size as u128 + 12 * pixels)?;
    let mut buffer = vec![0; size];
    let frame = reader.next_frame(&mut buffer).map_err(|e| fail(e.to_string()))?;
    let (width, height) = (frame.width as usize, frame.height as usize);
    let channels = frame.color_type.samples();
    let wide = frame.bit_depth == png::BitDepth::Sixteen;
    // sample i of the frame in [0, 1] (EXPAND leaves 8 or 16 bits, big-endian)
    let value = |i: usize| {
        if wide {
            f32::from(u16::from_be_bytes([buffer[2 * i], buffer[2 * i + 1]])) / 65535.0
        } else {
            f32::from(buffer[i]) / 255.0
        }
    };
    let rgb = (0..width * height)
        .flat_map(|p| {
            let first = p * channels;
            // grey (with or without alpha) has one value; colour three, then perhaps alpha
            let step = usize::from(channels >= 3);
            [value(first), value(first + step), value(first + 2 * step)]
        })
        .collect();
    Ok((width, height, rgb))
}

#[cfg(test)]
mod tests;
