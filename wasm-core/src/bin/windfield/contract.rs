//! `windfield contract`: the JavaScript module of the constants the core shares with the
//! page's code on stdout (`web/src/generated/contract.js`).

use super::failure::{print_out, Failure};

pub fn run() -> Result<(), Failure> {
    print_out(&windfield::contract::javascript())
}
