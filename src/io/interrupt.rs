//! Nothing partial left behind when the process is interrupted.
//!
//! [`super::write_atomically`] writes into a temporary file and renames it
//! over the target only on success; an error removes the temporary file.
//! A signal that ends the process (SIGINT from Ctrl-C, SIGTERM, SIGHUP)
//! runs no destructor, so without more the temporary file would stay. The
//! files being written are listed here, and
//! [`remove_partial_files_on_signal`] installs a handler that removes them
//! and then ends the process as the signal would have.
//!
//! Invariant: `PARTIAL` is null or points to a list that is never changed
//! nor freed after it is published (a new list replaces it; the old one is
//! leaked: one small list per file written). So the handler reads it
//! without locking or allocating, which is all a signal handler may do.

use std::ffi::CString;
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicPtr, Ordering};

/// The temporary files being written, as published for the handler.
static PARTIAL: AtomicPtr<Vec<CString>> = AtomicPtr::new(std::ptr::null_mut());

/// Serializes the publishers (the handler only reads).
static EDIT: Mutex<()> = Mutex::new(());

/// Publishes the list with `change` applied.
fn publish(change: impl FnOnce(&mut Vec<CString>)) {
    let _edit = EDIT
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let current = PARTIAL.load(Ordering::Acquire);
    // SAFETY: a published list is never freed or changed (module invariant).
    let mut list = unsafe { current.as_ref() }.cloned().unwrap_or_default();
    change(&mut list);
    PARTIAL.store(Box::into_raw(Box::new(list)), Ordering::Release);
}

/// Lists `path` as a temporary file being written.
pub(super) fn begin(path: &Path) {
    if let Some(name) = c_path(path) {
        publish(|list| list.push(name));
    }
}

/// Takes `path` off the list (written and renamed, or removed).
pub(super) fn end(path: &Path) {
    if let Some(name) = c_path(path) {
        publish(|list| list.retain(|p| *p != name));
    }
}

fn c_path(path: &Path) -> Option<CString> {
    use std::os::unix::ffi::OsStrExt;
    CString::new(path.as_os_str().as_bytes()).ok()
}

/// Installs the handler of SIGINT, SIGTERM and SIGHUP that removes every
/// temporary file being written, then ends the process by the same signal
/// (its default action: the exit status says which signal). For programs
/// (the `wingedge` command line); a library caller with handlers of its
/// own keeps them by not calling this.
pub fn remove_partial_files_on_signal() {
    for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        // SAFETY: `on_signal` is async-signal-safe (see there).
        unsafe {
            libc::signal(
                signal,
                on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t,
            );
        }
    }
}

/// Unlinks the published temporary files, restores the default action and
/// raises the signal again. Only async-signal-safe calls (`unlink`,
/// `signal`, `raise`) and reads of a list that never changes.
extern "C" fn on_signal(signal: libc::c_int) {
    let current = PARTIAL.load(Ordering::Acquire);
    // SAFETY: a published list is never freed or changed (module invariant).
    if let Some(list) = unsafe { current.as_ref() } {
        for name in list {
            // SAFETY: `name` is a NUL-terminated path.
            unsafe { libc::unlink(name.as_ptr()) };
        }
    }
    // SAFETY: restoring the default action and raising are
    // async-signal-safe.
    unsafe {
        libc::signal(signal, libc::SIG_DFL);
        libc::raise(signal);
    }
}
