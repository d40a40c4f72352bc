//! The solid objects as the wind and the gas meet them ([`crate::scene::bodies`]: each a
//! closed region of space with a signed distance d(x), negative inside, and an outward normal
//! n(x) = ∇d).
//!
//! [`Solids`] finds the solid nearest to a point within the layer and the solids whose wind
//! reaches a point (a uniform grid over the finite solids, [`SolidGrid`], so a point costs a
//! cell lookup and the few solids that can matter in the cell; planes, which reach everywhere,
//! are always tested) and puts points that ended inside a solid back on its surface, just
//! outside.

use crate::scene::bodies::Body;
use crate::wind::solid_grid::SolidGrid;
use glam::Vec3A;

/// The nearest solid to a point: its index, the signed distance d (m) and the normal there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nearest {
    pub index: usize,
    pub distance: f32,
    pub normal: Vec3A,
}

/// The lists of one grid cell: the finite solids whose layer may hold a point of it, and the
/// spheres and the other solids whose wind may reach one beyond their layer, each in the
/// scene's order.
#[derive(Debug, Clone, Copy, Default)]
pub struct Around<'a> {
    pub layers: &'a [u32],
    pub spheres: &'a [u32],
    pub others: &'a [u32],
}

impl Around<'_> {
    /// Whether any solid but `index` reaches the cell.
    #[inline]
    pub fn any_but(&self, index: usize) -> bool {
        let listed = |l: &[u32]| l.contains(&(index as u32)) as usize;
        self.spheres.len() + self.others.len() > listed(self.spheres) + listed(self.others)
    }
}

/// The scene's solids, with a uniform grid over the finite ones ([`SolidGrid`]).
#[derive(Debug, Clone, Default)]
pub struct Solids {
    pub bodies: Vec<Body>,
    /// The rounding of each solid's edges the wind sees ([`Body::rounded_distance`]).
    pub edges: Vec<f32>,
    /// The layer's width (m): how far from a solid [`Self::nearest`] looks.
    layer: f32,
    /// The most by which a rounded distance exceeds the true one (m): the largest rounding of
    /// an edge ([`Body::rounded_distance`]).
    slack: f32,
    /// Indices of the planes, tested at every point.
    planes: Vec<u32>,
    /// Without the grid (none): the finite solids, and the spheres and other solids whose wind
    /// reaches beyond their layer, every one visited at every point.
    grid: Option<SolidGrid>,
    finite: Vec<u32>,
    spheres: Vec<u32>,
    others: Vec<u32>,
}

impl Solids {
    /// The solid objects `bodies` with a layer `layer` metres wide over each (within it a
    /// point has a nearest solid), whose wind reaches `reach[i]` metres from solid i (none:
    /// no farther than its layer).
    pub fn new(bodies: Vec<Body>, layer: f32, reach: &[Option<f32>]) -> Self {
        let edges = vec![0.0; bodies.len()];
        Self::with_edges(bodies, edges, layer, reach)
    }

    /// [`Self::new`] with the wind seeing each solid's edges rounded by `edges[i]` (m).
    pub fn with_edges(
        bodies: Vec<Body>,
        edges: Vec<f32>,
        layer: f32,
        reach: &[Option<f32>],
    ) -> Self {
        let plane = |b: &Body| matches!(b, Body::Plane { .. });
        let sphere = |b: &Body| matches!(b, Body::Sphere { .. });
        let indices = |keep: &dyn Fn(usize) -> bool| -> Vec<u32> {
            (0..bodies.len())
                .filter(|&i| keep(i))
                .map(|i| i as u32)
                .collect()
        };
        Self {
            planes: indices(&|i| plane(&bodies[i])),
            finite: indices(&|i| !plane(&bodies[i])),
            spheres: indices(&|i| sphere(&bodies[i]) && reach[i].is_some()),
            others: indices(&|i| !sphere(&bodies[i]) && !plane(&bodies[i]) && reach[i].is_some()),
            grid: Some(SolidGrid::new(&bodies, layer, reach)),
            layer,
            slack: edges.iter().copied().fold(0.0, f32::max),
            bodies,
            edges,
        }
    }

