//! The header-only C++ samplers (`include/samplab/samplers.hpp`): their generated tables are
//! the library's, and compiled as host C++ by the system compiler they give the library's
//! values bit for bit, on a million random keys per family.

use std::fmt::Write as _;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use samplab::Seed;
use samplab::construct::cbc::{self, Weights};
use samplab::construct::pbrt::halton_digit_count;
use samplab::construct::radical::PRIMES;
use samplab::construct::sobol::{SOBOL_MAX_DIMS, direction_numbers};
use samplab::pixel::{Film, prepare};
use samplab::seed::mix64;

mod common;

use common::crate_dir;

fn include_dir() -> PathBuf {
    crate_dir().join("include")
}

/// How many dimensions pbrt's Halton sampler (and the header's) has: its prime table's.
const HALTON_DIMS: usize = 1000;

/// How many dimensions the pixel family `lattice` has.
const LATTICE_DIMS: usize = 1024;

/// The text of `include/samplab/tables.hpp`: the Sobol' direction numbers, the primes and
/// the Halton digit counts, each as a macro that the host and the device arrays both expand.
fn tables() -> String {
    let mut t = String::from(
        "/* The tables of samplers.hpp, generated from samplab's by the test `header.rs`\n \
         * (SAMPLAB_WRITE_HEADER=1 cargo test -p samplab-c --test header): do not edit.\n \
         * Sobol': Joe & Kuo 2008 (new-joe-kuo-6.21201), column k of dimension d bit-reversed\n \
         * (bit 0 the most significant digit). Lattice: the pixel family's generating vector\n \
         * (embedded fast CBC for 2^16 points, Nuyens & Cools 2006, weights (j + 1)^-2). Halton: the first primes, and how many digits pbrt-v4's\n \
         * single-precision loops randomize in each base ([0] Owen, [1] digit permutations). */\n\
         #ifndef SAMPLAB_TABLES_HPP\n#define SAMPLAB_TABLES_HPP\n\n\
         /* the fixed-width types: samplers.hpp declares them for NVRTC */\n\
         #ifndef __CUDACC_RTC__\n#include <stdint.h>\n#endif\n\n",
    );
    writeln!(
        t,
        "#define SAMPLAB_SOBOL_DIMS {SOBOL_MAX_DIMS}\n#define SAMPLAB_HALTON_DIMS {HALTON_DIMS}\n#define SAMPLAB_LATTICE_DIMS {LATTICE_DIMS}\n"
    )
    .unwrap();
    t.push_str("#define SAMPLAB_SOBOL_TABLE { \\\n");
    for d in 0..SOBOL_MAX_DIMS {
        let columns: Vec<String> = direction_numbers(d).iter().map(|c| format!("0x{:x}", c.reverse_bits())).collect();
        writeln!(t, "    {{{}}}, \\", columns.join(",")).unwrap();
    }
    t.push_str("}\n\n#define SAMPLAB_PRIME_TABLE { \\\n");
    for chunk in PRIMES[..HALTON_DIMS].chunks(16) {
        let primes: Vec<String> = chunk.iter().map(u32::to_string).collect();
        writeln!(t, "    {}, \\", primes.join(",")).unwrap();
    }
    t.push_str("}\n\n#define SAMPLAB_HALTON_DIGITS_TABLE { \\\n");
    for chunk in PRIMES[..HALTON_DIMS].chunks(16) {
        let counts: Vec<String> = chunk
            .iter()
            .map(|&b| format!("{{{},{}}}", halton_digit_count(b, false), halton_digit_count(b, true)))
            .collect();
        writeln!(t, "    {}, \\", counts.join(",")).unwrap();
    }
    // the pixel family's generating vector: embedded fast CBC for 2^16 points, weights
    // (j + 1)^-2 (greedy, so the first d components are every film's of d dimensions)
    t.push_str("}\n\n#define SAMPLAB_LATTICE_TABLE { \\\n");
    let z = cbc::construct(1 << 16, LATTICE_DIMS, Weights::decaying(2.0), true).unwrap();
    for chunk in z.chunks(16) {
        let z: Vec<String> = chunk.iter().map(u64::to_string).collect();
        writeln!(t, "    {}, \\", z.join(",")).unwrap();
    }
    t.push_str(
        "}\n\nnamespace samplab {\nnamespace tables {\n\n\
         /* the host's copies (NVRTC compiles device code only) */\n\
         #ifndef __CUDACC_RTC__\n\
         static const uint32_t sobol_reversed[SAMPLAB_SOBOL_DIMS][32] = SAMPLAB_SOBOL_TABLE;\n\
         static const uint32_t primes[SAMPLAB_HALTON_DIMS] = SAMPLAB_PRIME_TABLE;\n\
         static const uint8_t halton_digits[SAMPLAB_HALTON_DIMS][2] = SAMPLAB_HALTON_DIGITS_TABLE;\n\
         static const uint32_t lattice[SAMPLAB_LATTICE_DIMS] = SAMPLAB_LATTICE_TABLE;\n\
         #endif\n\n\
         #ifdef SAMPLAB_DEVICE_TABLE\n\
         static SAMPLAB_DEVICE_TABLE const uint32_t sobol_reversed_device[SAMPLAB_SOBOL_DIMS][32] = SAMPLAB_SOBOL_TABLE;\n\
         static SAMPLAB_DEVICE_TABLE const uint32_t primes_device[SAMPLAB_HALTON_DIMS] = SAMPLAB_PRIME_TABLE;\n\
         static SAMPLAB_DEVICE_TABLE const uint8_t halton_digits_device[SAMPLAB_HALTON_DIMS][2] = \
         SAMPLAB_HALTON_DIGITS_TABLE;\n\
         static SAMPLAB_DEVICE_TABLE const uint32_t lattice_device[SAMPLAB_LATTICE_DIMS] = SAMPLAB_LATTICE_TABLE;\n\
         #endif\n\n}  // namespace tables\n}  // namespace samplab\n\n#endif\n",
    );
    t
}

