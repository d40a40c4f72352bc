//! `windfield schema`: the scene format's JSON Schema (draft 2020-12) on stdout
//! (`public/scene.schema.json`).

use super::failure::Failure;

pub fn run() -> Result<(), Failure> {
    print!("{}", windfield::scene::scene_format::json_schema());
    Ok(())
}
