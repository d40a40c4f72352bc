//! `windfield schema`: the scene format's JSON Schema (draft 2020-12) on stdout
//! (`public/scene.schema.json`).

use super::failure::{print_out, Failure};

pub fn run() -> Result<(), Failure> {
    print_out(&windfield::scene::scene_format::json_schema())
}
