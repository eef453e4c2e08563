//! Tests of [`super`].

use super::*;

fn image(values: &[f32], vis: Option<Vec<f32>>) -> Image {
    Image { width: values.len(), height: 1, rgb: values.iter().flat_map(|&v| [v, v, v]).collect(), visibility: vis }
}

#[test]
fn errors_follow_their_definitions() {
    let reference = image(&[1.0, 2.0, 3.0, 4.0], Some(vec![1.0, 0.5, 0.2, 0.0]));
    let img = image(&[1.0, 2.5, 2.0, 4.0], None);
    let e = img.errors(&reference, false).unwrap();
    assert_eq!(e.pixels, 4);
    assert!((e.mse - (0.25 + 1.0) / 4.0).abs() < 1e-6);
    assert!((e.mean_abs - 1.5 / 4.0).abs() < 1e-6);
    assert!((e.max_abs - 1.0).abs() < 1e-6);
    assert!((e.relative - e.rmse / 2.5).abs() < 1e-6);
    let p = img.errors(&reference, true).unwrap();
    assert_eq!(p.pixels, 2);
    assert!((p.mse - 1.25 / 2.0).abs() < 1e-6);
    assert!(reference.errors(&img, true).is_err(), "no V channel");
    // displayed: 2.5 and 2.0 clamp to 1, as the reference's 2, 3 and 4 do
    let c = img.clamped().errors(&reference.clamped(), false).unwrap();
    assert_eq!((c.mse, c.max_abs), (0.0, 0.0));
    let c = image(&[-0.5, 0.25, 3.0, 1.0], None).clamped();
    assert_eq!([c.rgb[0], c.rgb[3], c.rgb[6], c.rgb[9]], [0.0, 0.25, 1.0, 1.0]);
}

#[test]
fn exr_round_trips_bit_for_bit() {
    let dir = std::env::temp_dir().join(format!("samplab-exr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("a.exr");
    let img = Image {
        width: 3,
        height: 2,
        rgb: (0..18).map(|i| i as f32 * 0.37 - 1.0).collect(),
        visibility: Some(vec![0.0, 0.25, 0.5, 0.75, 1.0, 0.125]),
    };
    img.write(&path).unwrap();
    assert_eq!(Image::read_exr(&path).unwrap(), img);
    std::fs::remove_dir_all(dir).unwrap();
}

/// A temporary folder of this test process.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("samplab-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn pictures_written_as_png_decode_to_their_bytes() {
    let bytes: Vec<u8> = (0..5 * 3 * 3).map(|i| (i * 37 % 256) as u8).collect();
    let mut picture = Srgb8::from_raw(5, 3, bytes.clone()).unwrap();
    assert!(Srgb8::from_raw(5, 3, bytes[1..].to_vec()).is_none());
    picture.set(4, 2, [1, 2, 3]);
    assert_eq!(picture.pixel(4, 2), [1, 2, 3]);
    let mut expected = bytes;
    expected[42..45].copy_from_slice(&[1, 2, 3]);
    let file = picture.png().unwrap();
    // the png crate's own decoder
    let mut reader = png::Decoder::new(Cursor::new(&file)).read_info().unwrap();
    let mut decoded = vec![0; reader.output_buffer_size().unwrap()];
    let frame = reader.next_frame(&mut decoded).unwrap();
    assert_eq!((frame.width, frame.height, frame.color_type), (5, 3, png::ColorType::Rgb));
    assert_eq!(decoded, expected);
    // and ours
    let dir = scratch("png-rgb");
    std::fs::write(dir.join("a.png"), &file).unwrap();
    let (w, h, values) = read_png(&dir.join("a.png")).unwrap();
    assert_eq!((w, h), (5, 3));
    assert_eq!(values, expected.iter().map(|&b| f32::from(b) / 255.0).collect::<Vec<_>>());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn every_kind_of_png_reads_as_rgb_in_the_unit_range() {
    use png::{BitDepth, ColorType};
    let dir = scratch("png-kinds");
    let path = dir.join("k.png");
    // 2 x 1 pixels of each kind, written by the png crate, and the values expected
    let palette = vec![10, 20, 30, 200, 150, 100];
    let kinds: [(ColorType, BitDepth, Vec<u8>, [f32; 6]); 6] = [
        (ColorType::Grayscale, BitDepth::Eight, vec![51, 255], [0.2, 0.2, 0.2, 1.0, 1.0, 1.0]),
        (ColorType::GrayscaleAlpha, BitDepth::Eight, vec![0, 9, 102, 0], [0.0, 0.0, 0.0, 0.4, 0.4, 0.4]),
        (ColorType::Rgba, BitDepth::Eight, vec![255, 0, 51, 7, 0, 102, 255, 0], [1.0, 0.0, 0.2, 0.0, 0.4, 1.0]),
        // 16-bit values are stored big-endian: 0x8000 and 0xffff
        (ColorType::Grayscale, BitDepth::Sixteen, vec![0x80, 0, 0xff, 0xff], {
            let half = 32768.0 / 65535.0;
            [half, half, half, 1.0, 1.0, 1.0]
        }),
        (
            ColorType::Indexed,
            BitDepth::Eight,
            vec![1, 0],
            [200.0 / 255.0, 150.0 / 255.0, 100.0 / 255.0, 10.0 / 255.0, 20.0 / 255.0, 30.0 / 255.0],
        ),
        // one bit per pixel: 0b10 in the row's first byte's high bits
        (ColorType::Grayscale, BitDepth::One, vec![0b1000_0000], [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]),
    ];
    for (color, depth, data, expected) in kinds {
        let mut encoder = png::Encoder::new(std::fs::File::create(&path).unwrap(), 2, 1);
        encoder.set_color(color);
        encoder.set_depth(depth);
        if color == ColorType::Indexed {
            encoder.set_palette(palette.clone());
        }
        encoder.write_header().unwrap().write_image_data(&data).unwrap();
        let (w, h, values) = read_png(&path).unwrap();
        assert_eq!((w, h), (2, 1), "{color:?} {depth:?}");
        assert_eq!(values, expected, "{color:?} {depth:?}");
    }
    std::fs::write(&path, b"not a png").unwrap();
    assert!(read_png(&path).unwrap_err().to_string().starts_with(&path.display().to_string()));
    std::fs::remove_dir_all(dir).unwrap();
}
