//! The boolean stress run: near-degenerate booleans by the hundred thousand
//! (`tests/common/boolean_cases.rs`: slits along faces, copies turned by
//! 1e-15 … 1e-9 rad, prisms on a box's faces, faces ulps apart, all of them
//! also far from the origin), each of the four operators. Every boolean of
//! valid operands must succeed, its written file must validate, and the
//! volumes must add up; the run prints the count, what the output stage had
//! to do, and every failure.
//!
//! `cargo run --release -p wingedge-bench --bin boolean_stress -- [CASES] [FIRST_SEED]`
//! (default 25,000 cases of four booleans: 100,000 booleans).

#[path = "../../../../tests/common/boolean_cases.rs"]
mod boolean_cases;

use std::sync::Mutex;
use std::time::Instant;

use boolean_cases::{Checked, FAMILIES, case, check};
use rayon::prelude::*;

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(25_000);
    let first: u64 = args
        .next()
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let start = Instant::now();
    let failures = Mutex::new(Vec::new());
    let per_family: Vec<(usize, usize, usize)> = (0..FAMILIES.len())
        .map(|family| {
            let count = cases / FAMILIES.len() as u64;
            let results: Vec<Result<Checked, String>> = (first..first + count)
                .into_par_iter()
                .map(|seed| check(&case(family, seed)).map_err(|e| format!("seed {seed}: {e}")))
                .collect();
            let (mut booleans, mut skipped, mut failed) = (0, 0, 0);
            for r in results {
                match r {
                    Ok(Checked::Passed(n)) => booleans += n,
                    Ok(Checked::InvalidOperand(_)) => skipped += 1,
                    Err(e) => {
                        failed += 1;
                        failures
                            .lock()
                            .map(|mut f| f.push(format!("{}: {e}", FAMILIES[family])))
                            .ok();
                    }
                }
            }
            (booleans, skipped, failed)
        })
        .collect();
    println!("| family | booleans | cases skipped (an operand not valid) | cases failed |");
    println!("|---|---:|---:|---:|");
    for (family, (booleans, skipped, failed)) in FAMILIES.iter().zip(&per_family) {
        println!("| {family} | {booleans} | {skipped} | {failed} |");
    }
    let total: usize = per_family.iter().map(|r| r.0).sum();
    let failed: usize = per_family.iter().map(|r| r.2).sum();
    println!(
        "\n{total} booleans in {:.1} s; {failed} cases failed",
        start.elapsed().as_secs_f64()
    );
    for f in failures.into_inner().unwrap_or_default() {
        println!("{f}");
    }
    if failed > 0 {
        std::process::exit(1);
    }
}
