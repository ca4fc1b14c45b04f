//! File input and output of the front ends.
//!
//! Output is atomic where that is possible: a regular file (or a path that does not exist yet)
//! is written to a temporary file in the same folder, then renamed over the target, so a crash
//! or a full disk never leaves half a file behind. A replaced file keeps its permission bits
//! (and, where the process may, its owner and group); a read-only file (no write permission
//! for its owner, or none for this process) is refused by name, not replaced. A symlink is followed to its target (the
//! link stays a link). A device, FIFO or socket (`-o /dev/null`, a pipe) is written in place:
//! renaming over it would replace the device by a regular file. `-` and `/dev/stdout` are the
//! standard output, written directly (see [`stdout_taken`]).
//!
//! Temporary files are named `.NAME.trochoplan-tmp-PID-N` (NAME shortened to keep the name
//! within 255 bytes): every temporary file still open is removed when the write fails, on a
//! panic and on SIGINT, SIGTERM or SIGHUP ([`remove_temporaries_on_exit`]); one left by a process
//! that was killed outright (SIGKILL, a power cut) is removed by the next write into its folder
//! once no process of its PID is alive.
//!
//! Input files must be regular files of at most [`MAX_INPUT_BYTES`]: a FIFO or `/dev/zero`
//! given as a job would hang or read without bound. [`check_distinct`] refuses an output that
//! is one of the inputs, or two outputs that are the same file, before any work.

use std::ffi::{OsStr, OsString};
use std::fs::{File, OpenOptions};
use std::io::{Read, Write};
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

/// Largest input file read (bytes): far above any job, polygon or path CSV a person writes.
pub const MAX_INPUT_BYTES: u64 = 64 * 1024 * 1024;

/// The part of every temporary file name after the target's name and before `PID-N`.
const TEMP_TAG: &str = ".trochoplan-tmp-";

/// The temporary files of this process that exist now (created, not yet renamed or removed).
static TEMPORARIES: Registry = Mutex::new(Vec::new());

/// Whether an output went to the standard output.
static STDOUT_TAKEN: AtomicBool = AtomicBool::new(false);

/// Whether `path` names the standard output: `-`, `/dev/stdout`, `/dev/fd/1` or
/// `/proc/self/fd/1`.
pub fn is_stdout(path: &Path) -> bool {
    matches!(path.as_os_str().as_bytes(), b"-" | b"/dev/stdout" | b"/dev/fd/1" | b"/proc/self/fd/1")
}

/// Whether an output was written to the standard output: the command's own report then goes
/// to the standard error, so that the output stays whole.
pub fn stdout_taken() -> bool {
    STDOUT_TAKEN.load(Ordering::Relaxed)
}

/// Write `bytes` to `path` (atomically for regular files, see the module docs). The error names
/// the path and the reason.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    if is_stdout(path) {
        STDOUT_TAKEN.store(true, Ordering::Relaxed);
        let mut out = std::io::stdout().lock();
        return out.write_all(bytes).and_then(|()| out.flush()).map_err(|e| fail(&e));
    }
    // the kernel's view first: `/dev/stderr` and `/proc/self/fd/N` are links that only it resolves
    if let Ok(m) = std::fs::metadata(path)
        && !m.is_file()
        && !m.is_dir()
    {
        return write_in_place(path, bytes).map_err(|e| fail(&e));
    }
    let target = resolve_links(path).map_err(|e| fail(&e))?;
    let existing = match std::fs::metadata(&target) {
        Ok(m) if m.is_dir() => return Err(fail(&"it is a folder")),
        Ok(m) if !m.is_file() => return write_in_place(&target, bytes).map_err(|e| fail(&e)),
        Ok(m) => Some(m),
        Err(_) => None,
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Some(name) = target.file_name() else {
        return Err(format!("{}: not a file path", path.display()));
    };
    if let Some(m) = &existing {
        // A read-only file stays as it is: one whose mode denies its owner writing (for root
        // too, who could write it), or that this process may not open for writing.
        let mode = m.permissions().mode() & 0o7777;
        let read_only = || fail(&format!("it is read-only (mode {mode:04o}): make it writable or choose another file"));
        if mode & 0o200 == 0 {
            return Err(read_only());
        }
        if let Err(e) = OpenOptions::new().write(true).open(&target) {
            return Err(if e.kind() == std::io::ErrorKind::PermissionDenied { read_only() } else { fail(&e) });
        }
    }
    remove_stale_temporaries(dir);
    let tmp = Temporary::create(&TEMPORARIES, dir.join(temporary_name(name))).map_err(|e| fail(&e))?;
    let result = (|| {
        let mut f = tmp.file()?;
        f.write_all(bytes)?;
        if let Some(m) = &existing {
            f.set_permissions(m.permissions())?;
            // the owner and group too where the process may set them (root, or its own group)
            let _ = std::os::unix::fs::fchown(f, Some(m.uid()), Some(m.gid()));
        }
        f.sync_all()?;
        tmp.rename_to(&target)
    })();
    result.map_err(|e| fail(&e))
}

