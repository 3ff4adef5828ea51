//! Writing an output file so that nothing is lost: the content goes to a
//! temporary file in the target's folder, which is flushed, synced and
//! renamed over the target only when every byte was written. A failure at
//! any point (a full disk, an encoder's error) removes the temporary file
//! and leaves the target as it was; a reader never sees a half-written
//! file, because the rename is atomic on one file system.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Writes `path` atomically: `fill` writes the content into a buffered
/// temporary file in `path`'s folder, which replaces `path` only when
/// `fill` and the flush and sync that follow succeed. The new file gets the
/// permissions a freshly created file would get (`0666` less the umask).
///
/// # Errors
///
/// Creating, writing, syncing or renaming the temporary file, or `fill`'s
/// own error; in every case `path` is untouched and the temporary file is
/// removed.
pub fn write_atomically<T>(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<&File>) -> io::Result<T>,
) -> io::Result<T> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy());
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".partial");
    // The name is listed for the signal handler before the file exists, so
    // a signal at any moment finds every temporary file there is.
    let temporary = builder.make_in(folder, |candidate| {
        #[cfg(target_os = "linux")]
        super::interrupt::begin(candidate);
        let created = create_new(candidate);
        #[cfg(target_os = "linux")]
        if created.is_err() {
            super::interrupt::end(candidate);
        }
        created
    })?;
    #[cfg(target_os = "linux")]
    let partial = temporary.path().to_path_buf();
    let written = (|| {
        let answer = {
            let mut writer = BufWriter::new(temporary.as_file());
            let answer = fill(&mut writer)?;
            writer.flush()?;
            answer
        };
        temporary.as_file().sync_all()?;
        temporary.persist(path).map_err(|e| e.error)?;
        Ok(answer)
    })();
    #[cfg(target_os = "linux")]
    super::interrupt::end(&partial);
    written
}

/// Creates `path`, failing if it exists, with the permissions a freshly
/// created file gets (`0666` less the umask).
fn create_new(path: &Path) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true).write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.mode(0o666);
    }
    options.open(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("wingedge-atomic-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect()
    }

    /// A write that fails half way leaves the old file whole and no
    /// temporary file behind; one that succeeds replaces it.
    #[test]
    fn a_failed_write_leaves_the_old_file() {
        let dir = scratch("fail");
        let path = dir.join("out.obj");
        std::fs::write(&path, "old content\n").unwrap();
        let failed = write_atomically(&path, |w| {
            w.write_all(b"half of the new ")?;
            Err::<(), _>(io::Error::other("disk full"))
        });
        assert_eq!(failed.unwrap_err().to_string(), "disk full");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old content\n");
        assert_eq!(leftovers(&dir), ["out.obj"]);
        write_atomically(&path, |w| w.write_all(b"new content\n")).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new content\n");
        assert_eq!(leftovers(&dir), ["out.obj"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A target in a folder that does not exist is an error, not a panic.
    #[test]
    fn a_missing_folder_is_an_error() {
        let dir = scratch("missing");
        let path = dir.join("no").join("such").join("out.obj");
        assert!(write_atomically(&path, |w| w.write_all(b"x")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
