//! Why a command stopped: bad input (exit status 2) or a failed read or write (exit status 1).
//! Every refusal names the flag or the file and JSON path it is about.

use windfield::ParamError;

/// A failure: bad input (exit 2) or a failed read or write (exit 1).
pub enum Failure {
    Input(String),
    Io(String),
}

/// The flag a parameter's path names: `spectrum.k_inertial` is `--k-inertial`.
pub fn flag_for(path: &str) -> String {
    let name = path
        .split('[')
        .next()
        .unwrap_or(path)
        .rsplit('.')
        .next()
        .unwrap_or(path);
    format!("--{}", name.replace('_', "-"))
}

/// A parameter's refusal, named by its flag.
pub fn input_error(e: ParamError) -> Failure {
    Failure::Input(format!("{}: {}", flag_for(&e.path), e.message))
}

/// Writes `text` to stdout. A reader that closed the pipe early (`windfield schema | head`)
/// ends the output quietly, as other tools do; any other failure to write is an I/O failure.
pub fn print_out(text: &str) -> Result<(), Failure> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(Failure::Io(format!("stdout: {e}")))
        }
        _ => Ok(()),
    }
}
