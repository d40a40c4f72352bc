//! One home for the contract between the core and the page: every number that the core and the
//! browser's code (the GPU views' shaders, the engine worker, the page's forms) must agree on.
//! Each is defined once, in the core module whose physics or format it belongs to; this module
//! lists them and writes them as a JavaScript module, `web/src/generated/contract.js`
//! (`windfield contract`), which the page imports instead of writing its own copies.
//! `tests/contract.rs` fails while the shipped file differs from what the core writes now.

use crate::export::flipbook::MAX_SHEET_SIDE;
use crate::export::volume::MAX_VOXEL;
use crate::field::lattice::{DEFAULT_EXTENT, MAX_EXTENT, MAX_POINTS, MIN_EXTENT};
use crate::field::spectrum::{DEFAULT_EPSILON, DEFAULT_K_INERTIAL, DEFAULT_SIGMA};
use crate::field::turbulent_field::DEFAULT_SEED;
use crate::frame::gpu_steps::BLOB_FLOATS;
use crate::frame::light_volume::{NEAR_COLUMN_STEPS, NEAR_COLUMN_VOXELS, VIEW_LIGHTS};
use crate::frame::packed::{
    BLOBS_PER_ROW, CLASS_BIAS, FOOTPRINT, INFO_HEADER, INFO_PER_CLASS, SUBCLASS_BITS,
    WORDS_PER_BLOB,
};
use crate::frame::shadow_grid::SHADOW_GRID_HEADER;
use crate::frame::views::SPHERE_FLOATS;
use crate::frame::volume::{BLUR_NARROW, BLUR_REACH, DIRECT_LIMIT, MAX_BLUR_RADIUS};
use crate::gas::simulation::MAX_STIR_RADIUS;
use crate::render::{STEP_FRACTION, TRUNCATION};
use crate::scene::blob_list::DEFAULT_RENDER_TIME;
use crate::scene::limits::{
    MAX_ALBEDO, MAX_COORD, MAX_EMITTERS, MAX_FPS, MAX_IMAGE_SIDE, MAX_SECONDS, MAX_STEPS,
};
use crate::wind::solid_grid::SOLID_GRID_HEADER;
use crate::wind::wall_set::EDGE_STEPS;
use crate::wind::walls::{
    CYLINDER_ZONE_INNER, CYLINDER_ZONE_OUTER, SPHERE_ZONE_INNER, SPHERE_ZONE_OUTER,
};
use crate::wind::wind_table::{CYLINDER_SOLID_KIND, PLANE_SOLID_KIND, SPHERE_SOLID_KIND};
use crate::wind::wind_table::{
    REPULSOR_KIND, SOURCE_KIND, UNIFORM_KIND, VORTEX_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE,
    WIND_TABLE_SOLID,
};

/// Where the generated module lives, from the repository's root.
pub const JS_PATH: &str = "web/src/generated/contract.js";

/// One shared number: its name (the Rust constant's), its value as JavaScript writes it, where
/// the core defines it, and what it means.
#[derive(Debug, Clone, PartialEq)]
pub struct Constant {
    pub name: &'static str,
    pub value: String,
    pub defined_in: &'static str,
    pub doc: &'static str,
}

/// A group of constants under a heading.
pub struct Section {
    pub heading: &'static str,
    pub constants: Vec<Constant>,
}

/// `shared!(NAME in "module": "doc")`: the constant `NAME` (in scope here) as a [`Constant`],
/// its value as JavaScript writes it: integers plainly, single-precision floats as their
/// shortest decimal (`0.8`, not `0.800000011920929`), `3.0` as `3`.
macro_rules! shared {
    ($name:ident in $module:literal: $doc:literal) => {
        Constant {
            name: stringify!($name),
            value: $name.to_string(),
            defined_in: $module,
            doc: $doc,
        }
    };
}

