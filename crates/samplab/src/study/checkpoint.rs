//! Finished chunks of one study in a folder, so that a stopped study resumes: a manifest
//! `study.json` naming the study by its fingerprint, and one file per chunk,
//! `<fingerprint's first 16 characters>-<chunk>.chunk`: the line `samplab-chunk 1`, a JSON
//! header line (`{"chunk":i,"fingerprint":...,"length":bytes}`), the chunk's bytes, and the
//! SHA-256 of all that. Every file is written to a temporary name and renamed, so it is
//! whole or absent; one that fails any check is refused with an error naming it, never used.

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use crate::error::{Error, Result};
use crate::io::write_atomic;

const MAGIC: &[u8] = b"samplab-chunk 1\n";

/// A study's fingerprint from its description `text`: the SHA-256, in hex (what names its
/// chunk files; Python's `Study` hashes its own canonical description the same way).
pub fn fingerprint(text: &str) -> String {
    Sha256::digest(text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect()
}

/// The chunk files of one study in one folder.
#[derive(Debug)]
pub struct Checkpoint {
    folder: PathBuf,
    fingerprint: String,
}

fn io(path: &Path, reason: impl std::fmt::Display) -> Error {
    Error::Io { path: path.display().to_string(), reason: reason.to_string() }
}

impl Checkpoint {
    /// The checkpoint of the study `fingerprint` (its manifest `manifest`, a JSON object
    /// with a `fingerprint` field) in `folder`, made if absent.
    ///
    /// # Errors
    /// `folder` is a file or cannot be made, or holds another study's manifest.
    pub fn open(folder: &Path, fingerprint: &str, manifest: &str) -> Result<Checkpoint> {
        if folder.exists() && !folder.is_dir() {
            return Err(io(folder, "the checkpoint must be a folder, and this is a file"));
        }
        std::fs::create_dir_all(folder).map_err(|e| io(folder, e))?;
        let path = folder.join("study.json");
        match std::fs::read_to_string(&path) {
            Ok(theirs) => {
                let theirs: serde_json::Value =
                    serde_json::from_str(&theirs).map_err(|_| io(&path, "not a samplab study manifest"))?;
                let theirs = theirs.get("fingerprint").and_then(serde_json::Value::as_str);
                let theirs = theirs.ok_or_else(|| io(&path, "not a samplab study manifest"))?;
                if theirs != fingerprint {
                    let (a, b) = (&theirs[..theirs.len().min(12)], &fingerprint[..fingerprint.len().min(12)]);
                    return Err(io(
                        folder,
                        format!(
                            "the checkpoint holds another study (fingerprint {a}, this one {b}); use another directory"
                        ),
                    ));
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => write_atomic(&path, manifest.as_bytes())?,
            Err(e) => return Err(io(&path, e)),
        }
        Ok(Checkpoint { folder: folder.to_path_buf(), fingerprint: fingerprint.to_string() })
    }

    fn prefix(&self) -> &str {
        &self.fingerprint[..self.fingerprint.len().min(16)]
    }

    fn file(&self, chunk: usize) -> PathBuf {
        self.folder.join(format!("{}-{chunk}.chunk", self.prefix()))
    }

    fn header(&self, chunk: usize, length: usize) -> String {
        serde_json::json!({"chunk": chunk, "fingerprint": self.fingerprint, "length": length}).to_string()
    }

    /// Keeps chunk `chunk`'s bytes.
    ///
    /// # Errors
    /// The file cannot be written.
    pub fn save(&self, chunk: usize, data: &[u8]) -> Result<()> {
        let mut body = MAGIC.to_vec();
        body.extend_from_slice(self.header(chunk, data.len()).as_bytes());
        body.push(b'\n');
        body.extend_from_slice(data);
        let digest = Sha256::digest(&body);
        body.extend_from_slice(&digest);
        write_atomic(&self.file(chunk), &body)
    }

    /// The kept chunks among the first `chunks`, by chunk.
    ///
    /// # Errors
    /// A chunk file that is not whole, not a chunk file, or another chunk's or another
    /// study's; a chunk file of another study in the folder.
    pub fn load(&self, chunks: usize) -> Result<Vec<(usize, Vec<u8>)>> {
        let mut found = Vec::new();
        for chunk in 0..chunks {
            let path = self.file(chunk);
            if path.exists() {
                found.push((chunk, self.read(&path, chunk)?));
            }
        }
        for entry in std::fs::read_dir(&self.folder).map_err(|e| io(&self.folder, e))? {
            let name = entry.map_err(|e| io(&self.folder, e))?.file_name();
            let name = name.to_string_lossy();
            if name.ends_with(".chunk") && !name.starts_with(self.prefix()) {
                return Err(io(&self.folder.join(&*name), "a chunk of another study; use another directory"));
            }
        }
        Ok(found)
    }

    fn read(&self, path: &Path, chunk: usize) -> Result<Vec<u8>> {
        let bad = |why: &str| io(path, format!("{why}; delete it to compute the chunk again"));
        // a link to a device (/dev/zero) or a FIFO would be read without end
        if !path.is_file() {
            return Err(bad("not a regular file"));
        }
        let raw = std::fs::read(path).map_err(|e| io(path, e))?;
        if !raw.starts_with(MAGIC) || raw.len() < MAGIC.len() + 32 {
            return Err(bad("not a samplab chunk file"));
        }
        let (body, digest) = raw.split_at(raw.len() - 32);
        if Sha256::digest(body).as_slice() != digest {
            return Err(bad("corrupted (its checksum does not match)"));
        }
        let rest = &body[MAGIC.len()..];
        let end = rest.iter().position(|&b| b == b'\n').ok_or_else(|| bad("not a samplab chunk file"))?;
        let header: serde_json::Value =
            serde_json::from_slice(&rest[..end]).map_err(|_| bad("not a samplab chunk file"))?;
        let data = &rest[end + 1..];
        if header.get("fingerprint").and_then(serde_json::Value::as_str) != Some(&self.fingerprint) {
            return Err(bad("a chunk of another study"));
        }
        if header != serde_json::from_str::<serde_json::Value>(&self.header(chunk, data.len())).expect("JSON") {
            let field = |k: &str| header.get(k).map_or("?".to_string(), ToString::to_string);
            return Err(bad(&format!(
                "holds chunk {} of {} bytes, not chunk {chunk}",
                field("chunk"),
                field("length")
            )));
        }
        Ok(data.to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_chunk_reads_back_and_a_damaged_one_is_refused() {
        let dir = std::env::temp_dir().join(format!("samplab-checkpoint-{}", std::process::id()));
        let c = Checkpoint::open(&dir, "ab12", r#"{"fingerprint":"ab12"}"#).unwrap();
        c.save(1, b"hello").unwrap();
        assert_eq!(c.load(3).unwrap(), vec![(1, b"hello".to_vec())]);
        // the header is JSON with sorted keys, as earlier checkpoints wrote it
        let raw = std::fs::read(dir.join("ab12-1.chunk")).unwrap();
        assert!(raw.starts_with(b"samplab-chunk 1\n{\"chunk\":1,\"fingerprint\":\"ab12\",\"length\":5}\nhello"));
        // one flipped bit: the checksum fails
        let mut flipped = raw.clone();
        flipped[MAGIC.len() + 40] ^= 1;
        std::fs::write(dir.join("ab12-1.chunk"), &flipped).unwrap();
        assert!(c.load(3).unwrap_err().to_string().contains("corrupted"));
        // chunk 1's file under chunk 2's name
        std::fs::write(dir.join("ab12-1.chunk"), &raw).unwrap();
        std::fs::write(dir.join("ab12-2.chunk"), &raw).unwrap();
        assert!(c.load(3).unwrap_err().to_string().contains("holds chunk 1 of 5 bytes, not chunk 2"));
        // another study's manifest
        assert!(Checkpoint::open(&dir, "cd34", "{}").unwrap_err().to_string().contains("holds another study"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
