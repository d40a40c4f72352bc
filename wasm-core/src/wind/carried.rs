//! Turbulence carried by the large scales (paper §7: "warp the domain of the turbulent scale
//! according to the large scales"), as Neyret's advected textures (SCA 2003).
//!
//! The small-scale field is sampled at coordinates X that the large-scale wind u_l (deflected
//! by the solids) advects: ∂X/∂t + u_l·∇X = 0, X = x at a reset. Advected coordinates drift and
//! distort without bound, so there are two phases, a and b, each reset every `carry_time` T_c,
//! b half a period after a. Phase a's weight is w = 1 − |1 − 2 τ_a/T_c| (τ_a its age: 0 at its
//! reset, 1 half a period later), phase b's 1 − w, and the blend is
//!
//!   u_s = (w u(X_a) + (1 − w) u(X_b + L/2)) / √(w² + (1 − w)²),
//!
//! so a phase is invisible when it resets. Phase b samples the field displaced by half its
//! period L on every axis: the two samples are then independent draws of the same statistics
//! even where the gas is at rest (X_a = X_b), and the factor keeps the field's energy exactly.
//!
//! Each blob carries its coordinates as offsets o = X − x (m), two vectors. Along the blob's
//! path dX/dt = (u − u_l)·∇X ≈ u − u_l (∇X ≈ I while a phase is young): X moves with the
//! blob's own and small-scale motion, and the offsets against the large-scale wind,
//! o ← o − u_l dt (u_l at the RK2 midpoint). A blob moving with the large-scale wind keeps its
//! X. At a phase's reset, and for a newborn, o = −u_l(x)·τ (the point the large-scale wind
//! brought there since the reset, to first order). Where no blob is (the wind command, the
//! wind slice), X is found by tracing x back through u_l to the reset.

use glam::Vec3A;

/// The blend of the two phases at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blend {
    /// The weights of phase a and b, divided by √(w² + (1 − w)²).
    pub weights: [f32; 2],
    /// Phase b's displacement, half the field's period on every axis (m).
    pub shift: Vec3A,
}

/// The two phases' settings: the reset period T_c (s) and half the field's period (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Phases {
    pub period: f64,
    pub shift: Vec3A,
}

impl Phases {
    /// The ages τ_a, τ_b (s) of the two phases at time `t`: phase a resets at k·T_c, b at
    /// (k + ½)·T_c.
    pub fn ages(&self, t: f64) -> [f64; 2] {
        let tc = self.period;
        let a = t - tc * (t / tc).floor();
        let b = t - tc * ((t / tc - 0.5).floor() + 0.5);
        [a, b]
    }

    /// The reset counts of the two phases at time `t` (a reset happened in a step when they
    /// change).
    pub fn resets(&self, t: f64) -> [i64; 2] {
        let s = t / self.period;
        [s.floor() as i64, (s - 0.5).floor() as i64]
    }

    /// The blend at time `t`.
    pub fn blend(&self, t: f64) -> Blend {
        let tau = self.ages(t)[0] / self.period;
        let w = (1.0 - (1.0 - 2.0 * tau).abs()).clamp(0.0, 1.0) as f32;
        let norm = 1.0 / (w * w + (1.0 - w) * (1.0 - w)).sqrt();
        Blend {
            weights: [w * norm, (1.0 - w) * norm],
            shift: self.shift,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_phase_is_invisible_at_its_reset_and_the_blend_keeps_the_energy() {
        let p = Phases {
            period: 2.0,
            shift: Vec3A::ONE,
        };
        for k in 0..200 {
            let t = 0.013 * k as f64;
            let [a, b] = p.ages(t);
            assert!((0.0..2.0).contains(&a) && (0.0..2.0).contains(&b), "{t}");
            assert!(
                ((a - b).abs() - 1.0).abs() < 1e-9,
                "{t}: half a period apart"
            );
            let [wa, wb] = p.blend(t).weights;
            // Independent samples of equal energy: (wa² + wb²)·E = E.
            assert!((wa * wa + wb * wb - 1.0).abs() < 1e-6);
        }
        assert_eq!(p.blend(0.0).weights[0], 0.0);
        assert_eq!(p.blend(1.0).weights[1], 0.0);
        assert_eq!(p.resets(1.99), [0, 0]);
        assert_eq!(p.resets(2.0), [1, 0]);
        assert_eq!(p.resets(3.0), [1, 1]);
    }
}
