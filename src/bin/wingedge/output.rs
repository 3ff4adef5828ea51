//! Standard output of the commands, and how every command ends: exit 0
//! when it answered, 1 when `validate` found defects, 2 with `error:
//! MESSAGE` on standard error when the input cannot be read or used.

use std::fmt::Display;
use std::io::{BufWriter, ErrorKind, StdoutLock, Write};
use std::process::ExitCode;

/// What a command returns: its exit code, or the message of a failure
/// (printed by [`exit`] with exit code 2).
pub type Outcome = Result<ExitCode, String>;

/// The process's exit for a command's outcome.
pub fn exit(outcome: Outcome) -> ExitCode {
    outcome.unwrap_or_else(|message| {
        eprintln!("error: {message}");
        ExitCode::from(2)
    })
}

/// Buffered standard output. A reader that went away (`| head -1`) ends
/// the output quietly: the command still succeeds, it only stops writing
/// (a `BufWriter` dropped with a buffer it cannot flush drops it silently).
pub struct Out {
    writer: BufWriter<StdoutLock<'static>>,
    open: bool,
}

impl Out {
    /// Standard output, locked for this command.
    pub fn new() -> Out {
        Out {
            writer: BufWriter::new(std::io::stdout().lock()),
            open: true,
        }
    }

    /// Writes `text`; returns whether a reader is still there (`false`
    /// once it went away: stop producing output).
    pub fn write(&mut self, text: impl Display) -> Result<bool, String> {
        if self.open {
            let written = write!(self.writer, "{text}");
            self.settle(written)?;
        }
        Ok(self.open)
    }

    /// Flushes what is buffered.
    pub fn finish(mut self) -> Result<(), String> {
        if self.open {
            let flushed = self.writer.flush();
            self.settle(flushed)?;
        }
        Ok(())
    }

    fn settle(&mut self, result: std::io::Result<()>) -> Result<(), String> {
        match result {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == ErrorKind::BrokenPipe => {
                self.open = false;
                Ok(())
            }
            Err(e) => Err(format!("standard output: cannot write: {e}")),
        }
    }
}

/// A rounded measure (volume, area, a coordinate) as a report shows it:
/// `decimals` places for ordinary magnitudes, scientific notation for
/// extreme ones (never hundreds of digits), and `overflow` when it does not
/// fit in `f64` (never a bare `NaN`).
pub fn measure(x: f64, decimals: usize) -> String {
    // −0 (the volume of the empty solid, summed from nothing) is 0.
    let x = x + 0.0;
    if !x.is_finite() {
        "overflow".to_string()
    } else if x == 0.0 || (1e-5..1e16).contains(&x.abs()) {
        format!("{x:.decimals$}")
    } else {
        wingedge::geom::Readable(x).to_string()
    }
}
