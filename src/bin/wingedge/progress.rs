//! A progress bar on standard error, shown only when it is a terminal.

use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicU32, Ordering};

/// Draws `label [#####.....] 50%` on standard error as the fraction grows.
pub struct Progress {
    label: &'static str,
    enabled: bool,
    shown: AtomicU32,
}

impl Progress {
    /// A bar that draws only when standard error is a terminal.
    pub fn new(label: &'static str) -> Progress {
        Progress {
            label,
            enabled: std::io::stderr().is_terminal(),
            shown: AtomicU32::new(0),
        }
    }

    /// Reports that `fraction` of the work is done (from any thread).
    pub fn update(&self, fraction: f64) {
        if !self.enabled {
            return;
        }
        let percent = (fraction.clamp(0.0, 1.0) * 100.0) as u32;
        if self.shown.fetch_max(percent, Ordering::Relaxed) >= percent {
            return;
        }
        let filled = (percent / 5) as usize;
        let mut err = std::io::stderr().lock();
        let _ = write!(
            err,
            "\r{} [{}{}] {percent:3}%",
            self.label,
            "#".repeat(filled),
            ".".repeat(20 - filled)
        );
        let _ = err.flush();
    }

    /// Ends the bar's line.
    pub fn finish(&self) {
        if self.enabled {
            eprintln!();
        }
    }
}
