//! The classroom's solid sphere: streamlines of the core's wind past a solid sphere in a uniform
//! wind, beside the same streamlines of the closed form, the potential flow around a sphere
//! (u = U − (a³/2)(3(U·r̂)r̂ − U)/r³), in the plane through the sphere's centre along the wind.

use crate::scene::scene_format::Scene;
use crate::wind::Wind;
use glam::Vec3;
use serde_json::json;

/// The streamlines of both winds, each `points` points of (x, y) in units of the radius.
#[derive(Debug, Clone)]
pub struct SphereFlow {
    /// `lines × points × 2` floats: the core's wind.
    pub core: Vec<f32>,
    /// The same for the closed form.
    pub closed_form: Vec<f32>,
    pub lines: usize,
    pub points: usize,
    /// The largest distance (radii) between a core streamline's point and the closed form's.
    pub largest_gap: f32,
}

/// The closed form: potential flow around a sphere of radius `a` at the origin in the wind `u`.
pub fn potential_flow(x: Vec3, a: f32, u: Vec3) -> Vec3 {
    let r = x.length();
    if r < a {
        return Vec3::ZERO;
    }
    let n = x / r;
    u - (n * (3.0 * u.dot(n)) - u) * (0.5 * a * a * a / (r * r * r))
}

/// Streamlines from `lines` starting points at x = −3.5 radii, y evenly from −1.6 to 1.6
/// radii (none on the stagnation line), traced by the fourth-order Runge–Kutta rule over 7
/// radii of travel in `points` points, for a sphere of unit radius in a unit wind along x.
pub fn sphere_flow(lines: usize, points: usize) -> SphereFlow {
    let scene = Scene::from_value(json!({
        "version": 1,
        "field": {"amplitude": 0, "boundary_width": 0.1},
        "wind": [{"type": "uniform", "velocity": [1, 0, 0]}],
        "render": {"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                                "color": [1, 1, 1], "solid": true}]}
    }))
    .expect("a valid scene");
    let frame = Wind::new(&scene, None).frame(0.0);
    let lines = lines.clamp(1, 64);
    let points = points.clamp(2, 2048);
    let h = 7.0 / (points - 1) as f32;
    let trace = |start: Vec3, wind: &dyn Fn(Vec3) -> Vec3| -> Vec<Vec3> {
        let mut x = start;
        let mut out = vec![x];
        for _ in 1..points {
            let k1 = wind(x);
            let k2 = wind(x + k1 * (0.5 * h));
            let k3 = wind(x + k2 * (0.5 * h));
            let k4 = wind(x + k3 * h);
            x += (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
            out.push(x);
        }
        out
    };
    let mut flow = SphereFlow {
        core: Vec::with_capacity(2 * lines * points),
        closed_form: Vec::with_capacity(2 * lines * points),
        lines,
        points,
        largest_gap: 0.0,
    };
    for l in 0..lines {
        let y = if lines == 1 {
            0.5
        } else {
            -1.6 + 3.2 * l as f32 / (lines - 1) as f32
        };
        let y = if y.abs() < 0.1 { 0.1f32.copysign(y) } else { y };
        let start = Vec3::new(-3.5, y, 0.0);
        let a = trace(start, &|x| frame.velocity(x));
        let b = trace(start, &|x| potential_flow(x, 1.0, Vec3::X));
        for (p, q) in a.iter().zip(&b) {
            flow.largest_gap = flow.largest_gap.max((*p - *q).length());
            flow.core.extend_from_slice(&[p.x, p.y]);
            flow.closed_form.extend_from_slice(&[q.x, q.y]);
        }
    }
    flow
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cores_streamlines_follow_the_closed_form() {
        let flow = sphere_flow(12, 200);
        assert_eq!(flow.core.len(), 2 * 12 * 200);
        assert!(flow.largest_gap < 0.05, "gap {}", flow.largest_gap);
        // Every streamline passes the sphere outside it.
        for p in flow.core.chunks(2) {
            assert!(p[0] * p[0] + p[1] * p[1] >= 0.99, "{p:?}");
        }
    }
}
