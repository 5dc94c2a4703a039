//! The one way host-sim writes a file: into a temporary file beside the target, renamed onto it only once
//! complete, and only onto a new path or a regular file (or a symbolic link to one).
//!
//! A directory, FIFO, socket or device at the target (or a link to one) is refused with [`Error::Output`]
//! naming the path (exit code 1), before anything is written and again before the rename; the target is
//! then untouched. A failed write removes the temporary file (`.NAME.partial-PID` in the target's
//! directory), so nothing half-written is left behind.

use crate::error::Error;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// What a non-regular file at `path` is, or `None` when `path` is new, a regular file, or a link to a
/// regular file (or to nothing).
fn refused_kind(path: &Path) -> Result<Option<&'static str>, Error> {
    let metadata = match std::fs::symlink_metadata(path) {
        Ok(metadata) => metadata,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(Error::output(path, e)),
    };
    let (metadata, link) = if metadata.file_type().is_symlink() {
        match std::fs::metadata(path) {
            Ok(target) => (target, " link to a"),
            // A dangling link: renaming onto it replaces the link.
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(Error::output(path, e)),
        }
    } else {
        (metadata, "")
    };
    let kind = kind_of(&metadata.file_type());
    Ok(kind.map(|kind| if link.is_empty() { kind } else { link_kind(kind) }))
}

fn kind_of(file_type: &std::fs::FileType) -> Option<&'static str> {
    use std::os::unix::fs::FileTypeExt;
    if file_type.is_file() {
        None
    } else if file_type.is_dir() {
        Some("a directory")
    } else if file_type.is_fifo() {
        Some("a FIFO")
    } else if file_type.is_socket() {
        Some("a socket")
    } else if file_type.is_block_device() || file_type.is_char_device() {
        Some("a device")
    } else {
        Some("not a regular file")
    }
}

fn link_kind(kind: &'static str) -> &'static str {
    match kind {
        "a directory" => "a link to a directory",
        "a FIFO" => "a link to a FIFO",
        "a socket" => "a link to a socket",
        "a device" => "a link to a device",
        _ => "a link to something not a regular file",
    }
}

/// Checks that a file may be written at `path`: it does not exist, or is a regular file (or a link to one).
///
/// # Errors
/// [`Error::Output`] naming `path` and what it is.
pub fn check_target(path: &Path) -> Result<(), Error> {
    match refused_kind(path)? {
        None => Ok(()),
        Some(kind) => Err(Error::output(path, format!("is {kind}, not a regular file: refusing to replace it"))),
    }
}

/// The temporary file beside `target`: `.NAME.partial-PID` in its directory (the extension kept last for
/// writers that choose a format by it: `.NAME.partial-PID.EXT`).
fn temporary_path(target: &Path) -> PathBuf {
    let name = target.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let pid = std::process::id();
    let temp = match target.extension() {
        Some(ext) => format!(".{name}.partial-{pid}.{}", ext.to_string_lossy()),
        None => format!(".{name}.partial-{pid}"),
    };
    target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")).join(temp)
}

/// Renames the complete temporary file `temp` onto `target` (checked again first); `temp` is removed on
/// failure.
fn rename_onto(temp: &Path, target: &Path) -> Result<(), Error> {
    let renamed =
        check_target(target).and_then(|()| std::fs::rename(temp, target).map_err(|e| Error::output(target, e)));
    if renamed.is_err() {
        let _ = std::fs::remove_file(temp);
    }
    renamed
}

/// A file being written: buffered into its temporary file, renamed onto the target by
/// [`AtomicFile::commit`]; dropped without a commit, the temporary file is removed.
pub struct AtomicFile {
    writer: Option<BufWriter<File>>,
    temp: PathBuf,
    target: PathBuf,
}

impl AtomicFile {
    /// Starts writing `target` (checked first).
    ///
    /// # Errors
    /// [`Error::Output`]: a target that may not be replaced, or a temporary file that cannot be created.
    pub fn create(target: &Path) -> Result<Self, Error> {
        check_target(target)?;
        let temp = temporary_path(target);
        let _ = std::fs::remove_file(&temp);
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)
            .map_err(|e| Error::output(target, e))?;
        Ok(Self { writer: Some(BufWriter::new(file)), temp, target: target.to_path_buf() })
    }

    /// The target path.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Flushes the file and renames it onto the target.
    ///
    /// # Errors
    /// [`Error::Output`] naming the target; the temporary file is then removed.
    pub fn commit(mut self) -> Result<(), Error> {
        let Some(writer) = self.writer.take() else {
            return Err(Error::internal("atomic file committed twice"));
        };
        if let Err(e) = writer.into_inner().map_err(|e| e.into_error()) {
            let _ = std::fs::remove_file(&self.temp);
            return Err(Error::output(&self.target, e));
        }
        rename_onto(&self.temp, &self.target)
    }
}

