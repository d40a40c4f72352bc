//! The numbers of the one line a command that writes ends with on stderr: counts with their
//! thousands grouped, and the wall time.

use std::time::Instant;

/// `n` with its thousands grouped: 41,203.
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Wall time since `start`, for the summary lines: "2.4 s".
pub fn wall(start: Instant) -> String {
    format!("{:.1} s", start.elapsed().as_secs_f64())
}
