//! Standard output that never panics. `println!` panics when stdout is a pipe its reader
//! has closed (`prism color blackbody:6500 | head -1`); `outln!` drops what the reader no
//! longer wants and lets the command finish (a render still writes its files), and names
//! any other failure to write once on stderr rather than losing it silently.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// Writes one line to stdout, as `println!` does.
macro_rules! outln {
    () => {
        $crate::stdout::line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::stdout::line(format_args!($($arg)*))
    };
}

/// Whether a write to stdout failed other than at a closed pipe.
static FAILED: AtomicBool = AtomicBool::new(false);

/// Writes `args` and a newline to stdout: a closed pipe is ignored, any other error is
/// reported once.
pub fn line(args: std::fmt::Arguments) {
    let mut out = std::io::stdout().lock();
    if let Err(error) = out.write_fmt(args).and_then(|()| out.write_all(b"\n"))
        && error.kind() != std::io::ErrorKind::BrokenPipe
        && !FAILED.swap(true, Ordering::Relaxed)
    {
        eprintln!("prism: error: cannot write to standard output: {error}");
    }
}

/// Whether some output was lost to an error other than a closed pipe.
pub fn failed() -> bool {
    FAILED.load(Ordering::Relaxed)
}
