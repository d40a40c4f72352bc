//! A smooth path through keyed points `[t, x, y, z]`: a cubic Hermite spline with Catmull-Rom
//! tangents for uneven key spacing (C¹: position and velocity continuous). Before the first key
//! and after the last the position holds and the velocity is zero.

use glam::DVec3;

#[derive(Debug, Clone)]
pub struct Path {
    times: Vec<f64>,
    points: Vec<DVec3>,
    tangents: Vec<DVec3>,
}

impl Path {
    /// `keys` must be non-empty with strictly increasing times (checked by the scene).
    pub fn new(keys: &[[f64; 4]]) -> Self {
        let times: Vec<f64> = keys.iter().map(|k| k[0]).collect();
        let points: Vec<DVec3> = keys.iter().map(|k| DVec3::new(k[1], k[2], k[3])).collect();
        let n = points.len();
        let tangents = (0..n)
            .map(|i| {
                if n < 2 {
                    DVec3::ZERO
                } else {
                    let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
                    (points[b] - points[a]) / (times[b] - times[a])
                }
            })
            .collect();
        Self {
            times,
            points,
            tangents,
        }
    }

    /// Position (m) and velocity (m/s) at time `t` (s).
    pub fn at(&self, t: f64) -> (DVec3, DVec3) {
        let n = self.points.len();
        if n == 1 || t <= self.times[0] {
            return (self.points[0], DVec3::ZERO);
        }
        if t >= self.times[n - 1] {
            return (self.points[n - 1], DVec3::ZERO);
        }
        let i = self.times.partition_point(|&k| k <= t) - 1;
        let h = self.times[i + 1] - self.times[i];
        let s = (t - self.times[i]) / h;
        let (s2, s3) = (s * s, s * s * s);
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        let (m0, m1) = (self.tangents[i] * h, self.tangents[i + 1] * h);
        let pos = p0 * (2.0 * s3 - 3.0 * s2 + 1.0)
            + m0 * (s3 - 2.0 * s2 + s)
            + p1 * (-2.0 * s3 + 3.0 * s2)
            + m1 * (s3 - s2);
        let vel = (p0 * (6.0 * s2 - 6.0 * s)
            + m0 * (3.0 * s2 - 4.0 * s + 1.0)
            + p1 * (-6.0 * s2 + 6.0 * s)
            + m1 * (3.0 * s2 - 2.0 * s))
            / h;
        (pos, vel)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_keys_with_continuous_velocity() {
        let p = Path::new(&[
            [0.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 2.0, 0.0],
            [3.0, 2.0, 0.0, 1.0],
        ]);
        assert!((p.at(1.0).0 - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-12);
        assert!((p.at(0.0).0 - DVec3::ZERO).length() < 1e-12);
        let (a, b) = (p.at(1.0 - 1e-9).1, p.at(1.0 + 1e-9).1);
        assert!((a - b).length() < 1e-6);
        // Velocity is the derivative of position.
        let t = 1.7;
        let fd = (p.at(t + 1e-6).0 - p.at(t - 1e-6).0) / 2e-6;
        assert!((fd - p.at(t).1).length() < 1e-6);
        assert_eq!(p.at(5.0), (DVec3::new(2.0, 0.0, 1.0), DVec3::ZERO));
    }

    #[test]
    fn two_keys_move_at_constant_velocity() {
        let p = Path::new(&[[0.0, 0.0, 0.0, 0.0], [2.0, 4.0, 0.0, 0.0]]);
        for t in [0.1, 0.5, 1.0, 1.9] {
            let (pos, vel) = p.at(t);
            assert!((pos.x - 2.0 * t).abs() < 1e-12 && (vel.x - 2.0).abs() < 1e-12);
        }
    }
}
