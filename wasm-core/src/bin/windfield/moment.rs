//! The moment a still or a volume shows: a scene simulated to `--seconds` (by default its
//! `render.time`), or a blob list as given, the moment it shows told by `--time`.

use super::failure::Failure;
use super::input::Input;
use std::path::Path;
use windfield::error::number;
use windfield::scene::blob_list::{Background, BlobList};
use windfield::scene::limits::MAX_SECONDS;
use windfield::{ParamError, Scene, Simulation};

/// Seconds of simulated time asked for with `--seconds`: a number, 0 or more. How many the
/// scene may take is the step budget's to say (`Simulation::budgeted_steps`, which names
/// `simulation.dt` and the time).
pub fn check_seconds(seconds: f64) -> Result<(), Failure> {
    if seconds.is_finite() && seconds >= 0.0 {
        Ok(())
    } else {
        Err(Failure::Input(format!(
            "--seconds: must be a number, 0 or more (got {})",
            number(seconds)
        )))
    }
}

/// A blob list's time given with `--time`: 0 to `scene::limits::MAX_SECONDS`.
pub fn check_list_time(time: f64) -> Result<(), Failure> {
    if time.is_finite() && (0.0..=MAX_SECONDS).contains(&time) {
        Ok(())
    } else {
        Err(Failure::Input(format!(
            "--time: must be a number between 0 and {MAX_SECONDS} (got {})",
            number(time)
        )))
    }
}

/// A scene simulated to `seconds` (refused over the step budget before it starts).
pub fn simulated(
    scene: Scene,
    seconds: f64,
    bad: impl Fn(ParamError) -> Failure,
) -> Result<Simulation, Failure> {
    let mut sim = Simulation::new(scene).map_err(&bad)?;
    let steps = sim.budgeted_steps(seconds).map_err(&bad)?;
    sim.run(steps);
    Ok(sim)
}

/// The blob list `input` (read from `path`) shows and, for a scene, the time it was simulated
/// to: a scene at `seconds` (default its `render.time`), or a blob list at `time`; `what` a
/// scene makes (`still`, `volume`) names it in the refusal of `--time`. With `transparent` the
/// list's background is `transparent`.
pub fn blob_list_at(
    input: Input,
    path: &Path,
    seconds: Option<f64>,
    time: Option<f64>,
    what: &str,
    transparent: bool,
) -> Result<(BlobList, Option<f64>), Failure> {
    match input {
        Input::Scene(_) if time.is_some() => Err(Failure::Input(format!(
            "--time: applies to blob lists; a scene's {what} records the time it is simulated to (--seconds)"
        ))),
        Input::Scene(mut scene) => {
            if transparent {
                scene.render.background = Background::Transparent;
            }
            let seconds = seconds.unwrap_or(scene.render.still_time());
            let bad = |e: ParamError| Failure::Input(format!("{}: {e}", path.display()));
            let sim = simulated(*scene, seconds, bad)?;
            Ok((sim.blob_list(), Some(sim.time())))
        }
        Input::List(_) if seconds.is_some() => Err(Failure::Input(
            "--seconds: applies to scenes only; this input is a blob list".into(),
        )),
        Input::List(mut list) => {
            if transparent {
                list.background = Background::Transparent;
            }
            if let Some(t) = time {
                check_list_time(t)?;
            }
            Ok((list, time))
        }
    }
}