impl Write for AtomicFile {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        match &mut self.writer {
            Some(writer) => writer.write(bytes),
            None => Err(std::io::Error::other("atomic file already committed")),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.writer.as_mut().map_or(Ok(()), Write::flush)
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.writer.take().is_some() {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Writes `bytes` to `path` ([`AtomicFile`]).
///
/// # Errors
/// [`Error::Output`] naming `path`.
pub fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), Error> {
    write_with(path, |w| w.write_all(bytes.as_ref()))
}

/// Writes to `path` what `fill` writes ([`AtomicFile`]); an error of `fill` leaves the target untouched.
///
/// # Errors
/// [`Error::Output`] naming `path`.
pub fn write_with(path: &Path, fill: impl FnOnce(&mut AtomicFile) -> std::io::Result<()>) -> Result<(), Error> {
    let mut file = AtomicFile::create(path)?;
    fill(&mut file).map_err(|e| Error::output(path, e))?;
    file.commit()
}

/// Writes `value` as JSON to `path` (pretty when `pretty`, then a line break), serialised straight into the
/// file.
///
/// # Errors
/// [`Error::Output`] naming `path`.
pub fn write_json(path: &Path, value: &impl serde::Serialize, pretty: bool) -> Result<(), Error> {
    write_with(path, |w| {
        if pretty { serde_json::to_writer_pretty(&mut *w, value) } else { serde_json::to_writer(&mut *w, value) }
            .map_err(std::io::Error::other)?;
        w.write_all(b"\n")
    })
}

/// Lets `render` write the file at a temporary path (with the target's extension), then renames it onto
/// `target`: for writers that take a path, such as the PNG backend of the plots.
///
/// # Errors
/// `render`'s error, or [`Error::Output`] naming `target`; the temporary file is removed either way.
pub fn write_via_path<E: From<Error>>(target: &Path, render: impl FnOnce(&Path) -> Result<(), E>) -> Result<(), E> {
    check_target(target)?;
    let temp = temporary_path(target);
    let _ = std::fs::remove_file(&temp);
    if let Err(e) = render(&temp) {
        let _ = std::fs::remove_file(&temp);
        return Err(e);
    }
    Ok(rename_onto(&temp, target)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("host-sim-atomic-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("read dir")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("partial"))
            .collect();
        names.sort();
        names
    }

    #[test]
    fn replaces_a_regular_file_and_writes_a_new_one() {
        let dir = scratch("regular");
        let old = dir.join("old.json");
        std::fs::write(&old, "old").expect("write");
        write(&old, "new").expect("replaced");
        assert_eq!(std::fs::read_to_string(&old).expect("read"), "new");
        write(&dir.join("new.json"), "fresh").expect("written");
        assert_eq!(std::fs::read_to_string(dir.join("new.json")).expect("read"), "fresh");
        assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn refuses_a_directory_and_a_link_to_one_leaving_them_untouched() {
        let dir = scratch("directory");
        let target = dir.join("out.json");
        std::fs::create_dir(&target).expect("mkdir");
        std::fs::write(target.join("inside"), "kept").expect("write");
        let error = write(&target, "x").expect_err("a directory is refused").to_string();
        assert!(error.contains("out.json") && error.contains("a directory"), "{error}");
        let link = dir.join("link.json");
        std::os::unix::fs::symlink(&target, &link).expect("symlink");
        let error = write(&link, "x").expect_err("a link to a directory is refused").to_string();
        assert!(error.contains("link.json") && error.contains("a link to a directory"), "{error}");
        assert_eq!(std::fs::read_to_string(target.join("inside")).expect("read"), "kept");
        assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_failed_fill_leaves_the_target_and_no_temporary_file() {
        let dir = scratch("failed");
        let target = dir.join("kept.csv");
        std::fs::write(&target, "before").expect("write");
        let result = write_with(&target, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(result.expect_err("fails").to_string().contains("disk full"));
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "before");
        let file = AtomicFile::create(&dir.join("dropped.csv")).expect("create");
        drop(file);
        assert!(!dir.join("dropped.csv").exists());
        assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_temporary_file_keeps_the_extension() {
        let temp = temporary_path(Path::new("plots/cardinality.png"));
        assert_eq!(temp.extension().and_then(|e| e.to_str()), Some("png"));
        assert_eq!(temp.parent(), Some(Path::new("plots")));
        assert!(temp.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with(".cardinality.png.partial-")));
    }
}
