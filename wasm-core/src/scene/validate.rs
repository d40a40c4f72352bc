//! The one validation walk of each format: [`Scene::validate`] visits every value of a scene
//! (docs/FORMATS.md, the scene format) and [`BlobList::validate`] every value of a blob list (docs/FORMATS.md), the two
//! sharing the walk over a view's camera, image, medium, lights and objects. The per-value
//! checks are [`crate::check`]'s; the bounds are [`super::limits`]'. An error names the value
//! by its JSON path and says what is allowed; the walk stops at the first.
//!
//! Everything that builds from a scene ([`crate::gas::simulation::Simulation`]) or a blob list
//! ([`crate::render::Renderer`]) runs this walk once at its door and nothing after it checks
//! again.

use crate::check;
use crate::error::ParamError;
use crate::field::MAX_SEED;
use crate::scene::blob_list::{
    Background, BlobList, Camera, Extinction, Image, Light, Medium, Object, Phase, RenderSettings,
};
use crate::scene::bodies::Body;
use crate::scene::flow_settings::FlowSettings;
use crate::scene::limits::{
    FLOW_BYTES_PER_CELL, FLOW_CELLS, FLOW_CUBE_TOLERANCE, MAX_ALBEDO, MAX_BIRTHS_PER_STEP,
    MAX_BLOBS_LIMIT, MAX_COORD, MAX_EMISSION, MAX_EMITTERS, MAX_FLOW_CELLS, MAX_IMAGE_SIDE,
    MAX_LIGHTS, MAX_LIST_BLOBS, MAX_LIST_OBJECTS, MAX_MASS0, MAX_OBJECTS, MAX_PATH_KEYS,
    MAX_PRIMITIVES, MAX_REVERSED_BLOB_STEPS, MAX_REVERSED_STEPS, MAX_SECONDS, MAX_SHAPES,
    MAX_SHAPES_BLOBS, MAX_SHAPE_BLOBS, MAX_SIGMA0, MAX_VISCOSITY_SUBSTEPS, TEMPERATURE,
    WORLD_MAPPING,
};
use crate::scene::scene_format::{
    Emitter, GasSettings, Primitive, Scene, DEFAULT_BOUNDARY_WIDTH, SCENE_VERSION,
};
use crate::scene::shapes::{Shape, Solid};

impl Scene {
    /// Checks every value against its range, section by section in the order of the format:
    /// version and seed, the list lengths (before anything looks inside the lists), the field
    /// and its world mapping, wind, emitters, simulation, gas, shapes, render.
    pub fn validate(&self) -> Result<(), ParamError> {
        if self.version != SCENE_VERSION {
            return Err(ParamError::new(
                "version",
                format!("must be {SCENE_VERSION} (got {})", self.version),
            ));
        }
        check::integer("seed", self.seed, 0, MAX_SEED)?;
        lengths(self)?;
        field(self)?;
        for (i, w) in self.wind.iter().enumerate() {
            primitive(&format!("wind[{i}]"), w)?;
        }
        for (i, e) in self.emitters.iter().enumerate() {
            emitter(&format!("emitters[{i}]"), e)?;
        }
        check::positive("simulation.dt", self.simulation.dt, 1.0)?;
        births(self)?;
        gas(&self.gas)?;
        for (i, s) in self.shapes.iter().enumerate() {
            shape(&format!("shapes[{i}]"), s)?;
        }
        shape_budgets(self)?;
        if let Some(t) = self.render.time {
            check::range("render.time", t, 0.0, MAX_SECONDS)?;
        }
        view(&self.render, "render.", MAX_OBJECTS)?;
        emitters_outside_solids(self)?;
        if let Some(f) = &self.flow {
            flow(f, self.simulation.dt)?;
        }
        if let Some(t) = self.render.time {
            // A still at `render.time` is a run like any other (docs/FORMATS.md, the command line).
            self.budgeted_steps(t)?;
        }
        Ok(())
    }
}