    /// The same solids without the grid: every solid visited at every point. What the grid
    /// must find, for checks of it.
    pub fn every_solid_visited(&self) -> Self {
        Self {
            grid: None,
            ..self.clone()
        }
    }

    /// The grid and the planes as the GPU stepper reads them ([`SolidGrid::write_gpu`]); an
    /// empty grid (no cells) without it.
    pub fn write_gpu_grid(&self, out: &mut Vec<f32>) {
        let none = SolidGrid::default();
        self.grid
            .as_ref()
            .unwrap_or(&none)
            .write_gpu(&self.planes, out);
    }

    /// The grid's cells and the entries of their lists (none without the grid).
    pub fn grid_size(&self) -> Option<(usize, usize)> {
        self.grid.as_ref().map(SolidGrid::size)
    }

    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// The lists of the grid cell holding `x` (every solid's without the grid).
    #[inline(always)]
    pub fn around(&self, x: Vec3A) -> Around<'_> {
        match &self.grid {
            None => Around {
                layers: &self.finite,
                spheres: &self.spheres,
                others: &self.others,
            },
            Some(g) => g.cell(x).map_or(Around::default(), |c| {
                let [layers, spheres, others] = g.lists(c);
                Around {
                    layers,
                    spheres,
                    others,
                }
            }),
        }
    }

    /// The solid with the smallest signed distance from `x` (edges rounded as the wind sees
    /// them) among those closer than the layer's width, or none.
    #[inline]
    pub fn nearest(&self, x: Vec3A) -> Option<Nearest> {
        self.nearest_among(self.around(x).layers, x)
    }

    /// [`Self::nearest`] among the finite solids `layers` (those of `x`'s cell) and the planes.
    #[inline(always)]
    pub fn nearest_among(&self, layers: &[u32], x: Vec3A) -> Option<Nearest> {
        let mut best: Option<Nearest> = None;
        for &i in layers.iter().chain(&self.planes) {
            let i = i as usize;
            if self.bodies[i].surely_beyond(x, self.layer) {
                continue;
            }
            let (d, n) = self.bodies[i].rounded_distance(x, self.edges[i]);
            if d < self.layer && best.is_none_or(|b| d < b.distance) {
                best = Some(Nearest {
                    index: i,
                    distance: d,
                    normal: n,
                });
            }
        }
        best
    }

    /// A lower bound (m) on the true distance from `x` to every solid, from the rounded
    /// distance `nearest` of the nearest solid within the layer there ([`Self::nearest_among`]
    /// over the lists of `x`'s cell; none: every solid lies a layer's width away or more, as
    /// the grid lists each solid wherever its layer may reach). A rounded edge lies within its
    /// rounding of the true one; a margin covers the distances' rounding. Zero or less: no
    /// bound.
    #[inline(always)]
    pub fn clearance(&self, nearest: Option<f32>, x: Vec3A) -> f32 {
        let d = nearest.map_or(self.layer, |d| d.min(self.layer));
        (d - self.slack) * 0.999 - 1e-6 * (1.0 + x.abs().max_element())
    }

    /// The most by which a rounded distance exceeds the true one (m): the largest rounding of
    /// an edge, which [`Self::clearance`] takes off.
    pub fn slack(&self) -> f32 {
        self.slack
    }

    /// [`Self::push_out`] for the end `x1` of a move from `x0`, which lay at least `clear` (m,
    /// [`Self::clearance`]) from every solid: a move shorter than that cannot end inside one
    /// (the distance changes by no more than the point moves), so `x1` is kept as it is.
    #[inline(always)]
    pub fn push_out_after(&self, x0: Vec3A, clear: f32, x1: Vec3A, gap: f32) -> Vec3A {
        if clear > 0.0 && (x1 - x0).length_squared() < clear * clear {
            x1
        } else {
            self.push_out(x1, gap)
        }
    }

    /// Whether `x` lies inside a solid (d < 0).
    #[inline(always)]
    pub fn inside(&self, x: Vec3A) -> Option<usize> {
        self.around(x)
            .layers
            .iter()
            .chain(&self.planes)
            .map(|&i| i as usize)
            .find(|&i| !self.bodies[i].surely_beyond(x, 0.0) && self.bodies[i].distance(x).0 < 0.0)
    }

    /// `x` put back on the surface, `gap` metres outside, if it lies inside a solid; else `x`.
    /// A point pushed out of one solid into another is pushed again (at most four times, for
    /// solids that overlap). Where overlapping solids send it back and forth (a mug's base
    /// sunk in the floor), it leaves them all by the shortest of seven ways: along the last
    /// normal or an axis, in steps growing by a quarter from `gap`.
    #[inline]
    pub fn push_out(&self, mut x: Vec3A, gap: f32) -> Vec3A {
        let start = x;
        let mut normal = Vec3A::Y;
        for _ in 0..4 {
            let Some(i) = self.inside(x) else {
                return x;
            };
            let (d, n) = self.bodies[i].distance(x);
            // The gap grows with the coordinates' size so the step survives rounding.
            let g = gap + 4.0 * f32::EPSILON * x.abs().max_element();
            x += n * (g - d);
            normal = n;
        }
        if self.inside(x).is_none() {
            return x;
        }
        let ways = [
            normal,
            Vec3A::X,
            Vec3A::NEG_X,
            Vec3A::Y,
            Vec3A::NEG_Y,
            Vec3A::Z,
            Vec3A::NEG_Z,
        ];
        let mut t = gap.max(1e-4);
        while t < 1e3 {
            if let Some(y) = ways
                .iter()
                .map(|&w| start + w * t)
                .find(|&y| self.inside(y).is_none())
            {
                return y;
            }
            t *= 1.25;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::rand_core::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    #[test]
    fn the_grid_finds_what_a_search_of_every_solid_finds() {
        let mut bodies = Vec::new();
        for i in 0..60 {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 6.0 - 3.0;
            let c = Vec3A::new(f(0.7548777), f(0.5698403), f(0.4301597));
            bodies.push(if i % 2 == 0 {
                Body::Sphere {
                    center: c,
                    radius: 0.05 + 0.002 * i as f32,
                }
            } else {
                Body::Cylinder {
                    base: c,
                    axis: Vec3A::new(0.3, 1.0, -0.2).normalize(),
                    radius: 0.08,
                    height: 0.3,
                }
            });
        }
        bodies.push(Body::Plane {
            point: Vec3A::new(0.0, -3.5, 0.0),
            normal: Vec3A::Y,
        });
        let layer = 0.25;
        // Every third solid's wind ends with its layer; the others reach 2–8 times as far.
        let reach: Vec<Option<f32>> = (0..bodies.len())
            .map(|i| (i % 3 != 0).then_some(layer * (2.0 + (i % 7) as f32)))
            .collect();
        let solids = Solids::new(bodies.clone(), layer, &reach);
        let (cells, _) = solids.grid_size().expect("a grid");
        assert!(cells > 1000, "{cells} cells");
        for i in 0..20_000 {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 8.0 - 4.0;
            let x = Vec3A::new(f(0.1234567), f(0.7654321), f(0.3141592));
            let brute = (0..bodies.len())
                .map(|j| (j, bodies[j].distance(x).0))
                .filter(|&(_, d)| d < layer)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(j, _)| j);
            assert_eq!(solids.nearest(x).map(|n| n.index), brute, "at {x}");
            // Every solid whose wind reaches x is listed, in the scene's order, the spheres
            // apart.
            let around = solids.around(x);
            for listed in [around.spheres, around.others] {
                assert!(listed.windows(2).all(|w| w[0] < w[1]), "at {x}");
            }
            for (j, r) in reach.iter().enumerate() {
                let reaches = r.is_some_and(|r| bodies[j].distance(x).0 < r);
                let list = match bodies[j] {
                    Body::Sphere { .. } => around.spheres,
                    _ => around.others,
                };
                assert!(!reaches || list.contains(&(j as u32)), "{j} at {x}");
            }
        }
    }

    #[test]
    fn points_inside_are_put_just_outside() {
        let solids = Solids::new(
            vec![
                Body::Cylinder {
                    base: Vec3A::ZERO,
                    axis: Vec3A::Y,
                    radius: 0.4,
                    height: 0.9,
                },
                Body::Plane {
                    point: Vec3A::ZERO,
                    normal: Vec3A::Y,
                },
            ],
            0.1,
            &[None, None],
        );
        for x in [
            Vec3A::new(0.1, 0.85, 0.0),
            Vec3A::new(0.39, 0.5, 0.01),
            Vec3A::new(1.0, -0.2, 0.0),
            Vec3A::new(0.3, 0.01, 0.0),
        ] {
            let y = solids.push_out(x, 1e-5);
            assert!(solids.inside(y).is_none(), "{x} → {y}");
            assert!((y - x).length() < 0.2 + 1e-3, "{x} → {y}");
        }
    }

    /// A move shorter than the clearance never ends inside a solid: [`Solids::push_out_after`]
    /// gives what [`Solids::push_out`] gives, for moves up to twice the clearance from points
    /// in and beyond the layers, by spheres, a plane and a cylinder whose rims the wind sees
    /// rounded (there the rounded distance exceeds the true one).
    #[test]
    fn a_move_within_the_clearance_never_ends_inside() {
        let cylinder = Body::Cylinder {
            base: Vec3A::new(0.5, 0.0, 0.0),
            axis: Vec3A::Y,
            radius: 0.3,
            height: 0.6,
        };
        let mut bodies = vec![cylinder];
        for i in 0..12 {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 2.0 - 1.0;
            bodies.push(Body::Sphere {
                center: Vec3A::new(f(0.7548777) - 0.5, 0.5 + 0.5 * f(0.5698403), f(0.4301597)),
                radius: 0.05 + 0.01 * i as f32,
            });
        }
        bodies.push(Body::Plane {
            point: Vec3A::ZERO,
            normal: Vec3A::Y,
        });
        let (layer, edge, gap) = (0.1, 0.04, 1e-5);
        let mut edges = vec![0.0; bodies.len()];
        edges[0] = edge;
        let solids = Solids::with_edges(bodies, edges, layer, &[None; 14]);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        // Uniform in [0, 1), as the gas draws (the top 24 bits of a draw).
        let mut u = || (rng.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32);
        let mut kept = 0;
        for _ in 0..50_000 {
            let x0 = Vec3A::new(3.0 * u() - 1.5, 1.6 * u() - 0.1, 3.0 * u() - 1.5);
            let nearest = solids.nearest(x0).map(|n| n.distance);
            let clear = solids.clearance(nearest, x0);
            let dir = Vec3A::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize_or(Vec3A::Y);
            let x1 = x0 + dir * (2.0 * clear.max(0.02) * u());
            assert_eq!(
                solids.push_out_after(x0, clear, x1, gap),
                solids.push_out(x1, gap),
                "{x0} → {x1}, clearance {clear}"
            );
            kept += (clear > 0.0 && (x1 - x0).length() < clear) as usize;
        }
        assert!(kept > 10_000, "{kept} moves within the clearance");
        // Just outside the cylinder's top rim, on the diagonal: the rounded distance exceeds
        // the true one by (√2 − 1) times the rounding, and a move straight at the rim by less
        // than the rounded distance ends inside.
        let out = Vec3A::new(1.0, 1.0, 0.0).normalize();
        let rim = Vec3A::new(0.8, 0.6, 0.0);
        let x0 = rim + out * 0.05;
        let rounded = solids.nearest(x0).expect("in the layer").distance;
        assert!(rounded > 0.05 + 0.4 * edge, "{rounded}");
        let x1 = rim - out * 0.005;
        assert!(solids.inside(x1).is_some());
        let clear = solids.clearance(Some(rounded), x0);
        assert_ne!(solids.push_out_after(x0, clear, x1, gap), x1);
    }
}