/// A list of temporary files that exist now: [`TEMPORARIES`] for the writes of this process.
type Registry = Mutex<Vec<PathBuf>>;

/// A temporary file of this process, listed in its registry ([`TEMPORARIES`]) while it exists;
/// removed when dropped unless renamed.
struct Temporary {
    path: PathBuf,
    file: Option<File>,
    registry: &'static Registry,
}

impl Temporary {
    /// Create the file (it must not exist) and list it, under one lock: a signal's clean-up
    /// sees every file that exists.
    fn create(registry: &'static Registry, path: PathBuf) -> std::io::Result<Temporary> {
        let mut list = registry.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let file = OpenOptions::new().write(true).create_new(true).open(&path)?;
        list.push(path.clone());
        Ok(Temporary { path, file: Some(file), registry })
    }

    fn file(&self) -> std::io::Result<&File> {
        self.file.as_ref().ok_or_else(|| std::io::Error::other("temporary file already closed"))
    }

    /// Rename it over `target` and unlist it, under one lock.
    fn rename_to(&self, target: &Path) -> std::io::Result<()> {
        let mut list = self.registry.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        std::fs::rename(&self.path, target)?;
        list.retain(|p| p != &self.path);
        Ok(())
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        self.file = None;
        let mut list = self.registry.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(i) = list.iter().position(|p| p == &self.path) {
            let _ = std::fs::remove_file(&self.path);
            list.remove(i);
        }
    }
}

/// Remove every temporary file of `registry` ([`TEMPORARIES`]: of this process) that still
/// exists. `wait`: block for a write in progress (a signal); without it (a panic, which may have
/// struck inside a write) a held list is left to the unwinding writes' own clean-up.
fn remove_temporaries(registry: &Registry, wait: bool) {
    let list = if wait {
        Some(registry.lock().unwrap_or_else(std::sync::PoisonError::into_inner))
    } else {
        match registry.try_lock() {
            Ok(l) => Some(l),
            Err(std::sync::TryLockError::Poisoned(e)) => Some(e.into_inner()),
            Err(std::sync::TryLockError::WouldBlock) => None,
        }
    };
    if let Some(mut list) = list {
        for p in list.drain(..) {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Remove the temporary files of this process on a panic, and on SIGINT, SIGTERM and SIGHUP
/// (then exit with status 128 + the signal's number, as a shell reports a process the signal
/// ended). Called once at the start of the command-line front end.
pub fn remove_temporaries_on_exit() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        remove_temporaries(&TEMPORARIES, false);
        previous(info);
    }));
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    match signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) {
        Ok(mut signals) => {
            std::thread::spawn(move || {
                if let Some(sig) = signals.forever().next() {
                    // the list stays locked until the process ends: no new temporary file
                    let mut list = TEMPORARIES.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                    for p in list.drain(..) {
                        let _ = std::fs::remove_file(p);
                    }
                    std::process::exit(128 + sig);
                }
            });
        }
        Err(e) => {
            eprintln!("trochoplan: cannot watch for signals ({e}); an interrupted write may leave a temporary file")
        }
    }
}