impl BlobList {
    /// Checks the view and every blob; paths are those of the blob list's JSON.
    pub fn validate(&self) -> Result<(), ParamError> {
        check::length("blobs", self.blobs.len(), MAX_LIST_BLOBS, "blobs")?;
        view(&self.settings(), "", MAX_LIST_OBJECTS)?;
        for (i, b) in self.blobs.iter().enumerate() {
            let bp = format!("blobs[{i}]");
            check::vector(&format!("{bp}.center"), b.center, MAX_COORD)?;
            check::positive(&format!("{bp}.sigma"), b.sigma, MAX_COORD)?;
            check::range(&format!("{bp}.mass"), b.mass, 0.0, MAX_MASS0)?;
            if let Some(a) = b.albedo {
                check::colour(&format!("{bp}.albedo"), a, f64::from(MAX_ALBEDO))?;
            }
            if let Some(q) = b.emission {
                check::colour(&format!("{bp}.emission"), q, MAX_EMISSION)?;
            }
        }
        Ok(())
    }
}

/// The list lengths, the memory guards checked before anything looks inside the lists.
fn lengths(scene: &Scene) -> Result<(), ParamError> {
    check::length("wind", scene.wind.len(), MAX_PRIMITIVES, "primitives")?;
    check::length("emitters", scene.emitters.len(), MAX_EMITTERS, "emitters")?;
    check::length("shapes", scene.shapes.len(), MAX_SHAPES, "shapes")?;
    for (i, w) in scene.wind.iter().enumerate() {
        if let Primitive::Repulsor { path, .. } = w {
            let at = format!("wind[{i}].path");
            check::length(&at, path.len(), MAX_PATH_KEYS, "keys")?;
        }
    }
    for (i, e) in scene.emitters.iter().enumerate() {
        let at = format!("emitters[{i}].path");
        check::length(&at, e.path.len(), MAX_PATH_KEYS, "keys")?;
    }
    Ok(())
}

/// The field's parameters (lattice, spectrum, seed: the field's own check) and its world
/// mapping (docs/FORMATS.md, the field).
fn field(scene: &Scene) -> Result<(), ParamError> {
    scene.field_params().validate()?;
    let f = &scene.field;
    let [lo, hi] = WORLD_MAPPING.period;
    for (i, &l) in f.period.iter().enumerate() {
        check::range(&format!("field.period[{i}]"), l, lo, hi)?;
    }
    let [lo, hi] = WORLD_MAPPING.time_period;
    check::range("field.time_period", f.time_period, lo, hi)?;
    let [lo, hi] = WORLD_MAPPING.amplitude;
    check::range("field.amplitude", f.amplitude, lo, hi)?;
    // The layer over a solid: thinner than half the field's shortest period, so the ramp never
    // spans a whole period of the eddies it turns. The layer acts only on solids: a scene
    // without them and with the default width keeps any period the field allows.
    let half = 0.5 * f.period.iter().copied().fold(f64::INFINITY, f64::min);
    let unused_default = !scene.has_solids() && f.boundary_width == DEFAULT_BOUNDARY_WIDTH;
    let bound = if unused_default { f64::INFINITY } else { half };
    if !(f.boundary_width.is_finite() && f.boundary_width > 0.0 && f.boundary_width <= bound) {
        return Err(ParamError::new(
            "field.boundary_width",
            format!(
                "must be a finite number greater than 0 and at most half the field's shortest \
                 period, {half} m (got {})",
                f.boundary_width
            ),
        ));
    }
    if let Some(t) = f.carry_time {
        check::positive("field.carry_time", t, 1e6)?;
    }
    Ok(())
}

