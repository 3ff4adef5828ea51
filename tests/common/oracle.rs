//! The manifold3d oracle: the python3 scripts of `tests/oracle/`, run as
//! child processes. The oracle is required: when python3 or manifold3d is
//! missing, or a script fails, the test fails and says how to install it.

use std::ffi::OsStr;
use std::path::Path;
use std::process::Command;

/// How to install the oracle, for the failure messages.
const INSTALL: &str = "python3 -m pip install -r tests/oracle/requirements.txt";

/// Runs `python3 tests/oracle/SCRIPT ARGS…` and returns its standard
/// output.
///
/// # Panics
///
/// If python3 cannot be started, or the script exits with failure (the
/// message holds its exit code, its standard error and [`INSTALL`]).
pub fn run<I, S>(script: &str, args: I) -> Vec<u8>
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/oracle")
        .join(script);
    let run = Command::new("python3")
        .arg(&path)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 for the manifold3d oracle ({script}): {e}; install it with: {INSTALL}"));
    assert!(
        run.status.success(),
        "the manifold3d oracle ({script}) failed (exit {:?}):\n{}\ninstall it with: {INSTALL}",
        run.status.code(),
        String::from_utf8_lossy(&run.stderr)
    );
    run.stdout
}
