//! The terminal: what a command says on stderr, and what it prints on stdout.
//!
//! `println!` and `eprintln!` panic when their stream is closed or full (`evhi
//! scenarios | head -1`, `2>/dev/full`). Here a diagnostic that cannot be written is
//! dropped, since the run's files matter more than its commentary ([`crate::diag!`],
//! [`crate::diag_text!`]), and a command's product that cannot be written is an error the
//! caller can tell apart ([`emit`]): a reader that went away ([`is_closed_pipe`]) ends
//! the command quietly, as other command-line tools do, and a full disk is reported.

use std::io::Write;

/// `eprintln!` for diagnostics: a failed write (stderr closed or full) is dropped,
/// never a panic.
#[macro_export]
macro_rules! diag {
    ($($arg:tt)*) => {{
        use ::std::io::Write as _;
        let _ = ::std::writeln!(::std::io::stderr(), $($arg)*);
    }};
}

/// `eprint!` for diagnostics (no line end added), dropping a failed write.
#[macro_export]
macro_rules! diag_text {
    ($($arg:tt)*) => {{
        use ::std::io::Write as _;
        let _ = ::std::write!(::std::io::stderr(), $($arg)*);
    }};
}

/// Writes a command's product to stdout and flushes it; the error says why it could
/// not (see [`is_closed_pipe`]).
pub fn emit(text: &str) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()
}

/// Whether `e` (or an I/O error inside it) means that the reader of stdout went away:
/// the command then ends quietly and successfully, as `cat` or `ls` piped into `head`.
pub fn is_closed_pipe(e: &(dyn std::error::Error + 'static)) -> bool {
    let mut cause = Some(e);
    while let Some(c) = cause {
        if let Some(io) = c.downcast_ref::<std::io::Error>() {
            return io.kind() == std::io::ErrorKind::BrokenPipe;
        }
        cause = c.source();
    }
    false
}

/// A size in bytes in the decimal unit that shows it with three significant digits
/// or more: `17.3 MB`, `1.30 MB`, `512 kB`, `40 B`.
pub fn size_text(bytes: f64) -> String {
    let (value, unit) = [(1e12, "TB"), (1e9, "GB"), (1e6, "MB"), (1e3, "kB")]
        .into_iter()
        .find(|&(scale, _)| bytes >= scale)
        .map_or((bytes, "B"), |(scale, unit)| (bytes / scale, unit));
    if unit == "B" {
        format!("{value:.0} B")
    } else if value >= 100.0 {
        format!("{value:.0} {unit}")
    } else if value >= 10.0 {
        format!("{value:.1} {unit}")
    } else {
        format!("{value:.2} {unit}")
    }
}

/// `text` for one line of a terminal: each control character (a CR or LF in a path
/// the user typed, an escape sequence) written as its Rust escape (`\r`, `\u{1b}`),
/// everything else as it is.
pub fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn control_characters_are_escaped_and_the_rest_kept() {
        assert_eq!(
            super::one_line("runs/a\r\nb\u{1b}[2J é"),
            "runs/a\\r\\nb\\u{1b}[2J é"
        );
    }
}