/// No emitter is centred inside a solid object (its blobs could never leave it): the centre,
/// or every key of a moving emitter's path.
fn emitters_outside_solids(scene: &Scene) -> Result<(), ParamError> {
    let bodies: Vec<(usize, Body)> = scene
        .render
        .objects
        .iter()
        .enumerate()
        .filter_map(|(j, o)| Body::of(o).map(|b| (j, b)))
        .collect();
    if bodies.is_empty() {
        return Ok(());
    }
    for (i, e) in scene.emitters.iter().enumerate() {
        let places: Vec<(String, [f32; 3])> = if e.path.is_empty() {
            vec![(format!("emitters[{i}].center"), e.center)]
        } else {
            e.path
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    (
                        format!("emitters[{i}].path[{k}]"),
                        [p[1] as f32, p[2] as f32, p[3] as f32],
                    )
                })
                .collect()
        };
        for (path, x) in places {
            for (j, body) in &bodies {
                let (d, _) = body.distance(glam::Vec3A::from_array(x));
                if d < 0.0 {
                    let kind = match body {
                        Body::Sphere { .. } => "sphere",
                        Body::Plane { .. } => "plane",
                        Body::Cylinder { .. } => "cylinder",
                    };
                    return Err(ParamError::new(
                        path,
                        format!(
                            "lies inside the solid {kind} render.objects[{j}] ({:.3} m below \
                             its surface): move the emitter out of it, or make the object not \
                             solid (render.objects[{j}].solid: false)",
                            -d
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

fn decay(path: &str, decay: Option<f32>) -> Result<(), ParamError> {
    match decay {
        Some(l) => check::positive(&format!("{path}.decay"), l, MAX_COORD),
        None => Ok(()),
    }
}

/// A large-scale wind primitive (paper Eq. 3's u_l).
fn primitive(path: &str, w: &Primitive) -> Result<(), ParamError> {
    let p = |s: &str| format!("{path}.{s}");
    match w {
        Primitive::Uniform {
            velocity,
            position,
            decay: l,
            ..
        } => {
            check::vector(&p("velocity"), *velocity, 1e4)?;
            check::vector(&p("position"), *position, MAX_COORD)?;
            decay(path, *l)
        }
        Primitive::Source {
            position,
            strength,
            radius,
            decay: l,
            ..
        } => {
            check::vector(&p("position"), *position, MAX_COORD)?;
            check::range(&p("strength"), *strength, -1e6, 1e6)?;
            check::positive(&p("radius"), *radius, MAX_COORD)?;
            decay(path, *l)
        }
        Primitive::Vortex {
            position,
            axis,
            strength,
            radius,
            decay: l,
            ..
        } => {
            check::vector(&p("position"), *position, MAX_COORD)?;
            check::direction(&p("axis"), *axis)?;
            check::range(&p("strength"), *strength, -1e6, 1e6)?;
            check::positive(&p("radius"), *radius, MAX_COORD)?;
            decay(path, *l)
        }
        Primitive::Repulsor {
            radius,
            strength,
            path: keys,
            color,
            decay: l,
            ..
        } => {
            check::positive(&p("radius"), *radius, MAX_COORD)?;
            check::range(&p("strength"), *strength, 0.0, 1e4)?;
            path_keys(path, keys)?;
            if let Some(c) = color {
                check::colour(&p("color"), *c, 1.0)?;
            }
            decay(path, *l)
        }
    }
}

/// A repulsor's (or a moving emitter's) path: at least one key `[t, x, y, z]`, times strictly
/// increasing.
fn path_keys(path: &str, keys: &[[f64; 4]]) -> Result<(), ParamError> {
    if keys.is_empty() {
        return Err(ParamError::new(
            format!("{path}.path"),
            "must hold at least one key [t, x, y, z]",
        ));
    }
    for (k, key) in keys.iter().enumerate() {
        for (c, v) in key.iter().enumerate() {
            check::range(&format!("{path}.path[{k}][{c}]"), *v, -MAX_COORD, MAX_COORD)?;
        }
        if k > 0 && key[0] <= keys[k - 1][0] {
            return Err(ParamError::new(
                format!("{path}.path[{k}][0]"),
                "key times must increase strictly",
            ));
        }
    }
    Ok(())
}

/// An emitter (paper §6: region of birth, birth rate, σ0 and m0).
fn emitter(path: &str, e: &Emitter) -> Result<(), ParamError> {
    let p = |s: &str| format!("{path}.{s}");
    if !e.path.is_empty() {
        path_keys(path, &e.path)?;
    }
    check::vector(&p("center"), e.center, MAX_COORD)?;
    check::direction(&p("normal"), e.normal)?;
    check::range(&p("radius"), e.radius, 0.0, MAX_COORD)?;
    for (i, &s) in e.size.iter().enumerate() {
        check::range(&format!("{path}.size[{i}]"), s, 0.0, MAX_COORD)?;
    }
    check::range(&p("rate"), e.rate, 0.0, 1e6)?;
    blob_birth(path, e.sigma0, e.mass0, e.albedo, e.emission)?;
    check::vector(&p("velocity"), e.velocity, 1e4)?;
    check::positive(&p("velocity_time"), e.velocity_time, 1e6)?;
    let [lo, hi] = TEMPERATURE;
    check::range(&p("temperature"), e.temperature, lo, hi)
}

/// The flow (docs/FORMATS.md, the flow): its box, its cells (each within [`FLOW_CELLS`], at
/// most [`MAX_FLOW_CELLS`] in all, cubes within [`FLOW_CUBE_TOLERANCE`]), its constants, and
/// its viscosity's substeps at the step `dt` (s) within [`MAX_VISCOSITY_SUBSTEPS`].
fn flow(f: &FlowSettings, dt: f64) -> Result<(), ParamError> {
    for (i, &v) in f.bounds.iter().enumerate() {
        check::range(&format!("flow.box[{i}]"), v, -MAX_COORD, MAX_COORD)?;
    }
    for a in 0..3 {
        let (lo, hi) = (f.bounds[a], f.bounds[a + 3]);
        if hi <= lo {
            return Err(ParamError::new(
                format!("flow.box[{}]", a + 3),
                format!(
                    "must be greater than flow.box[{a}] (the box's lower corner), got {} ≤ {}",
                    crate::error::number(hi),
                    crate::error::number(lo)
                ),
            ));
        }
    }
    let [fewest, most] = FLOW_CELLS;
    for (i, &n) in f.cells.iter().enumerate() {
        check::integer(
            &format!("flow.cells[{i}]"),
            n as u64,
            fewest as u64,
            most as u64,
        )?;
    }
    let count = f.cell_count();
    if count > MAX_FLOW_CELLS {
        return Err(ParamError::new(
            "flow.cells",
            format!(
                "{count} cells ({} × {} × {}) are over the limit of {MAX_FLOW_CELLS} \
                 (2^21, {} MB of solver): fewer cells",
                f.cells[0],
                f.cells[1],
                f.cells[2],
                (MAX_FLOW_CELLS * FLOW_BYTES_PER_CELL) >> 20
            ),
        ));
    }
    let h = f.h();
    let spacings = f.spacings();
    if spacings
        .iter()
        .any(|s| (s - h).abs() > FLOW_CUBE_TOLERANCE * h)
    {
        return Err(ParamError::new(
            "flow.cells",
            format!(
                "the box's sides per cell ({} m, {} m, {} m) must agree within {} % (the cells \
                 are cubes): choose cells in proportion to the box",
                crate::error::number(spacings[0]),
                crate::error::number(spacings[1]),
                crate::error::number(spacings[2]),
                FLOW_CUBE_TOLERANCE * 100.0
            ),
        ));
    }
    check::range("flow.viscosity", f.viscosity, 0.0, 10.0)?;
    check::range("flow.buoyancy", f.buoyancy, 0.0, 1.0)?;
    for (i, &g) in f.gravity.iter().enumerate() {
        check::range(&format!("flow.gravity[{i}]"), g, -1e3, 1e3)?;
    }
    check::range("flow.cooling", f.cooling, 0.0, 1e3)?;
    let substeps = f.viscosity_substeps(dt);
    if substeps > MAX_VISCOSITY_SUBSTEPS {
        return Err(ParamError::new(
            "flow.viscosity",
            format!(
                "ν = {} m²/s at dt = {dt:?} s on cells of {} m needs {substeps} substeps a \
                 step, over the limit of {MAX_VISCOSITY_SUBSTEPS}: a smaller viscosity, a \
                 smaller simulation.dt or coarser cells",
                crate::error::number(f.viscosity),
                crate::error::number(h)
            ),
        ));
    }
    Ok(())
}

/// What every born blob carries, under `path` (paper §6: an emitter's births and an initial
/// set's points alike): σ0 in (0, [`MAX_SIGMA0`]] m, m0 in (0, [`MAX_MASS0`]], an optional
/// albedo in [0, [`MAX_ALBEDO`]] and an optional emission in [0, [`MAX_EMISSION`]] per channel.
fn blob_birth(
    path: &str,
    sigma0: f32,
    mass0: f32,
    albedo: Option<[f32; 3]>,
    emission: Option<[f32; 3]>,
) -> Result<(), ParamError> {
    check::positive(&format!("{path}.sigma0"), sigma0, MAX_SIGMA0)?;
    check::positive(&format!("{path}.mass0"), mass0, MAX_MASS0)?;
    if let Some(a) = albedo {
        check::colour(&format!("{path}.albedo"), a, f64::from(MAX_ALBEDO))?;
    }
    if let Some(q) = emission {
        check::colour(&format!("{path}.emission"), q, MAX_EMISSION)?;
    }
    Ok(())
}

/// Births a step, Σ over the enabled emitters of rate × dt, within [`MAX_BIRTHS_PER_STEP`].
fn births(scene: &Scene) -> Result<(), ParamError> {
    let dt = scene.simulation.dt;
    let births: f64 = scene
        .emitters
        .iter()
        .filter(|e| e.enabled)
        .map(|e| e.rate * dt)
        .sum();
    if births <= MAX_BIRTHS_PER_STEP {
        return Ok(());
    }
    Err(ParamError::new(
        "emitters",
        format!(
            "the enabled emitters' rates × simulation.dt = {dt:?} s make {births:.0} births \
             a step, over the limit of {MAX_BIRTHS_PER_STEP:.0}: lower the rates or \
             simulation.dt"
        ),
    ))
}

/// The gas constants (paper Eqs. 12, 15, 16) and its caps.
fn gas(g: &GasSettings) -> Result<(), ParamError> {
    check::range("gas.diffusion", g.diffusion, 0.0, 1e3)?;
    check::range("gas.dissipation", g.dissipation, 0.0, 1e3)?;
    if let Some(s) = g.split_sigma {
        check::positive("gas.split_sigma", s, 1e4)?;
    }
    check::integer(
        "gas.max_blobs",
        g.max_blobs as u64,
        1,
        MAX_BLOBS_LIMIT as u64,
    )?;
    check::range("gas.min_mass", g.min_mass, 0.0, 1e12)
}

/// An initial blob set (paper §6, "3-D morphing").
fn shape(path: &str, s: &Shape) -> Result<(), ParamError> {
    let p = |name: &str| format!("{path}.{name}");
    check::vector(&p("center"), s.center, MAX_COORD)?;
    check::direction(&p("axis"), s.axis)?;
    check::positive(&p("radius"), s.radius, MAX_COORD)?;
    check::positive(&p("thickness"), s.thickness, MAX_COORD)?;
    if s.shape != Solid::Points {
        check::integer(&p("count"), s.count as u64, 1, MAX_SHAPE_BLOBS as u64)?;
    }
    if s.points.len() > MAX_SHAPE_BLOBS {
        return Err(ParamError::new(
            p("points"),
            format!("at most {MAX_SHAPE_BLOBS} points"),
        ));
    }
    for (i, &q) in s.points.iter().enumerate() {
        check::vector(&format!("{path}.points[{i}]"), q, MAX_COORD)?;
    }
    blob_birth(path, s.sigma0, s.mass0, s.albedo, s.emission)?;
    if let Some(t) = s.reverse_from {
        check::positive(&p("reverse_from"), t, 1e4)?;
    }
    Ok(())
}

/// The blobs of all shapes together, and what reversed shapes keep: every step of their run,
/// each holding the set's blobs (or, when the gas splits, up to `gas.max_blobs`).
fn shape_budgets(scene: &Scene) -> Result<(), ParamError> {
    let total: usize = scene.shapes.iter().map(Shape::blob_count).sum();
    if total > MAX_SHAPES_BLOBS {
        return Err(ParamError::new(
            "shapes",
            format!(
                "all shapes together make {total} blobs, over the limit of \
                 {MAX_SHAPES_BLOBS}: lower their counts"
            ),
        ));
    }
    let (mut steps, mut blob_steps) = (0.0, 0.0);
    for shape in &scene.shapes {
        if let Some(t) = shape.reverse_from {
            // The run a reversed set keeps is a run like any other (docs/FORMATS.md, the command line).
            let kept = scene.simulation.budgeted_steps(t)? as f64 + 1.0;
            let per_step = match scene.gas.split_sigma {
                Some(_) => shape.blob_count().max(scene.gas.max_blobs),
                None => shape.blob_count(),
            };
            steps += kept;
            blob_steps += per_step as f64 * kept;
        }
    }
    let over = |what: &str, got: f64, limit: f64| {
        ParamError::new(
            "shapes",
            format!(
                "reversed sets keep every step of their run: {what} must stay below \
                 {limit:e} (got {got:.3e})"
            ),
        )
    };
    if blob_steps > MAX_REVERSED_BLOB_STEPS {
        return Err(over(
            "blobs × (reverse_from / dt + 1), a splitting gas counting gas.max_blobs a step,",
            blob_steps,
            MAX_REVERSED_BLOB_STEPS,
        ));
    }
    if steps > MAX_REVERSED_STEPS {
        return Err(over(
            "the steps, reverse_from / dt + 1,",
            steps,
            MAX_REVERSED_STEPS,
        ));
    }
    Ok(())
}

/// What a blob list shares with a scene's `render` section, with at most `max_objects`
/// objects; paths start with `prefix` (`render.` for a scene, empty for a blob list).
fn view(v: &RenderSettings, prefix: &str, max_objects: usize) -> Result<(), ParamError> {
    let p = |s: &str| format!("{prefix}{s}");
    check::length(&p("lights"), v.lights.len(), MAX_LIGHTS, "lights")?;
    check::length(&p("objects"), v.objects.len(), max_objects, "objects")?;
    camera(&v.camera, prefix)?;
    image(&v.image, prefix)?;
    medium(&v.medium, prefix)?;
    for (i, l) in v.lights.iter().enumerate() {
        light(&p(&format!("lights[{i}]")), l)?;
    }
    if let Background::Colour(c) = v.background {
        check::colour(&p("background"), c, 1e6)?;
    }
    for (i, o) in v.objects.iter().enumerate() {
        object(&p(&format!("objects[{i}]")), o)?;
    }
    Ok(())
}

/// A pinhole camera: a target apart from the position, an up not along the view.
fn camera(c: &Camera, prefix: &str) -> Result<(), ParamError> {
    let p = |s: &str| format!("{prefix}camera.{s}");
    check::vector(&p("position"), c.position, MAX_COORD)?;
    check::vector(&p("target"), c.target, MAX_COORD)?;
    check::direction(&p("up"), c.up)?;
    check::range(&p("fov_y_deg"), c.fov_y_deg, 0.1, 179.0)?;
    let view: Vec<f32> = (0..3).map(|i| c.target[i] - c.position[i]).collect();
    let len2: f32 = view.iter().map(|v| v * v).sum();
    if len2 < 1e-12 {
        return Err(ParamError::new(
            p("target"),
            "must differ from camera.position",
        ));
    }
    let cross = [
        view[1] * c.up[2] - view[2] * c.up[1],
        view[2] * c.up[0] - view[0] * c.up[2],
        view[0] * c.up[1] - view[1] * c.up[0],
    ];
    let up2: f32 = c.up.iter().map(|v| v * v).sum();
    if cross.iter().map(|v| v * v).sum::<f32>() < 1e-10 * len2 * up2 {
        return Err(ParamError::new(
            p("up"),
            "must not be parallel to the view direction",
        ));
    }
    Ok(())
}

fn image(image: &Image, prefix: &str) -> Result<(), ParamError> {
    let side = MAX_IMAGE_SIDE as u64;
    check::integer(&format!("{prefix}image.width"), image.width as u64, 1, side)?;
    check::integer(
        &format!("{prefix}image.height"),
        image.height as u64,
        1,
        side,
    )
}

/// The medium's optical constants (paper Appendix B).
fn medium(m: &Medium, prefix: &str) -> Result<(), ParamError> {
    let p = |s: &str| format!("{prefix}medium.{s}");
    match m.extinction {
        Extinction::Grey(k) => check::range(&p("extinction"), k, 0.0, 1e6)?,
        Extinction::Rgb(rgb) => {
            for (i, k) in rgb.into_iter().enumerate() {
                check::range(&format!("{}[{i}]", p("extinction")), k, 0.0, 1e6)?;
            }
        }
    }
    check::colour(&p("albedo"), m.albedo, 1.0)?;
    if let Phase::HenyeyGreenstein { g } = m.phase {
        if !(g.is_finite() && g > -1.0 && g < 1.0) {
            return Err(ParamError::new(
                p("phase.g"),
                format!(
                    "must be strictly between -1 and 1 (got {})",
                    crate::check::Number::echo(g)
                ),
            ));
        }
    }
    Ok(())
}

fn light(path: &str, light: &Light) -> Result<(), ParamError> {
    let color = match light {
        Light::Point { position, color } => {
            check::vector(&format!("{path}.position"), *position, MAX_COORD)?;
            color
        }
        Light::Directional { direction, color } => {
            check::direction(&format!("{path}.direction"), *direction)?;
            color
        }
    };
    check::colour(&format!("{path}.color"), *color, 1e6)
}

fn object(path: &str, object: &Object) -> Result<(), ParamError> {
    let p = |s: &str| format!("{path}.{s}");
    match object {
        Object::Sphere {
            center,
            radius,
            color,
            ..
        } => {
            check::vector(&p("center"), *center, MAX_COORD)?;
            check::positive(&p("radius"), *radius, MAX_COORD)?;
            check::colour(&p("color"), *color, 1.0)
        }
        Object::Plane {
            point,
            normal,
            color,
            ..
        } => {
            check::vector(&p("point"), *point, MAX_COORD)?;
            check::direction(&p("normal"), *normal)?;
            check::colour(&p("color"), *color, 1.0)
        }
        Object::Cylinder {
            base,
            axis,
            radius,
            height,
            color,
            ..
        } => {
            check::vector(&p("base"), *base, MAX_COORD)?;
            check::direction(&p("axis"), *axis)?;
            check::positive(&p("radius"), *radius, MAX_COORD)?;
            check::positive(&p("height"), *height, MAX_COORD)?;
            check::colour(&p("color"), *color, 1.0)
        }
    }
}
