//! Native benchmarks; one JSON object per line: `{"name": ..., "value": ..., "unit": ...}`.
//! Run through `npm run bench` (which adds the WASM figures) or
//! `cargo run --release --example bench`.

use std::time::Instant;
use windfield::field::{FieldParams, TurbulentField};

/// Median wall time in milliseconds of `runs` calls after one warm-up call.
fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

fn emit(name: &str, value: f64, unit: &str) {
    println!(
        "{}",
        serde_json::json!({ "name": name, "value": (value * 1000.0).round() / 1000.0, "unit": unit })
    );
}

/// Peak resident set size of this process in MiB (Linux), if known.
fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn main() {
    let params = FieldParams::default();
    let ms = median_ms(7, || {
        std::hint::black_box(TurbulentField::generate(&params).expect("valid"));
    });
    emit("field_generate_32x32x32x32_native_ms", ms, "ms");
    if let Some(mib) = peak_rss_mib() {
        emit("native_peak_rss_mib", mib, "MiB");
    }
}