/// Every shared constant, by what it belongs to.
pub fn sections() -> Vec<Section> {
    let packed_frame = vec![
        shared!(WORDS_PER_BLOB in "frame::packed":
            "32-bit words per packed blob: centre xyz, σ, mass (f32), albedo and emitted source (halves); two RGBA32UI texels."),
        shared!(BLOBS_PER_ROW in "frame::packed":
            "Blobs per row of the blob texture; the exact march's index and shadow textures are as many texels wide."),
        shared!(CLASS_BIAS in "frame::packed":
            "σ class k starts at σ = √2^(k − CLASS_BIAS) m."),
        shared!(SUBCLASS_BITS in "frame::packed":
            "Within a class the blobs are ordered by σ² to this many bits of its mantissa."),
        shared!(FOOTPRINT in "frame::packed":
            "A blob's footprint in the real-time view and the frame's bounds reach this many σ from its centre."),
        shared!(INFO_HEADER in "frame::packed":
            "Floats of the frame's info before its classes: count, lo xyz, hi xyz, emissive, σ_min, classes."),
        shared!(INFO_PER_CLASS in "frame::packed":
            "Floats of the frame's info per σ class: index, offset, count, σ_max."),
        shared!(SPHERE_FLOATS in "frame::views":
            "Floats per moving sphere of a frame: x, y, z, radius, r, g, b."),
    ];
    let volume_view = vec![
        shared!(DIRECT_LIMIT in "frame::volume":
            "Blobs narrower than this many voxels (σ < DIRECT_LIMIT · h) are splatted directly; wider ones go through the particle mesh."),
        shared!(MAX_BLUR_RADIUS in "frame::volume":
            "Longest blur kernel of the particle mesh, in voxels either side of the centre."),
        shared!(BLUR_NARROW in "frame::volume":
            "A mesh blur narrower than this many voxels (its standard deviation) is three taps."),
        shared!(BLUR_REACH in "frame::volume":
            "A wider mesh blur samples its Gaussian out to this many of its standard deviations."),
        shared!(VIEW_LIGHTS in "frame::light_volume":
            "Most lights the GPU views draw (the light volume holds one per channel)."),
        shared!(NEAR_COLUMN_VOXELS in "frame::light_volume":
            "How far towards a light (density voxels) the march sums the shadow column itself before reading the light volume."),
        shared!(NEAR_COLUMN_STEPS in "frame::light_volume":
            "Midpoint steps of that near part of the shadow column."),
    ];
    let exact_march = vec![
        shared!(TRUNCATION in "render::gaussian": "Blobs are truncated at this many σ."),
        shared!(STEP_FRACTION in "render::renderer":
            "Longest step along a ray, as a fraction of the smallest σ active on it."),
        shared!(SHADOW_GRID_HEADER in "frame::shadow_grid":
            "Floats of the shadow grid before its columns: lo xyz, hi xyz, res, lights."),
    ];
    let gpu_stepper = vec![
        shared!(BLOB_FLOATS in "frame::gpu_steps":
            "Floats per blob record handed to the GPU stepper: centre xyz, σ²; mass, age, τ, heat at birth h0; v0 xyz, 0; albedo rgb, 0; emission rgb, 0; carried offsets of phases a and b xyz, 0."),
        shared!(WIND_TABLE_HEADER in "wind::wind_table":
            "Floats of a frozen wind table's header: field slices (has field, i0, i1, f), offset, cells per metre, velocity scale, constant wind and primitive count, solids (count, layer width, has potential, carried), potential scale, carried weights and resets."),
        shared!(WIND_TABLE_PRIMITIVE in "wind::wind_table":
            "Floats per frozen primitive of a wind table: kind, 1/decay, a, b; decay origin, plane it is the image in; p, first image; q, images."),
        shared!(WIND_TABLE_SOLID in "wind::wind_table":
            "Floats per solid of a wind table: kind, difference step, doublet, 0; centre/point/base, radius; normal/axis, height; the doublet's vector."),
        shared!(SOLID_GRID_HEADER in "wind::solid_grid":
            "Floats of the solids' grid before its cells: lo xyz, cells; cells per metre xyz, planes; cells along x, y, z, 0. Then one vec4 per cell (its lists' bounds) and the members, the planes first."),
        shared!(SPHERE_SOLID_KIND in "wind::wind_table": "A solid sphere's kind in a wind table."),
        shared!(PLANE_SOLID_KIND in "wind::wind_table": "A solid plane's kind in a wind table."),
        shared!(CYLINDER_SOLID_KIND in "wind::wind_table": "A solid cylinder's kind in a wind table."),
        shared!(EDGE_STEPS in "wind::wall_set":
            "A cylinder's rims are rounded by this many difference steps for the wind."),
        shared!(SPHERE_ZONE_INNER in "wind::walls":
            "A sphere's doublet is exact within this many radii of its centre."),
        shared!(SPHERE_ZONE_OUTER in "wind::walls":
            "A sphere's doublet has faded to nothing at this many radii."),
        shared!(CYLINDER_ZONE_INNER in "wind::walls":
            "A cylinder's doublet is exact within this many radii of its axis."),
        shared!(CYLINDER_ZONE_OUTER in "wind::walls":
            "A cylinder's doublet has faded to nothing at this many radii."),
        shared!(UNIFORM_KIND in "wind::wind_table": "A uniform wind's kind in a wind table."),
        shared!(SOURCE_KIND in "wind::wind_table": "A source's (or sink's) kind in a wind table."),
        shared!(VORTEX_KIND in "wind::wind_table": "A vortex's kind in a wind table."),
        shared!(REPULSOR_KIND in "wind::wind_table": "A repulsor's kind in a wind table."),
    ];
    let scene_format = vec![
        shared!(MIN_EXTENT in "field::lattice":
            "Smallest lattice extent along any axis (field.size[i])."),
        shared!(MAX_EXTENT in "field::lattice":
            "Largest lattice extent along any axis (field.size[i])."),
        shared!(MAX_POINTS in "field::lattice": "Most lattice points in all (nx · ny · nz · nt)."),
        shared!(DEFAULT_EXTENT in "field::lattice":
            "The lattice's extent along every axis where none is named (field.size)."),
        shared!(DEFAULT_EPSILON in "field::spectrum": "ε where none is named (field.spectrum.epsilon)."),
        shared!(DEFAULT_K_INERTIAL in "field::spectrum":
            "k_inertial where none is named (field.spectrum.k_inertial)."),
        shared!(DEFAULT_SIGMA in "field::spectrum": "σ where none is named (field.spectrum.sigma)."),
        shared!(DEFAULT_SEED in "field::turbulent_field": "The seed where none is named."),
        shared!(DEFAULT_RENDER_TIME in "scene::blob_list":
            "The moment (s) a still or a poster shows when neither the scene's render.time nor the caller names one."),
        shared!(MAX_IMAGE_SIDE in "scene::limits":
            "Widest and tallest image (pixels) a still, a capture or an export may be."),
        shared!(MAX_STEPS in "scene::limits": "Most fixed steps one run may take (a step call, a recording)."),
        shared!(MAX_SECONDS in "scene::limits":
            "Longest simulated time (s) a scene's render.time or a blob list's time may give."),
        shared!(MAX_COORD in "scene::limits": "Largest coordinate magnitude (m) a scene or a blob list may hold."),
        shared!(MAX_EMITTERS in "scene::limits": "Most emitters a scene may hold."),
        shared!(MAX_ALBEDO in "scene::limits":
            "Largest albedo of a channel (the medium's, an emitter's, a blob's), from 0."),
    ];
    let browser_api = vec![
        shared!(MAX_FPS in "scene::limits":
            "Highest frame rate (frames a second) a sequence of frames or a flipbook may be asked for, greater than 0."),
        shared!(MAX_SHEET_SIDE in "export::flipbook": "Most pixels along either side of a flipbook's sheet."),
        shared!(MAX_VOXEL in "export::volume": "Largest voxel side (m) of a volume export, greater than 0."),
        shared!(MAX_STIR_RADIUS in "gas::simulation":
            "Widest reach (m) of a stir (the pointer's wind), greater than 0."),
    ];
    vec![
        Section {
            heading: "The packed frame (every GPU view's blobs)",
            constants: packed_frame,
        },
        Section {
            heading: "The real-time volume view",
            constants: volume_view,
        },
        Section {
            heading: "The exact march (the reference renderer's rules)",
            constants: exact_march,
        },
        Section {
            heading: "The GPU stepper (the gas advected on the GPU)",
            constants: gpu_stepper,
        },
        Section {
            heading: "The scene format",
            constants: scene_format,
        },
        Section {
            heading: "Exports and stirs (the browser API's arguments the core checks)",
            constants: browser_api,
        },
    ]
}

