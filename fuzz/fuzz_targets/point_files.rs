//! Point files: the first byte picks the format (text, CSV, npy, JSON), the rest is the file.
#![no_main]

use libfuzzer_sys::fuzz_target;
use samplab::io::{Format, decode};

fuzz_target!(|data: &[u8]| {
    let Some((&which, bytes)) = data.split_first() else { return };
    let format = [Format::Text, Format::Csv, Format::Npy, Format::Json][usize::from(which % 4)];
    if let Ok(sets) = decode(bytes, format, "fuzz") {
        assert!(sets.iter().all(|s| s.as_slice().iter().all(|x| x.is_finite())));
    }
});
