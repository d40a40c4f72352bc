//! The bounds of the two formats (the scene and the blob list of docs/FORMATS.md): largest
//! coordinates, list lengths and the memory guards, checked before anything is built
//! ([`super::validate`]) and stated in the JSON Schema ([`super::scene_format::json_schema`]).
//!
//! Costs behind the memory guards: a live blob costs the core 80 bytes (76 of state, 4 of decay
//! factor); a blob handed to a renderer 88 more (its record), and the renderer's own copy of it
//! 88 + 44 + its share of the hierarchy.

/// Longest scene text read (bytes): a scene file, or the JSON the browser's worker is handed,
/// is refused over it before it is parsed. The largest scene the list budgets allow in
/// ordinary notation is a few megabytes.
pub const MAX_SCENE_BYTES: usize = 64 << 20;

/// Largest accepted coordinate magnitude (m).
pub const MAX_COORD: f64 = 1.0e6;

/// The world mapping's ranges (docs/FORMATS.md, the field), `[lowest, highest]` of each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldMapping {
    /// Metres one spatial period of the field spans, along each axis.
    pub period: [f64; 2],
    /// Seconds one temporal period of the field spans.
    pub time_period: [f64; 2],
    /// The small-scale velocity's scale (0 turns the turbulence off).
    pub amplitude: [f64; 2],
}

/// The world mapping's ranges, one home for every check of them. Periods far below a
/// millimetre or a millisecond put world points at lattice coordinates and speeds beyond single
/// precision.
pub const WORLD_MAPPING: WorldMapping = WorldMapping {
    period: [1e-3, 1e4],
    time_period: [1e-3, 1e6],
    amplitude: [0.0, 1e3],
};

/// The largest σ0 (m) a born blob may have (an emitter's births and an initial set's points
/// alike, paper §6); σ0 is greater than 0.
pub const MAX_SIGMA0: f64 = 1e4;
/// The largest m0 a born blob may have; m0 is greater than 0.
pub const MAX_MASS0: f64 = 1e12;
/// The largest albedo of a channel: the fraction of the light a blob scatters, from 0 (a whole
/// number, as the JSON Schema writes it).
pub const MAX_ALBEDO: u8 = 1;
/// The largest self-emission Q of a channel, from 0.
pub const MAX_EMISSION: f64 = 1e6;

/// Most live blobs (`gas.max_blobs`): 80 MB of blob state, twice that while a step splits.
pub const MAX_BLOBS_LIMIT: usize = 1_000_000;
/// Most births in one step: Σ over the enabled emitters of rate × `simulation.dt` (a step
/// holds its births until it caps the gas, so they come on top of `max_blobs`).
pub const MAX_BIRTHS_PER_STEP: f64 = 100_000.0;
/// Most blobs one initial set (`shapes[i]`) may hold.
pub const MAX_SHAPE_BLOBS: usize = 200_000;
/// Most blobs all `shapes` together make at time 0 (before any cap applies).
pub const MAX_SHAPES_BLOBS: usize = 1_000_000;
/// Memory guard on reversed shapes, which store their whole run: Σ over them of the blobs a
/// step may hold × (steps + 1).
pub const MAX_REVERSED_BLOB_STEPS: f64 = 2e6;
/// Most steps the reversed shapes keep together (each kept step costs about 600 bytes of
/// its own, whatever its blobs).
pub const MAX_REVERSED_STEPS: f64 = 1e5;
/// Most wind primitives (each is evaluated for every blob at every step).
pub const MAX_PRIMITIVES: usize = 256;
/// Most emitters.
pub const MAX_EMITTERS: usize = 256;
/// Most initial blob sets.
pub const MAX_SHAPES: usize = 256;
/// Most keys on a repulsor's path.
pub const MAX_PATH_KEYS: usize = 10_000;

/// Longest simulated time (s) a scene's `render.time` or a blob list's time may give: the
/// longest run the step budget allows at the largest step (`simulation.dt` = 1 s). A run's own
/// time (`--seconds`) is bounded by the step budget alone, whose refusal names `simulation.dt`.
pub const MAX_SECONDS: f64 = 1e6;
/// Most fixed steps one run may take (docs/FORMATS.md, the command line): more is refused before it starts.
pub const MAX_STEPS: u64 = 1_000_000;
/// Highest frame rate (frames a second) a sequence of frames or a flipbook may be asked for;
/// it is greater than 0.
pub const MAX_FPS: f64 = 1e4;

/// Largest image side in pixels.
pub const MAX_IMAGE_SIDE: u32 = 8192;
/// Most lights in a scene or a blob list (each adds a shadow ray to every step of every ray).
pub const MAX_LIGHTS: usize = 64;
/// Most opaque objects in a scene.
pub const MAX_OBJECTS: usize = 256;
/// Most opaque objects in a blob list: a scene's objects plus the spheres of its repulsors.
pub const MAX_LIST_OBJECTS: usize = MAX_OBJECTS + MAX_PRIMITIVES;
/// Most blobs in a blob list: what the largest scene can show, `gas.max_blobs` of gas plus the
/// reversed shapes' blobs (at most 2,000,000 over all their steps).
pub const MAX_LIST_BLOBS: usize = MAX_BLOBS_LIMIT + 2 * MAX_SHAPES_BLOBS;

/// The cells a flow may have along each axis (`flow.cells[i]`), `[fewest, most]`.
pub const FLOW_CELLS: [usize; 2] = [8, 256];
/// Most cells of a flow (2^21): its solver holds about [`FLOW_BYTES_PER_CELL`] bytes a cell.
pub const MAX_FLOW_CELLS: u64 = 1 << 21;
/// What the flow's solver holds a cell (bytes): its face velocities and their scratch copies,
/// the projection's vectors in double precision, the solid cells and the temperature.
pub const FLOW_BYTES_PER_CELL: u64 = 200;
/// How far the box's sides per cell may differ from their mean (relative): the cells are cubes.
pub const FLOW_CUBE_TOLERANCE: f64 = 0.01;
/// Most cell-steps (cells × steps) one run with a flow may take: about an hour of one core at
/// the largest grid.
pub const MAX_FLOW_CELL_STEPS: f64 = 1e10;
/// Most substeps of the flow's explicit viscosity in one step (each substep keeps ν·dt/h² at
/// most [`FLOW_VISCOSITY_STEP`]).
pub const MAX_VISCOSITY_SUBSTEPS: f64 = 64.0;
/// The largest ν·dt/h² of one substep of the flow's explicit viscosity (forward Euler of the
/// seven-point Laplacian is stable up to 1/6).
pub const FLOW_VISCOSITY_STEP: f64 = 0.125;
/// An emitter's `temperature` range (K above the ambient air): down to absolute zero at room
/// temperature, up to a flame's ten thousand.
pub const TEMPERATURE: [f64; 2] = [-273.15, 1e4];