/// The temporary name for target file name `name`: `.NAME.trochoplan-tmp-PID-N`, NAME cut to
/// keep the whole within the file system's 255-byte limit, N counting this process's files.
fn temporary_name(name: &OsStr) -> OsString {
    static COUNTER: AtomicU32 = AtomicU32::new(0);
    let tail = format!("{TEMP_TAG}{}-{}", std::process::id(), COUNTER.fetch_add(1, Ordering::Relaxed));
    let room = 255 - 1 - tail.len();
    let name = name.as_bytes();
    let mut out = Vec::with_capacity(255);
    out.push(b'.');
    out.extend_from_slice(&name[..name.len().min(room)]);
    out.extend_from_slice(tail.as_bytes());
    OsString::from_vec(out)
}

/// The PID in a temporary file name of this program (this naming, or the earlier
/// `.trochoplan-PID-N.tmp`), if it is one.
fn temporary_pid(name: &OsStr) -> Option<u32> {
    let name = std::str::from_utf8(name.as_bytes()).ok().or_else(|| {
        // a non-UTF-8 target name: only the tail after the tag matters
        let b = name.as_bytes();
        let tag = TEMP_TAG.as_bytes();
        let at = b.windows(tag.len()).rposition(|w| w == tag)?;
        std::str::from_utf8(&b[at..]).ok()
    })?;
    let digits = |s: &str| -> Option<u32> {
        let (pid, n) = s.split_once('-')?;
        n.bytes().all(|c| c.is_ascii_digit()).then_some(())?;
        (!n.is_empty() && pid.bytes().all(|c| c.is_ascii_digit())).then(|| pid.parse().ok())?
    };
    if let Some((_, tail)) = name.rsplit_once(TEMP_TAG) {
        return digits(tail);
    }
    name.strip_prefix(".trochoplan-")?.strip_suffix(".tmp").and_then(digits)
}

