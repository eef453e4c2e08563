//! The C interface from C: the checked-in header is cbindgen's output for the source, and a
//! C program compiled with the system compiler against `libsamplab_c.so` gets the library's
//! values bit for bit.

mod common;

use std::process::Command;

use common::{compile, crate_dir};

use samplab::Seed;
use samplab::pixel::{Film, PIXEL_SAMPLERS, prepare};

#[test]
fn the_header_is_cbindgens_output() {
    let config = cbindgen::Config::from_file(crate_dir().join("cbindgen.toml")).unwrap();
    let mut generated = Vec::new();
    cbindgen::generate_with_config(crate_dir(), config).unwrap().write(&mut generated);
    let path = crate_dir().join("include/samplab.h");
    if std::env::var_os("SAMPLAB_WRITE_HEADER").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let checked_in = std::fs::read(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/samplab.h is not cbindgen's output for src/lib.rs: run SAMPLAB_WRITE_HEADER=1 cargo test -p samplab-c"
    );
}

#[test]
fn a_c_program_gets_the_librarys_values() {
    let dir = std::env::temp_dir().join(format!("samplab-c-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join("example");
    compile(&crate_dir().join("tests/example.c"), &exe);
    for e in PIXEL_SAMPLERS.iter() {
        let name = e.about.name;
        let out = Command::new(&exe).arg(name).output().unwrap();
        assert!(out.status.success(), "{name}: exit {:?}: {}", out.status.code(), String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8(out.stdout).unwrap();
        let p = prepare(name, Film { width: 16, height: 9, spp: 16, dims: 8 }, Seed(7)).unwrap();
        assert!(text.starts_with(&format!("# {}\n", p.spec())), "{name}: {text}");
        let mut values = 0;
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let f: Vec<&str> = line.split(' ').collect();
            let k: Vec<u32> = f[..5].iter().map(|w| w.parse().unwrap()).collect();
            let ours = p.sample_padded([k[0], k[1]], k[2], k[3], k[4]).unwrap();
            assert_eq!(hex_float(f[5]), ours, "{name}: {line}");
            if k[4] < 8 {
                assert_eq!(ours, p.sample([k[0], k[1]], k[2], k[3], k[4]), "{name}: {line}");
            }
            values += 1;
        }
        assert_eq!(values, 4 * 3 * 6 * 10, "{name}");
        if name == "zsobol" {
            assert!(text.ends_with("# error: spp = 3: zsobol: spp a power of two: try 2 and 4\n"), "{text}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The guide's C example (docs/guide/pixels.md) compiles as it is printed and prints the
/// library's values.
#[test]
fn the_guides_c_example_runs() {
    let page = std::fs::read_to_string(crate_dir().join("../../docs/guide/pixels.md")).unwrap();
    let code = page.split("```c\n").nth(1).and_then(|rest| rest.split("```").next()).expect("a C block in pixels.md");
    let dir = std::env::temp_dir().join(format!("samplab-c-guide-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (source, exe) = (dir.join("app.c"), dir.join("app"));
    std::fs::write(&source, code).unwrap();
    compile(&source, &exe);
    let out = Command::new(&exe).output().unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert!(out.status.success(), "the guide's C example: {}", String::from_utf8_lossy(&out.stderr));
    let values: Vec<f64> =
        String::from_utf8(out.stdout).unwrap().split_whitespace().map(|w| w.parse().unwrap()).collect();
    let zsobol = prepare("zsobol", Film { width: 1920, height: 1080, spp: 64, dims: 32 }, Seed(7)).unwrap();
    assert_eq!(values, [zsobol.sample([640, 360], 0, 5, 2), zsobol.sample([640, 360], 0, 5, 4)]);
}

/// A C99 hexadecimal float (`%a`: 0x1.8p-1, 0x0p+0) as f64, exactly.
fn hex_float(text: &str) -> f64 {
    let body = text.strip_prefix("0x").unwrap();
    let (mantissa, exponent) = body.split_once('p').unwrap();
    let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let mut m = u64::from_str_radix(whole, 16).unwrap() as f64;
    for (k, c) in fraction.chars().enumerate() {
        m += f64::from(c.to_digit(16).unwrap()) * 16f64.powi(-(k as i32 + 1));
    }
    m * 2f64.powi(exponent.parse().unwrap())
}

#[test]
fn the_version_and_the_families_are_the_librarys() {
    use samplab_c::*;
    // SAFETY: a static NUL-terminated string
    let version = unsafe { std::ffi::CStr::from_ptr(samplab_version()) }.to_str().unwrap();
    assert_eq!(version, env!("CARGO_PKG_VERSION"));
    let header = format!("{SAMPLAB_VERSION_MAJOR}.{SAMPLAB_VERSION_MINOR}.{SAMPLAB_VERSION_PATCH}");
    assert_eq!(header, version, "the header's SAMPLAB_VERSION_* are not the crate's version");
    let mut first: *const SamplabFamily = std::ptr::null();
    // SAFETY: a writable pointer; then the table the library owns
    let families = unsafe {
        let n = samplab_pixel_families(&raw mut first);
        assert_eq!(samplab_pixel_families(std::ptr::null_mut()), n);
        std::slice::from_raw_parts(first, n)
    };
    assert_eq!(families.len(), PIXEL_SAMPLERS.iter().count());
    for (f, e) in families.iter().zip(PIXEL_SAMPLERS.iter()) {
        // SAFETY: the table's strings are NUL-terminated and live as long as the process
        let text = |p| unsafe { std::ffi::CStr::from_ptr(p) }.to_str().unwrap().to_string();
        assert_eq!(text(f.name), e.about.name);
        assert_eq!((text(f.spp), text(f.dims), f.max_dims), (e.spp.describe(), e.dims(), e.max_dims));
        // the most dimensions are accepted, one more refused
        let film = |dims| Film { width: 4, height: 4, spp: e.spp.first_from(4, 2).unwrap_or(4) as u32, dims };
        assert!(prepare(e.about.name, film(f.max_dims.min(64)), Seed(1)).is_ok(), "{}", e.about.name);
        if f.max_dims < samplab::pixel::MAX_DIMS {
            assert!(prepare(e.about.name, film(f.max_dims + 1), Seed(1)).is_err(), "{}", e.about.name);
        }
    }
}

/// Past the film's dimensions: values in [0, 1) for every family, uniform (their mean and
/// variance within 5 standard errors of 1/2 and 1/12), and not the `independent` family's.
///
/// Failure probability about 2e-5: two checks at 5 standard errors (normal tails, 4096
/// values each: 5.7e-7) for each of 17 families. Fixed seed. Least work: 16 x 16 pixels x
/// 16 samples, milliseconds; fewer values would leave a biased padding unseen.
#[test]
fn values_past_the_films_dimensions_are_uniform_padding_never_nan() {
    let film = Film { width: 16, height: 16, spp: 16, dims: 4 };
    let independent = prepare("independent", film, Seed(9)).unwrap();
    for e in PIXEL_SAMPLERS.iter() {
        let p = prepare(e.about.name, film, Seed(9)).unwrap();
        let mut values = Vec::new();
        for (x, y, i, d) in
            (0..16).flat_map(|x| (0..16).flat_map(move |y| (0..16).map(move |i| (x, y, i, 4 + (x + y + i) % 300))))
        {
            let v = p.sample_padded([x, y], 2, i, d).unwrap();
            assert!((0.0..1.0).contains(&v), "{}: {v}", e.about.name);
            assert_ne!(v, independent.sample([x, y], 2, i, d), "{}: the independent family's value", e.about.name);
            values.push(v);
        }
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - 0.5) * (v - 0.5)).sum::<f64>() / n;
        // sd of a uniform's mean: sqrt(1/12 / n); of (u - 1/2)^2's mean: sqrt(1/180 / n)
        assert!((mean - 0.5).abs() < 5.0 * (1.0 / 12.0 / n).sqrt(), "{}: mean {mean}", e.about.name);
        assert!((var - 1.0 / 12.0).abs() < 5.0 * (1.0 / 180.0 / n).sqrt(), "{}: variance {var}", e.about.name);
        // keys outside the film are still errors
        assert!(p.sample_padded([16, 0], 0, 0, 9).is_err() && p.sample_padded([0, 0], 0, 16, 9).is_err());
    }
}

#[test]
fn a_polled_preparation_stops_when_told() {
    use std::sync::atomic::{AtomicU32, Ordering};
    unsafe extern "C" fn stop_at_the_second_call(_: f64, user: *mut std::ffi::c_void) -> i32 {
        // SAFETY: the test passes a live AtomicU32
        let calls = unsafe { &*user.cast::<AtomicU32>() };
        i32::from(calls.fetch_add(1, Ordering::Relaxed) == 0)
    }
    let calls = AtomicU32::new(0);
    let mut error = [0 as std::ffi::c_char; 128];
    // SAFETY: valid strings and buffers; the callback takes the AtomicU32
    let s = unsafe {
        samplab_c::samplab_pixels_new_polled(
            c"heitz2019".as_ptr(),
            256,
            256,
            256,
            32,
            7,
            Some(stop_at_the_second_call),
            (&raw const calls).cast_mut().cast(),
            error.as_mut_ptr(),
            error.len(),
        )
    };
    assert!(s.is_null(), "prepared although told to stop");
    // SAFETY: NUL-terminated by the library
    let message = unsafe { std::ffi::CStr::from_ptr(error.as_ptr()) }.to_str().unwrap();
    assert!(message.contains("interrupted"), "{message}");
    // told to stop at the second call, and not called after it
    assert_eq!(calls.load(Ordering::Relaxed), 2);
    // and a quick family prepares with a poll as without one
    unsafe extern "C" fn go_on(_: f64, _: *mut std::ffi::c_void) -> i32 {
        1
    }
    // SAFETY: as above
    let quick = unsafe {
        samplab_c::samplab_pixels_new_polled(
            c"zsobol".as_ptr(),
            16,
            16,
            16,
            8,
            7,
            Some(go_on),
            std::ptr::null_mut(),
            error.as_mut_ptr(),
            error.len(),
        )
    };
    assert!(!quick.is_null());
    // SAFETY: made above, freed once
    unsafe { samplab_c::samplab_pixels_free(quick) };
}

/// `samplab_pixels_header_tables` gives the library's tables: sized by a NULL call, copied
/// whole into a buffer that holds them, nothing written into one that does not.
#[test]
fn the_header_tables_through_the_c_interface_are_the_librarys() {
    use samplab_c::*;
    let film = Film { width: 8, height: 8, spp: 16, dims: 8 };
    for (spec, words) in [("pmj02", 64 * 16), ("pmj02.bn:mask=16", 64 * 16 + 16 * 16 * 2), ("zsobol", 0)] {
        let name = std::ffi::CString::new(spec).unwrap();
        let mut error = [0 as std::ffi::c_char; 256];
        // SAFETY: a NUL-terminated spec and a writable error buffer of its length
        let s = unsafe { samplab_pixels_new(name.as_ptr(), 8, 8, 16, 8, 3, error.as_mut_ptr(), error.len()) };
        assert!(!s.is_null(), "{spec}");
        let ours = prepare(spec, film, Seed(3)).unwrap().header_tables();
        assert_eq!(ours.len(), words, "{spec}");
        // SAFETY: a live sampler; NULL, then buffers of the lengths given
        unsafe {
            assert_eq!(samplab_pixels_header_tables(s, std::ptr::null_mut(), 0), words, "{spec}");
            let mut short = vec![7u32; words.saturating_sub(1)];
            assert_eq!(samplab_pixels_header_tables(s, short.as_mut_ptr(), short.len()), words);
            assert!(short.iter().all(|&w| w == 7), "{spec}: written into a short buffer");
            let mut out = vec![0u32; words];
            assert_eq!(samplab_pixels_header_tables(s, out.as_mut_ptr(), out.len()), words);
            assert_eq!(out, ours, "{spec}");
            samplab_pixels_free(s);
        }
    }
}
