//! The C interface from C: the checked-in header is cbindgen's output for the source, and a
//! C program compiled with the system compiler against `libsamplab_c.so` gets the library's
//! values bit for bit.

use std::path::{Path, PathBuf};
use std::process::Command;

use samplab::Seed;
use samplab::pixel::{Film, PIXEL_SAMPLERS, prepare};

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

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

/// The folder holding the cdylib cargo built beside this test.
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    [deps, deps.parent().unwrap()]
        .into_iter()
        .find(|d| d.join("libsamplab_c.so").is_file())
        .expect("libsamplab_c.so beside the test binary")
        .to_path_buf()
}

/// Compile the C program `source` into `out`, against the header and the library.
fn compile(source: &Path, out: &Path) {
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(out)
        .arg(source)
        .arg("-I")
        .arg(crate_dir().join("include"))
        .arg("-L")
        .arg(library_dir())
        .args(["-lsamplab_c", "-lm"])
        .output()
        .unwrap_or_else(|e| panic!("running the C compiler {cc}: {e}"));
    assert!(
        status.status.success(),
        "{} does not compile: {}",
        source.display(),
        String::from_utf8_lossy(&status.stderr)
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
        let out = Command::new(&exe).arg(name).env("LD_LIBRARY_PATH", library_dir()).output().unwrap();
        assert!(out.status.success(), "{name}: exit {:?}: {}", out.status.code(), String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8(out.stdout).unwrap();
        let p = prepare(name, Film { width: 16, height: 9, spp: 16, dims: 8 }, Seed(7)).unwrap();
        assert!(text.starts_with(&format!("# {}\n", p.spec())), "{name}: {text}");
        let mut values = 0;
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let f: Vec<&str> = line.split(' ').collect();
            let k: Vec<u32> = f[..5].iter().map(|w| w.parse().unwrap()).collect();
            let ours = p.sample([k[0], k[1]], k[2], k[3], k[4]);
            assert_eq!(hex_float(f[5]), ours, "{name}: {line}");
            values += 1;
        }
        assert_eq!(values, 4 * 3 * 6 * 8, "{name}");
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
    let out = Command::new(&exe).env("LD_LIBRARY_PATH", library_dir()).output().unwrap();
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