#[test]
fn the_headers_tables_are_the_librarys() {
    let path = include_dir().join("samplab/tables.hpp");
    let generated = tables();
    if std::env::var_os("SAMPLAB_WRITE_HEADER").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/samplab/tables.hpp is not the library's tables: run SAMPLAB_WRITE_HEADER=1 cargo test -p samplab-c --test header"
    );
}

/// `source` compiled as C++17 with the system C++ compiler (-Wall -Wextra and `extra`),
/// warnings as errors, the header on the include path.
fn compile_cxx(source: &Path, exe: &Path, extra: &[&str]) {
    let cxx = std::env::var("CXX").unwrap_or_else(|_| "c++".into());
    let out = Command::new(&cxx)
        .args(["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror"])
        .args(extra)
        .arg("-I")
        .arg(include_dir())
        .arg(source)
        .arg("-o")
        .arg(exe)
        .output()
        .unwrap_or_else(|e| panic!("running the C++ compiler {cxx}: {e}"));
    assert!(out.status.success(), "{} does not compile: {}", source.display(), String::from_utf8_lossy(&out.stderr));
}

/// `tests/header_values.cpp`, compiled with every warning that might catch a narrowing.
fn compile(dir: &Path) -> PathBuf {
    let exe = dir.join("header_values");
    let strict = ["-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow"];
    compile_cxx(&crate_dir().join("tests/header_values.cpp"), &exe, &strict);
    exe
}

/// Keys: (x, y, frame, index, dimension).
type Key = [u32; 5];

/// `count` random keys inside the film (frames 0 to 3: frame 0 takes pbrt's seed as it is).
fn keys(film: Film, count: usize, stream: u64) -> Vec<Key> {
    let mut state = mix64(stream);
    let mut below = |n: u32| {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        ((u128::from(mix64(state)) * u128::from(n)) >> 64) as u32
    };
    (0..count).map(|_| [below(film.width), below(film.height), below(4), below(film.spp), below(film.dims)]).collect()
}

/// The header's values of `keys` for a family (the program's arguments).
fn header_values(exe: &Path, args: &[String], keys: &[Key]) -> Vec<f64> {
    let mut child = Command::new(exe).args(args).stdin(Stdio::piped()).stdout(Stdio::piped()).spawn().unwrap();
    let bytes: Vec<u8> = keys.iter().flatten().flat_map(|w| w.to_le_bytes()).collect();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(&bytes));
    let mut out = Vec::new();
    child.stdout.take().unwrap().read_to_end(&mut out).unwrap();
    writer.join().unwrap().unwrap();
    assert!(child.wait().unwrap().success(), "header_values {args:?}");
    out.chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect()
}

/// The first key whose values differ, for the failure message.
fn first_difference(name: &str, keys: &[Key], header: &[f64], ours: impl Fn(&Key) -> f64) {
    assert_eq!(header.len(), keys.len(), "{name}: one value per key");
    if let Some((k, h)) = keys.iter().zip(header).find(|(k, h)| h.to_bits() != ours(k).to_bits()) {
        panic!("{name}: key (x, y, frame, index, dim) = {k:?}: the header gives {h:e}, the library {:e}", ours(k));
    }
}

