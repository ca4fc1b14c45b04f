//! File input and output of the front ends.
//!
//! Output is atomic where that is possible: a regular file (or a path that does not exist yet)
//! is written to a temporary file in the same folder, then renamed over the target, so a crash
//! or a full disk never leaves half a file behind. A symlink is followed to its target (the
//! link stays a link). A device, FIFO or socket (`-o /dev/null`, `-o /dev/stdout`, a pipe) is
//! written in place: renaming over it would replace the device by a regular file.
//!
//! Input files must be regular files of at most [`MAX_INPUT_BYTES`]: a FIFO or `/dev/zero`
//! given as a job would hang or read without bound.

use std::fs::{File, OpenOptions};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// Largest input file read (bytes): far above any job, polygon or path CSV a person writes.
pub const MAX_INPUT_BYTES: u64 = 64 * 1024 * 1024;

/// Write `bytes` to `path` (atomically for regular files, see the module docs). The error names
/// the path and the reason.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    let target = resolve_links(path).map_err(|e| fail(&e))?;
    match std::fs::metadata(&target) {
        Ok(m) if m.is_dir() => return Err(fail(&"it is a folder")),
        Ok(m) if !m.is_file() => return write_in_place(&target, bytes).map_err(|e| fail(&e)),
        _ => {}
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if target.file_name().is_none() {
        return Err(format!("{}: not a file path", path.display()));
    }
    let tmp = dir.join(temporary_name());
    let result = (|| {
        let mut f = OpenOptions::new().write(true).create_new(true).open(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, &target)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        fail(&e)
    })
}

/// Read a whole input file as text: a regular file (symlinks followed) of at most
/// [`MAX_INPUT_BYTES`]. `what` names the file in the error ("job file", "polygon file").
pub fn read_input(path: &Path, what: &str) -> Result<String, String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot read {what} {}: {e}", path.display());
    let meta = std::fs::metadata(path).map_err(|e| fail(&e))?;
    if !meta.is_file() {
        return Err(fail(&"not a regular file (a FIFO, device or folder cannot be read as input)"));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(fail(&format!("{} bytes, more than the {MAX_INPUT_BYTES} bytes an input may have", meta.len())));
    }
    let mut text = String::new();
    // `take` bounds the read even if the file grows while we read it
    File::open(path).and_then(|f| f.take(MAX_INPUT_BYTES + 1).read_to_string(&mut text)).map_err(|e| fail(&e))?;
    if text.len() as u64 > MAX_INPUT_BYTES {
        return Err(fail(&format!("more than the {MAX_INPUT_BYTES} bytes an input may have")));
    }
    Ok(text)
}

/// `path` with every symlink in its last component followed (a missing target is fine: the
/// write creates it where the link points).
fn resolve_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    // a bound instead of the OS's loop detection: a link cycle is an error, not a hang
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = std::fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// A short temporary name, unique within this process and across processes: a long target
/// name must not make it longer than the file system's 255-byte limit.
fn temporary_name() -> String {
    static COUNTER: AtomicU32 = AtomicU32::new(0);
    format!(".trochoplan-{}-{}.tmp", std::process::id(), COUNTER.fetch_add(1, Ordering::Relaxed))
}

/// Write to a device, FIFO or socket as it is (no truncation, no rename).
fn write_in_place(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut f = OpenOptions::new().write(true).open(path)?;
    f.write_all(bytes)?;
    f.flush()
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn writes_and_replaces_whole_file() {
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("out.csv");
        write_atomic(&p, b"first").expect("write");
        write_atomic(&p, b"second").expect("write");
        assert_eq!(std::fs::read_to_string(&p).expect("read"), "second");
        assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 1, "no temporary file left");
    }

    #[test]
    fn missing_folder_is_a_clear_error() {
        let err = write_atomic(Path::new("/nonexistent-dir/x.csv"), b"x").expect_err("must fail");
        assert!(err.contains("/nonexistent-dir/x.csv"), "{err}");
    }

    #[test]
    fn longest_legal_names_can_be_written() {
        // issue #13: names of 246–255 bytes failed, the temporary name was 9+ bytes longer
        let dir = tempfile::tempdir().expect("tempdir");
        for len in [246, 250, 255] {
            let p = dir.path().join(format!("{}.nc", "n".repeat(len - 3)));
            write_atomic(&p, b"G0 X0\n").unwrap_or_else(|e| panic!("{len} bytes: {e}"));
            assert_eq!(std::fs::read(&p).expect("read"), b"G0 X0\n");
        }
        assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 3, "no temporary file left");
    }

    #[test]
    fn symlinks_are_followed_and_stay_links() {
        let dir = tempfile::tempdir().expect("tempdir");
        let real = dir.path().join("real.nc");
        std::fs::write(&real, "old").expect("write");
        let link = dir.path().join("link.nc");
        std::os::unix::fs::symlink("real.nc", &link).expect("symlink");
        write_atomic(&link, b"new").expect("write through the link");
        assert!(std::fs::symlink_metadata(&link).expect("meta").file_type().is_symlink(), "still a link");
        assert_eq!(std::fs::read_to_string(&real).expect("read"), "new");
        // a dangling link creates its target
        let dangling = dir.path().join("dangling.nc");
        std::os::unix::fs::symlink("made.nc", &dangling).expect("symlink");
        write_atomic(&dangling, b"x").expect("write");
        assert_eq!(std::fs::read_to_string(dir.path().join("made.nc")).expect("read"), "x");
    }

    #[test]
    fn devices_are_written_in_place_not_replaced() {
        // issue #13: `-o /dev/null` as root replaced /dev/null by a regular file
        write_atomic(Path::new("/dev/null"), b"G0 X0\n").expect("write to /dev/null");
        let meta = std::fs::metadata("/dev/null").expect("meta");
        assert!(!meta.is_file(), "/dev/null must still be a device");
    }

    #[test]
    fn folders_are_refused_by_name() {
        let dir = tempfile::tempdir().expect("tempdir");
        let err = write_atomic(dir.path(), b"x").expect_err("a folder");
        assert!(err.contains("folder"), "{err}");
    }

    #[test]
    fn inputs_must_be_bounded_regular_files() {
        let dir = tempfile::tempdir().expect("tempdir");
        let job = dir.path().join("job.toml");
        std::fs::write(&job, "feed = 600\n").expect("write");
        assert_eq!(read_input(&job, "job file").expect("read"), "feed = 600\n");
        // issue #13: `--job /dev/zero` read without bound, a FIFO hung
        for p in ["/dev/zero", "/dev/null"] {
            let err = read_input(Path::new(p), "job file").expect_err(p);
            assert!(err.contains("job file") && err.contains("regular file"), "{err}");
        }
        let fifo = dir.path().join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
        assert!(made.success());
        let err = read_input(&fifo, "job file").expect_err("a FIFO");
        assert!(err.contains("regular file"), "{err}");
        let err = read_input(dir.path(), "polygon file").expect_err("a folder");
        assert!(err.contains("polygon file"), "{err}");
        let big = dir.path().join("big.csv");
        let f = File::create(&big).expect("create");
        f.set_len(MAX_INPUT_BYTES + 1).expect("sparse file");
        let err = read_input(&big, "path file").expect_err("too big");
        assert!(err.contains("bytes"), "{err}");
    }
}