/// Remove the temporary files in `dir` of processes no longer alive (a SIGKILL or a crash of
/// the machine left them). Liveness is read from `/proc`; without it nothing is removed.
fn remove_stale_temporaries(dir: &Path) {
    let proc = Path::new("/proc/self");
    if !proc.exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = temporary_pid(&name) else { continue };
        let regular = e.file_type().is_ok_and(|t| t.is_file());
        if regular && pid != std::process::id() && !Path::new("/proc").join(pid.to_string()).exists() {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// What a file of a command is to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Input,
    Output,
}

/// The identity of a file for [`check_distinct`]: the standard output, an existing file's
/// device and inode, or a path that does not exist yet (its folder resolved).
#[derive(Clone, Debug, PartialEq, Eq)]
enum FileId {
    Stdout,
    Inode(u64, u64),
    New(PathBuf),
}

fn file_id(path: &Path) -> Option<FileId> {
    if is_stdout(path) {
        return Some(FileId::Stdout);
    }
    match std::fs::metadata(path) {
        // devices, FIFOs and sockets may be named twice (`/dev/null` for two outputs)
        Ok(m) if m.is_file() || m.is_dir() => Some(FileId::Inode(m.dev(), m.ino())),
        Ok(_) => None,
        Err(_) => {
            let target = resolve_links(path).ok()?;
            let dir = match target.parent() {
                Some(d) if !d.as_os_str().is_empty() => d,
                _ => Path::new("."),
            };
            Some(FileId::New(dir.canonicalize().ok()?.join(target.file_name()?)))
        }
    }
}

/// Refuse, before any work, an output that is also an input and two outputs that are the same
/// file (same inode, through links, `..` or `./`; or both the standard output). `files`: each
/// file's flag (as typed, e.g. `--export`), its path if given, and its role. The error names
/// both flags and the file.
pub fn check_distinct(files: &[(&str, Option<&Path>, Role)]) -> Result<(), String> {
    let known: Vec<(&str, &Path, Role, FileId)> = files
        .iter()
        .filter_map(|&(flag, path, role)| {
            let path = path?;
            Some((flag, path, role, file_id(path)?))
        })
        .collect();
    for (i, (flag_a, path_a, role_a, id_a)) in known.iter().enumerate() {
        for (flag_b, path_b, role_b, id_b) in &known[i + 1..] {
            if id_a != id_b || (*role_a == Role::Input && *role_b == Role::Input) {
                continue;
            }
            let (a, b) = (format!("{flag_a} {}", path_a.display()), format!("{flag_b} {}", path_b.display()));
            return Err(match (role_a, role_b, id_a) {
                (Role::Output, Role::Output, FileId::Stdout) => {
                    format!("{a} and {b} both write to the standard output: give one of them a file")
                }
                (Role::Output, Role::Output, _) => {
                    format!("{a} and {b} are the same file: give each output its own file")
                }
                (Role::Input, _, _) => format!("{b} would replace the input {a}: choose another output file"),
                (_, _, _) => format!("{a} would replace the input {b}: choose another output file"),
            });
        }
    }
    Ok(())
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
        // names of 246–255 bytes failed, the temporary name was 9+ bytes longer
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
        // `-o /dev/null` as root replaced /dev/null by a regular file
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
        // `--job /dev/zero` read without bound, a FIFO hung
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

    fn mode(p: &Path) -> u32 {
        std::fs::metadata(p).expect("meta").permissions().mode() & 0o7777
    }

    #[test]
    fn a_replaced_file_keeps_its_mode_and_read_only_files_are_refused() {
        let dir = tempfile::tempdir().expect("tempdir");
        for m in [0o640, 0o600, 0o755, 0o664] {
            let p = dir.path().join(format!("kept-{m:o}.nc"));
            std::fs::write(&p, "old").expect("write");
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(m)).expect("chmod");
            write_atomic(&p, b"new").expect("replace");
            assert_eq!(std::fs::read_to_string(&p).expect("read"), "new");
            assert_eq!(mode(&p), m, "mode {m:o} kept");
        }
        // read-only (no owner write bit): refused by name, left as it was, for root too
        for m in [0o444, 0o400] {
            let p = dir.path().join(format!("ro-{m:o}.nc"));
            std::fs::write(&p, "old").expect("write");
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(m)).expect("chmod");
            let err = write_atomic(&p, b"new").expect_err("read-only");
            assert!(err.contains("read-only") && err.contains(&format!("{m:04o}")) && err.contains("ro-"), "{err}");
            assert_eq!(std::fs::read_to_string(&p).expect("read"), "old");
            assert_eq!(mode(&p), m);
        }
        // a new file gets the usual mode of a created file (0666 less the umask), not the
        // mode of a file replaced before it
        let fresh = dir.path().join("fresh.nc");
        write_atomic(&fresh, b"x").expect("write");
        let reference = dir.path().join("reference");
        File::create(&reference).expect("create");
        assert_eq!(mode(&fresh), mode(&reference));
        let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").flatten().map(|e| e.file_name()).collect();
        assert!(left.iter().all(|n| temporary_pid(n).is_none()), "no temporary file left: {left:?}");
    }

    /// A PID that no process has now: a child that has been waited for.
    fn dead_pid() -> u32 {
        let mut child = std::process::Command::new("true").spawn().expect("spawn");
        let pid = child.id();
        child.wait().expect("wait");
        pid
    }

    #[test]
    fn stale_temporaries_of_dead_processes_are_removed_by_the_next_write() {
        let dir = tempfile::tempdir().expect("tempdir");
        let dead = dead_pid();
        let stale = [format!(".big.nc.trochoplan-tmp-{dead}-0"), format!(".trochoplan-{dead}-3.tmp")];
        // a live process's (this one's and PID 1's) and look-alikes of other names stay
        let kept = [
            format!(".big.nc.trochoplan-tmp-{}-0", std::process::id()),
            ".big.nc.trochoplan-tmp-1-0".to_string(),
            format!("big.nc.trochoplan-tmp-{dead}-x"),
            "notes.txt".to_string(),
        ];
        for n in stale.iter().chain(&kept) {
            std::fs::write(dir.path().join(n), "partial").expect("write");
        }
        write_atomic(&dir.path().join("out.nc"), b"G0 X0\n").expect("write");
        for n in &stale {
            assert!(!dir.path().join(n).exists(), "{n} removed");
        }
        for n in &kept {
            assert!(dir.path().join(n).exists(), "{n} kept");
        }
    }

    #[test]
    fn temporary_names_name_the_target_and_the_process_and_stay_short() {
        let pid = std::process::id();
        let n = temporary_name(OsStr::new("slot.nc"));
        let text = n.to_str().expect("utf-8");
        assert!(text.starts_with(".slot.nc.trochoplan-tmp-"), "{text}");
        assert_eq!(temporary_pid(&n), Some(pid));
        let long = "n".repeat(255);
        let n = temporary_name(OsStr::new(&long));
        assert!(n.len() <= 255, "{}", n.len());
        assert_eq!(temporary_pid(&n), Some(pid));
    }

    #[test]
    fn temporaries_listed_are_removed_on_a_signal_or_panic() {
        // a registry of its own: clearing the process's one would remove the temporary file of
        // a write another test is making at the same time
        static LISTED: Registry = Mutex::new(Vec::new());
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join(temporary_name(OsStr::new("x.nc")));
        let t = Temporary::create(&LISTED, p.clone()).expect("create");
        assert!(p.exists());
        remove_temporaries(&LISTED, true);
        assert!(!p.exists(), "removed");
        drop(t); // already unlisted: nothing left to do
        assert!(!p.exists());
    }

    #[test]
    fn stdout_names_are_recognised() {
        for p in ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"] {
            assert!(is_stdout(Path::new(p)), "{p}");
        }
        for p in ["./-", "stdout", "/dev/stderr", "-o"] {
            assert!(!is_stdout(Path::new(p)), "{p}");
        }
    }

    #[test]
    fn outputs_that_are_inputs_or_each_other_are_refused_with_both_flags() {
        let dir = tempfile::tempdir().expect("tempdir");
        let input = dir.path().join("in.txt");
        std::fs::write(&input, "0,0\n").expect("write");
        let same = dir.path().join("sub/../in.txt");
        std::fs::create_dir(dir.path().join("sub")).expect("mkdir");
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink("in.txt", &link).expect("symlink");
        let hard = dir.path().join("hard.txt");
        std::fs::hard_link(&input, &hard).expect("hard link");
        for out in [&input, &same, &link, &hard] {
            let err =
                check_distinct(&[("--polygon", Some(&input), Role::Input), ("--export", Some(out), Role::Output)])
                    .expect_err("output is the input");
            assert!(err.contains("--polygon") && err.contains("--export"), "{err}");
        }
        // two outputs, one not there yet, spelled two ways
        let new = dir.path().join("new.csv");
        let new2 = dir.path().join("sub/../new.csv");
        let err =
            check_distinct(&[("--series", Some(&new), Role::Output), ("--force-series", Some(&new2), Role::Output)])
                .expect_err("same output");
        assert!(err.contains("--series") && err.contains("--force-series") && err.contains("same file"), "{err}");
        let err = check_distinct(&[
            ("--series", Some(Path::new("-")), Role::Output),
            ("--force-series", Some(Path::new("/dev/stdout")), Role::Output),
        ])
        .expect_err("both stdout");
        assert!(err.contains("standard output"), "{err}");
        // distinct files, two inputs that are one file, and /dev/null twice are fine
        let other = dir.path().join("other.csv");
        check_distinct(&[
            ("--job", Some(&input), Role::Input),
            ("--materials", Some(&hard), Role::Input),
            ("--series", Some(&new), Role::Output),
            ("--force-series", Some(&other), Role::Output),
            ("--front", None, Role::Output),
        ])
        .expect("distinct");
        let null = Path::new("/dev/null");
        check_distinct(&[("--series", Some(null), Role::Output), ("--force-series", Some(null), Role::Output)])
            .expect("a device may take two outputs");
    }
}
