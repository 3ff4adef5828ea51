//! Running the `wingedge` binary from tests (compiled with the `cli`
//! feature only, which builds the binary).

use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How long a command may run before the test calls it hung. Not a speed
/// assertion: a healthy command finishes in a small fraction of it, even
/// in a debug build on a loaded machine.
const HUNG_AFTER: Duration = Duration::from_secs(300);

/// What a finished command left behind.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The exit code (-1 when killed by a signal).
    pub code: i32,
    /// Standard output, as bytes.
    pub stdout: Vec<u8>,
    /// Standard error, as text.
    pub stderr: String,
    /// The command's own peak resident memory in bytes: the last `VmHWM`
    /// read from the running command, or `wait4`'s resource usage of this
    /// one child when that is smaller or nothing was read (`None` where
    /// there is neither).
    pub peak_rss: Option<u64>,
}

impl Outcome {
    /// Standard output as text.
    pub fn out(&self) -> String {
        String::from_utf8_lossy(&self.stdout).into_owned()
    }
}

/// Runs `wingedge ARGS` in the crate root with empty standard input;
/// returns the exit code, standard output and standard error.
pub fn wingedge(args: &[&str]) -> (i32, String, String) {
    let o = run(args, "", &[]);
    let out = o.out();
    (o.code, out, o.stderr)
}

/// Runs `wingedge ARGS` in the crate root with `stdin` as standard input.
pub fn wingedge_stdin(args: &[&str], stdin: &str) -> (i32, String, String) {
    let o = run(args, stdin, &[]);
    let out = o.out();
    (o.code, out, o.stderr)
}

/// Runs `wingedge ARGS` in the crate root with `stdin` as standard input
/// and `env` added to the environment. Panics if it runs longer than
/// [`HUNG_AFTER`] (after killing it).
pub fn run(args: &[&str], stdin: &str, env: &[(&str, &str)]) -> Outcome {
    let mut child = Command::new(env!("CARGO_BIN_EXE_wingedge"))
        .args(args)
        .envs(env.iter().copied())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let mut input = child.stdin.take().expect("stdin is piped");
    let stdin = stdin.as_bytes().to_vec();
    // Feed and drain on threads so that no pipe fills up and blocks.
    let feeder = std::thread::spawn(move || {
        // A command that exits without reading its input closes the pipe.
        let _ = input.write_all(&stdin);
    });
    let mut stdout_pipe = child.stdout.take().expect("stdout is piped");
    let mut stderr_pipe = child.stderr.take().expect("stderr is piped");
    let stdout = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        stdout_pipe
            .read_to_end(&mut bytes)
            .expect("stdout is readable");
        bytes
    });
    let stderr = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        stderr_pipe
            .read_to_end(&mut bytes)
            .expect("stderr is readable");
        bytes
    });
    let (code, peak_rss) = wait_or_kill(&mut child, args);
    feeder.join().expect("stdin feeder");
    Outcome {
        code,
        peak_rss,
        stdout: stdout.join().expect("stdout reader"),
        stderr: String::from_utf8_lossy(&stderr.join().expect("stderr reader")).into_owned(),
    }
}

/// Waits for `child` (running `wingedge ARGS`); kills it and panics if it
/// runs longer than [`HUNG_AFTER`]. Returns its exit code (-1 when killed
/// by a signal) and, on Linux, its own peak resident memory in bytes.
fn wait_or_kill(child: &mut std::process::Child, args: &[&str]) -> (i32, Option<u64>) {
    let started = Instant::now();
    let mut high_water = None;
    loop {
        if let Some((code, peak)) = reaped(child) {
            // `wait4`'s figure also holds what the child shared with this
            // process before it started wingedge (a child spawned with
            // `CLONE_VM` inherits this process's high-water mark at `exec`,
            // and this test process may be large): the last high-water
            // mark read from wingedge itself is its own.
            let peak = match (peak, high_water) {
                (Some(p), Some(h)) => Some(p.min(h)),
                (p, h) => p.or(h),
            };
            return (code, peak);
        }
        if let Some(h) = own_high_water(child) {
            high_water = Some(h);
        }
        if started.elapsed() > HUNG_AFTER {
            let _ = child.kill();
            let _ = child.wait();
            panic!("wingedge {args:?} still running after {HUNG_AFTER:?}: killed");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// `child`'s exit code and peak resident memory if it has ended (reaped
/// by `wait4`, which reports that one child's resource usage).
#[cfg(target_os = "linux")]
fn reaped(child: &mut std::process::Child) -> Option<(i32, Option<u64>)> {
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: rusage is plain data, written by wait4.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: polls our own child, writing into the two locals.
    let r = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
    if r == 0 {
        return None;
    }
    assert_eq!(r, pid, "wait4 of wingedge");
    let code = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else {
        -1
    };
    // Linux reports kilobytes.
    let peak = u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024;
    Some((code, Some(peak)))
}

/// The high-water mark of resident memory of `child` in bytes once it
/// runs wingedge (`VmHWM` of `/proc/PID/status`, which starts afresh at
/// `exec`); `None` before that, after it ended, or off Linux.
fn own_high_water(child: &std::process::Child) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{}/status", child.id())).ok()?;
    let mut lines = status.lines();
    if lines.next()? != "Name:\twingedge" {
        return None;
    }
    let kb = lines.find_map(|l| l.strip_prefix("VmHWM:"))?;
    let kb: u64 = kb.trim().trim_end_matches("kB").trim().parse().ok()?;
    Some(kb * 1024)
}

/// `child`'s exit code if it has ended (no resource usage here).
#[cfg(not(target_os = "linux"))]
fn reaped(child: &mut std::process::Child) -> Option<(i32, Option<u64>)> {
    let status = child.try_wait().expect("the child can be waited for")?;
    Some((status.code().unwrap_or(-1), None))
}

/// Runs `wingedge ARGS` in the crate root, reads its standard output up to
/// the end of the first line, then closes it, as `wingedge ARGS | head -1`
/// does. Returns the exit code, the first line and standard error.
pub fn run_first_line_only(args: &[&str]) -> Outcome {
    use std::io::BufRead;
    let mut child = Command::new(env!("CARGO_BIN_EXE_wingedge"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let mut stderr_pipe = child.stderr.take().expect("stderr is piped");
    let stderr = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        stderr_pipe
            .read_to_end(&mut bytes)
            .expect("stderr is readable");
        bytes
    });
    let mut first = Vec::new();
    {
        let mut reader = std::io::BufReader::new(child.stdout.take().expect("stdout is piped"));
        reader
            .read_until(b'\n', &mut first)
            .expect("stdout is readable");
        // Dropping the reader closes the pipe.
    }
    let (code, peak_rss) = wait_or_kill(&mut child, args);
    Outcome {
        code,
        peak_rss,
        stdout: first,
        stderr: String::from_utf8_lossy(&stderr.join().expect("stderr reader")).into_owned(),
    }
}
