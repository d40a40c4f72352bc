//! The coarse-grid flow's step (`wind::flow`) as a WebAssembly module of raw exports for
//! `npm run bench` (scripts/bench.mjs times [`flow_step`] from Node): the case of
//! `examples/bench.rs`'s flow rows, an open 1.6 m box of `n`³ cells round one solid sphere in
//! a 1 m/s wind, steps of 0.02 s. Built by `cargo build --profile wasm --target
//! wasm32-unknown-unknown --no-default-features --example flow-wasm`; natively it builds and
//! does the same.

use std::cell::RefCell;
use windfield::wind::flow::{Faces, Flow, Grid, MacField};

thread_local! {
    /// The flow and its wind u_p.
    static CASE: RefCell<Option<(Flow, MacField)>> = const { RefCell::new(None) };
}

/// Sets up the case on `n`³ cells, at rest.
#[no_mangle]
pub extern "C" fn flow_new(n: u32) {
    let n = n as usize;
    let h = 1.6 / n as f32;
    let grid = Grid::new([0.0; 3], [n; 3], h);
    let mut flow = Flow::new(grid.clone(), Faces::OPEN);
    flow.solids.add_sphere(&grid, [0.8; 3], 0.3, [0.0; 3]);
    let u_p = MacField::from_fn(&grid, |_| [1.0, 0.0, 0.0]);
    CASE.with(|c| *c.borrow_mut() = Some((flow, u_p)));
}

/// One step of 0.02 s of the case; returns its CG iterations (0 before [`flow_new`]).
#[no_mangle]
pub extern "C" fn flow_step() -> u32 {
    CASE.with(|c| match c.borrow_mut().as_mut() {
        Some((flow, u_p)) => flow.step(0.02, u_p, None, &[]).iterations as u32,
        None => 0,
    })
}