/// One pixel family through the header and the library: `count` keys of `film` (the
/// family's header tables, where it has any, passed in a file beside the program).
fn pixel_family(exe: &Path, spec: &str, family: &str, randomize: &str, film: Film, count: usize) {
    let seed = mix64(spec.len() as u64 ^ u64::from(film.spp)) | 1 << 40;
    let pixels = prepare(spec, film, Seed(seed)).unwrap();
    let keys = keys(film, count, seed);
    let mut args = [
        family,
        &seed.to_string(),
        &film.width.to_string(),
        &film.height.to_string(),
        &film.spp.to_string(),
        randomize,
    ]
    .map(str::to_string)
    .to_vec();
    let tables = pixels.header_tables();
    if !tables.is_empty() {
        let path = exe.with_file_name(format!("tables-{}", film.spp));
        std::fs::write(&path, tables.iter().flat_map(|w| w.to_le_bytes()).collect::<Vec<u8>>()).unwrap();
        args.push(path.display().to_string());
    }
    let header = header_values(exe, &args, &keys);
    first_difference(spec, &keys, &header, |k| pixels.sample([k[0], k[1]], k[2], k[3], k[4]));
}

#[test]
fn the_header_gives_the_librarys_values_on_a_million_keys_per_family() {
    let dir = std::env::temp_dir().join(format!("samplab-header-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let exe = compile(&dir);
    const MILLION: usize = 1_000_000;
    let film = |width, height, spp, dims| Film { width, height, spp, dims };
    let hd = |spp, dims| film(1920, 1080, spp, dims);
    pixel_family(&exe, "independent", "independent", "-", hd(64, 64), MILLION);
    // a prime, a square and a rectangular count of strata
    for spp in [7, 64, 96] {
        pixel_family(&exe, "stratified", "stratified", "-", hd(spp, 64), MILLION / 3 + 1);
    }
    // the Hilbert curve's order, on a film whose sides are not a power of two
    pixel_family(&exe, "zsobol:curve=hilbert", "zsobol-hilbert", "fastowen", hd(32, 64), MILLION / 2);
    pixel_family(
        &exe,
        "zsobol:curve=hilbert,randomize=owen",
        "zsobol-hilbert",
        "owen",
        film(100, 60, 64, 64),
        MILLION / 2,
    );
    // films of fewer dimensions than the table: the vector's components are greedy
    pixel_family(&exe, "lattice", "lattice", "-", hd(64, 64), MILLION / 2);
    pixel_family(&exe, "lattice", "lattice", "-", film(64, 48, 1 << 18, LATTICE_DIMS as u32), MILLION / 2);
    // past 2^16 samples the index's high digits are read too
    pixel_family(&exe, "sobol", "sobol", "-", film(64, 48, 1 << 18, SOBOL_MAX_DIMS as u32), MILLION);
    pixel_family(&exe, "sobol", "sobol+table", "-", film(64, 48, 1 << 18, 600), MILLION / 4);
    for randomize in ["none", "xor", "fastowen", "owen"] {
        pixel_family(
            &exe,
            &format!("sobol.padded:randomize={randomize}"),
            "sobol.padded",
            randomize,
            hd(100, 64),
            MILLION / 4,
        );
        // an even and an odd power of two samples (pbrt's odd digit)
        for spp in [64, 32] {
            pixel_family(&exe, &format!("zsobol:randomize={randomize}"), "zsobol", randomize, hd(spp, 64), MILLION / 8);
        }
    }
    // a power of two samples (the index nested-uniform scrambled) and not (hashed)
    for spp in [64, 100] {
        pixel_family(&exe, "pmj02", "pmj02", "-", hd(spp, 64), MILLION / 4);
        pixel_family(&exe, "pmj02.bn", "pmj02.bn", "64", hd(spp, 64), MILLION / 4);
    }
    for randomize in ["none", "permutedigits", "owen"] {
        pixel_family(
            &exe,
            &format!("halton:randomize={randomize}"),
            "halton",
            randomize,
            hd(16, HALTON_DIMS as u32),
            MILLION / 3 + 1,
        );
    }
    // the digit permutations from a table (frame 0, dimensions below 200; the others hashed)
    pixel_family(&exe, "halton", "halton+table", "permutedigits", hd(16, 400), MILLION / 4);
    // a film smaller than a tile, and one that is not square
    pixel_family(&exe, "halton", "halton", "permutedigits", film(20, 10, 7, 40), 10_000);
    // the point-set sequences served per pixel (the shift's offsets cost O(dim): 64 dims)
    for randomize in ["xor", "owen", "shift"] {
        let dims = if randomize == "shift" { 64 } else { SOBOL_MAX_DIMS as u32 };
        let spec = format!("sobol.{randomize}");
        pixel_family(&exe, &spec, "sobol-sequence", randomize, film(64, 48, 1 << 18, dims), MILLION / 3 + 1);
    }
    for randomize in ["none", "xor", "owen", "shift"] {
        // any index of the 32-bit sequence; the shift's offsets cost O(dim) each: 64 dims
        let dims = if randomize == "shift" { 64 } else { SOBOL_MAX_DIMS as u32 };
        let keys = keys(film(1, 1, u32::MAX, dims), MILLION / 4, randomize.len() as u64);
        let spec = if randomize == "none" { "sobol".to_string() } else { format!("sobol.{randomize}") };
        let plan = samplab::sampler::build(&spec).unwrap().plan(1, dims as usize).unwrap();
        let seed = 0xDEAD_BEEF_u64 << randomize.len();
        let access = plan.access(Seed(seed)).unwrap();
        let args = ["points:sobol", &seed.to_string(), "0", "0", "0", randomize].map(str::to_string);
        let header = header_values(&exe, &args, &keys);
        first_difference(&spec, &keys, &header, |k| access.sample(u64::from(k[3]), k[4] as usize).unwrap());
        // `samplab generate --seed S` writes set 0 under set_seed(S, 0)
        let set = samplab::sampler::build(&spec).unwrap().plan(64, 3).unwrap().generate_sets(
            Seed(seed),
            1,
            &samplab::progress::Progress::SILENT,
        );
        let first = set.unwrap().remove(0);
        let keys: Vec<Key> = (0..64).flat_map(|i| (0..3).map(move |d| [0, 0, 0, i, d])).collect();
        let derived = samplab::Seed(seed).derive(0).0.to_string();
        let args = ["points:sobol", &derived, "0", "0", "0", randomize].map(str::to_string);
        assert_eq!(header_values(&exe, &args, &keys), first.as_slice(), "{spec}: set 0 of generate --seed {seed}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The guide's C++ example (docs/guide/header.md) compiles as printed and prints the
/// library's values.
#[test]
fn the_guides_cpp_example_runs() {
    let page = std::fs::read_to_string(crate_dir().join("../../docs/guide/header.md")).unwrap();
    let code =
        page.split("```cpp\n").nth(1).and_then(|rest| rest.split("```").next()).expect("a C++ block in header.md");
    let dir = std::env::temp_dir().join(format!("samplab-header-guide-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (source, exe) = (dir.join("app.cpp"), dir.join("app"));
    std::fs::write(&source, code).unwrap();
    compile_cxx(&source, &exe, &[]);
    let out = Command::new(&exe).output().unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let values: Vec<f64> =
        String::from_utf8(out.stdout).unwrap().split_whitespace().map(|w| w.parse().unwrap()).collect();
    let zsobol = prepare("zsobol", Film { width: 1920, height: 1080, spp: 64, dims: 32 }, Seed(7)).unwrap();
    let sobol = prepare("sobol", Film { width: 1920, height: 1080, spp: 64, dims: 32 }, Seed(7)).unwrap();
    assert_eq!(
        values,
        [zsobol.sample([640, 360], 0, 5, 2), zsobol.sample([640, 360], 0, 5, 3), sobol.sample([640, 360], 0, 5, 4)]
    );
}

/// The small path tracer of `bench/c-client/pathtracer.c` built twice, against the C
/// interface and (as C++) on the header alone: the same image bytes for every family the
/// header has without the C interface's tables, padding past the film's 12 dimensions
/// included (about a fifth of the values drawn).
#[test]
fn the_path_tracer_renders_the_same_image_through_the_header() {
    let dir = std::env::temp_dir().join(format!("samplab-header-pathtracer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = crate_dir().join("../../bench/c-client/pathtracer.c");
    let (c, header) = (dir.join("pathtracer-c"), dir.join("pathtracer-header"));
    common::compile(&source, &c);
    compile_cxx(&source, &header, &["-x", "c++", "-DSAMPLAB_HEADER"]);
    for family in ["independent", "stratified", "sobol", "sobol.padded", "zsobol", "lattice", "halton"] {
        let image = |exe: &Path| {
            let out = dir.join("image.f32");
            let run = Command::new(exe).args([family, "16", "16", "12", "7"]).arg(&out).output().unwrap();
            assert!(run.status.success(), "{family}: {}", String::from_utf8_lossy(&run.stderr));
            std::fs::read(&out).unwrap()
        };
        let ours = image(&c);
        assert_eq!(ours.len(), 16 * 16 * 4, "{family}");
        assert!(image(&header) == ours, "{family}: the header's image differs from the C interface's");
    }
    std::fs::remove_dir_all(&dir).ok();
}
