//! How `wingedge csg` scales with the number of leaves: a union of `n`
//! disjoint unit boxes on a grid with gaps (each box meets none of the
//! others), `n` from 1,000 to 300,000, printed as a table of wall time,
//! peak memory and the stages the command reports, with the slope of
//! log time against log n between rows and over the whole table. The
//! answer is `n` separate boxes, so a cost that follows the answer grows
//! as `n` (slope 1), as `n log n` at worst.
//!
//! ```text
//! cargo build --release -p wingedge --bin wingedge -p wingedge-bench --bin csg_scaling
//! target/release/csg_scaling [N ...] [--limit SECONDS]
//! ```
//!
//! Each `n` runs `wingedge csg SCENE -o OUT` (the binary next to this
//! one) in a child process; its peak resident memory is the child's
//! (`getrusage`). After a run longer than `--limit` (default 120 s) the
//! larger `n` are skipped, so an algorithm that grows as `n³` cannot stall
//! the table. Scenes and results are written to a scratch folder and
//! removed.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

const DEFAULT_N: [usize; 6] = [1_000, 3_000, 10_000, 30_000, 100_000, 300_000];

/// The scene: a union of `n` unit boxes at even coordinates of a cube grid
/// (gaps of one unit between them).
fn scene(n: usize) -> String {
    let side = (1..).find(|s: &usize| s * s * s >= n).unwrap_or(1);
    let mut text = String::from("{\"root\": {\"union\": [\n");
    for i in 0..n {
        let (x, y, z) = (
            2 * (i % side),
            2 * (i / side % side),
            2 * (i / (side * side)),
        );
        let comma = if i + 1 < n { "," } else { "" };
        writeln!(
            text,
            "{{\"box\": {{\"min\": [{x}, {y}, {z}], \"max\": [{}, {}, {}]}}}}{comma}",
            x + 1,
            y + 1,
            z + 1
        )
        .unwrap();
    }
    text.push_str("]}}\n");
    text
}

/// One run: wall seconds, the child's peak memory in MiB, its exit code
/// and its report of the stages (the line with "tessellate").
struct Run {
    seconds: f64,
    peak_mib: f64,
    code: i32,
    stages: String,
}

/// Runs `wingedge csg scene -o out`, measuring the child alone; its
/// output goes to `log`.
fn run(wingedge: &Path, scene: &Path, out: &Path, log: &Path) -> Result<Run> {
    let clock = Instant::now();
    let file = std::fs::File::create(log)?;
    let child = Command::new(wingedge)
        .arg("csg")
        .arg(scene)
        .arg("-o")
        .arg(out)
        .stdout(file.try_clone()?)
        .stderr(file)
        .spawn()?;
    let pid = child.id() as libc::pid_t;
    // Reaped with wait4 for the child's own resource usage.
    let mut status = 0;
    // SAFETY: rusage is plain data, written by wait4.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waits for our own child, writing into the two locals.
    let reaped = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    let seconds = clock.elapsed().as_secs_f64();
    if reaped != pid {
        return Err(format!("wait4 failed for {}", scene.display()).into());
    }
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let stages = text
        .lines()
        .find(|l| l.contains("tessellate"))
        .unwrap_or("")
        .trim()
        .to_string();
    let code = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else {
        -1
    };
    Ok(Run {
        seconds,
        peak_mib: usage.ru_maxrss as f64 / 1024.0,
        code,
        stages,
    })
}

fn main() -> Result<()> {
    let mut sizes = Vec::new();
    let mut limit = 120.0;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--limit" {
            limit = args.next().ok_or("--limit needs seconds")?.parse()?;
        } else {
            sizes.push(a.replace(['_', ','], "").parse::<usize>()?);
        }
    }
    if sizes.is_empty() {
        sizes = DEFAULT_N.to_vec();
    }
    let me = std::env::current_exe()?;
    let wingedge: PathBuf = me.with_file_name("wingedge");
    if !wingedge.exists() {
        return Err(format!(
            "{} not found: cargo build --release --bin wingedge first",
            wingedge.display()
        )
        .into());
    }
    let scratch = std::env::temp_dir().join(format!("csg_scaling-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)?;
    println!(
        "| boxes n | time (s) | slope since previous | peak memory (MiB) | exit | stages (s) |"
    );
    println!("|---:|---:|---:|---:|---:|---|");
    let mut rows: Vec<(usize, f64)> = Vec::new();
    for &n in &sizes {
        let path = scratch.join(format!("boxes_{n}.json"));
        std::fs::write(&path, scene(n))?;
        let out = scratch.join("out.obj");
        let r = run(&wingedge, &path, &out, &scratch.join("log.txt"))?;
        let _ = std::fs::remove_file(&path);
        let _ = std::fs::remove_file(&out);
        let slope = rows.last().map_or("".to_string(), |&(m, t)| {
            format!("{:.2}", (r.seconds / t).ln() / (n as f64 / m as f64).ln())
        });
        // The stage line without its leading total.
        let stages = r.stages.split_once(": ").map_or("", |(_, s)| s);
        println!(
            "| {n} | {:.2} | {slope} | {:.0} | {} | {stages} |",
            r.seconds, r.peak_mib, r.code
        );
        rows.push((n, r.seconds));
        if r.seconds > limit {
            println!("(larger n skipped: this run took more than {limit} s)");
            break;
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    if rows.len() >= 2 {
        // Least squares of log t against log n.
        let k = rows.len() as f64;
        let xs: Vec<f64> = rows.iter().map(|&(n, _)| (n as f64).ln()).collect();
        let ys: Vec<f64> = rows.iter().map(|&(_, t)| t.max(1e-6).ln()).collect();
        let (mx, my) = (xs.iter().sum::<f64>() / k, ys.iter().sum::<f64>() / k);
        let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
        println!(
            "\nslope of log time against log n over the table: {:.2}",
            sxy / sxx
        );
    }
    Ok(())
}