/// The generated JavaScript module: a header naming its generator, then one documented
/// `export const` per constant.
pub fn javascript() -> String {
    let mut out = String::from(
        "// GENERATED by the windfield core (wasm-core/src/contract.rs) with `windfield contract`:\n\
         // do not edit. The numbers the core and the page's code share, each defined once in the\n\
         // core. Regenerate after changing one:\n\
         //   (cd wasm-core && cargo run --release --bin windfield -- contract) > web/src/generated/contract.js\n\
         // wasm-core/tests/contract.rs fails while this file differs from what the core writes.\n",
    );
    for section in sections() {
        out.push_str(&format!("\n// {}\n", section.heading));
        for c in section.constants {
            out.push_str(&format!(
                "\n/** {} (`{}::{}`) */\nexport const {} = {};\n",
                c.doc, c.defined_in, c.name, c.name, c.value
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_constant_has_one_name_and_a_javascript_number() {
        let all: Vec<Constant> = sections().into_iter().flat_map(|s| s.constants).collect();
        let mut names: Vec<&str> = all.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all.len(), "a name is listed twice");
        for c in &all {
            let v: f64 = c.value.parse().expect("a number");
            assert!(v.is_finite() && v >= 0.0, "{}: {}", c.name, c.value);
        }
        assert_eq!(
            all.iter().find(|c| c.name == "BLUR_NARROW").unwrap().value,
            "0.8"
        );
    }
}
