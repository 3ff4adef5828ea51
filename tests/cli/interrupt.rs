//! An interrupted command loses nothing: the old output stays and no
//! partial file remains (SIGINT while `cells --npy` writes 134 MB).

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::temp_dir::TempDir;

/// The temporary files of an atomic write in `dir` (`.NAME.XXXX.partial`).
fn partial_files(dir: &std::path::Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .expect("the folder")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".partial"))
        .collect()
}

/// SIGINT while the array is being written (seen as its temporary file
/// appearing): the process ends by the signal, the old file is intact and
/// the temporary file is gone (before, it stayed behind; and before the
/// atomic writes, the target was truncated in place).
#[test]
fn sigint_while_writing_leaves_the_old_file_and_nothing_partial() {
    use std::os::unix::process::ExitStatusExt;
    let dir = TempDir::new("interrupt");
    let target = dir.write("cells.npy", "old content\n");
    let mut child = Command::new(env!("CARGO_BIN_EXE_wingedge"))
        .args(["cells", "fixtures/valid/cube.obj", "--depth", "9", "--npy"])
        .arg(&target)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("wingedge runs");
    let start = Instant::now();
    while partial_files(dir.path()).is_empty() {
        assert!(
            child.try_wait().expect("the child").is_none(),
            "the command ended before its temporary file was seen"
        );
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "no temporary file"
        );
        std::thread::sleep(Duration::from_micros(200));
    }
    let pid = libc::pid_t::try_from(child.id()).expect("a pid");
    // SAFETY: sending a signal to our own child.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGINT) }, 0);
    let status = child.wait().expect("the child ends");
    assert_eq!(status.signal(), Some(libc::SIGINT), "{status:?}");
    assert_eq!(
        std::fs::read_to_string(&target).expect("the old file"),
        "old content\n"
    );
    assert_eq!(partial_files(dir.path()), Vec::<String>::new());
}
