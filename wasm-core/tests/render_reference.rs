//! The reference renderer against a brute-force quadrature of the rendering model (docs/FORMATS.md), the closed-form
//! transparency of one blob, and the brute-force (no tree) blob search.

use glam::DVec3;
use serde_json::json;
use windfield::render::{psnr, RenderOptions, Renderer, TRUNCATION};
use windfield::scene::blob_list::{BlobList, Encoding, Object};
use windfield::{Scene, Simulation};

/// the rendering model (docs/FORMATS.md) by direct quadrature in f64: every blob untruncated, midpoint steps along the
/// primary ray, shadow transmittance by its own midpoint march towards each light, zero where
/// [`twin_blocked`] finds an object on the way.
fn twin(list: &BlobList) -> Vec<f64> {
    twin_with(list, true)
}

/// Where the twin's cylinder tests sample a segment inside the cylinder's bounding sphere.
const CYLINDER_SAMPLES: usize = 2000;

/// A closed cylinder in f64: base, unit axis, radius, height.
struct TwinCylinder {
    base: DVec3,
    axis: DVec3,
    radius: f64,
    height: f64,
}

impl TwinCylinder {
    fn of(base: [f32; 3], axis: [f32; 3], radius: f32, height: f32) -> Self {
        Self {
            base: DVec3::from_array(base.map(f64::from)),
            axis: DVec3::from_array(axis.map(f64::from)).normalize(),
            radius: radius as f64,
            height: height as f64,
        }
    }

    fn inside(&self, p: DVec3) -> bool {
        let along = (p - self.base).dot(self.axis);
        let radial = (p - self.base - self.axis * along).length();
        (0.0..=self.height).contains(&along) && radial <= self.radius
    }

    /// The part (t0, t1) of the line x + t·d inside the bounding sphere, if any.
    fn bounding_span(&self, x: DVec3, d: DVec3) -> Option<(f64, f64)> {
        let m = self.base + self.axis * (0.5 * self.height);
        let r2 = self.radius * self.radius + 0.25 * self.height * self.height;
        let tc = (m - x).dot(d);
        let miss2 = (x + d * tc - m).length_squared();
        (miss2 < r2).then(|| {
            let w = (r2 - miss2).sqrt();
            (tc - w, tc + w)
        })
    }

    /// The first point of x + t·d, 0 < t < t_max, inside the cylinder: sampled, then bisected.
    fn first_inside(&self, x: DVec3, d: DVec3, t_max: f64) -> Option<f64> {
        let (a, b) = self.bounding_span(x, d)?;
        let (a, b) = (a.max(0.0), b.min(t_max));
        if b <= a {
            return None;
        }
        let dt = (b - a) / CYLINDER_SAMPLES as f64;
        let k = (1..=CYLINDER_SAMPLES).find(|&k| self.inside(x + d * (a + dt * k as f64)))?;
        let (mut out, mut inn) = (a + dt * (k - 1) as f64, a + dt * k as f64);
        for _ in 0..60 {
            let mid = 0.5 * (out + inn);
            if self.inside(x + d * mid) {
                inn = mid;
            } else {
                out = mid;
            }
        }
        Some(inn)
    }

    /// The outward normal at a surface point: of the nearest of the side and the two caps.
    fn normal(&self, p: DVec3) -> DVec3 {
        let along = (p - self.base).dot(self.axis);
        let radial = p - self.base - self.axis * along;
        let side = (radial.length() - self.radius).abs();
        if side <= along.abs().min((along - self.height).abs()) {
            radial.normalize()
        } else if along.abs() < (along - self.height).abs() {
            -self.axis
        } else {
            self.axis
        }
    }
}

/// Whether an opaque object lies on the segment from `x` along unit `l` over (0, `len`) (`len`
/// ∞ for a directional light), found by other means than the renderer's: a sphere by the
/// segment's closest approach to its centre (from outside), a plane by the sides its two ends
/// lie on, a cylinder by sampling the segment for a point inside it (from outside).
fn twin_blocked(objects: &[Object], x: DVec3, l: DVec3, len: f64) -> bool {
    objects.iter().any(|obj| match obj {
        Object::Sphere { center, radius, .. } => {
            let c = DVec3::from_array(center.map(f64::from));
            let r = *radius as f64;
            let t = (c - x).dot(l).clamp(0.0, len);
            (x - c).length() > r && (x + l * t - c).length() < r
        }
        Object::Plane { point, normal, .. } => {
            let n = DVec3::from_array(normal.map(f64::from));
            let p = DVec3::from_array(point.map(f64::from));
            let start = n.dot(x - p);
            let end = if len.is_finite() {
                n.dot(x + l * len - p)
            } else {
                n.dot(l)
            };
            start * end < 0.0
        }
        Object::Cylinder {
            base,
            axis,
            radius,
            height,
            ..
        } => {
            let cyl = TwinCylinder::of(*base, *axis, *radius, *height);
            !cyl.inside(x) && cyl.first_inside(x, l, len).is_some()
        }
    })
}

/// [`twin`], with the objects' shadows (`object_shadows`) or without them (to show that a scene's
/// object shadows matter).
fn twin_with(list: &BlobList, object_shadows: bool) -> Vec<f64> {
    let (w, h) = (list.image.width, list.image.height);
    let cam = &list.camera;
    let o = DVec3::from_array(cam.position.map(f64::from));
    let fwd = (DVec3::from_array(cam.target.map(f64::from)) - o).normalize();
    let right = fwd
        .cross(DVec3::from_array(cam.up.map(f64::from)))
        .normalize();
    let up = right.cross(fwd);
    let th = (cam.fov_y_deg as f64).to_radians().mul_add(0.5, 0.0).tan();
    let kappa = DVec3::from_array(list.medium.extinction.rgb().map(f64::from));
    let medium_albedo = DVec3::from_array(list.medium.albedo.map(f64::from));
    let blobs: Vec<(DVec3, f64, f64, DVec3, DVec3)> = list
        .blobs
        .iter()
        .map(|b| {
            (
                DVec3::from_array(b.center.map(f64::from)),
                b.sigma as f64,
                b.mass as f64,
                b.albedo
                    .map_or(medium_albedo, |a| DVec3::from_array(a.map(f64::from))),
                b.emission
                    .map_or(DVec3::ZERO, |q| DVec3::from_array(q.map(f64::from))),
            )
        })
        .collect();
    let density = |x: DVec3, b: &(DVec3, f64, f64, DVec3, DVec3)| {
        b.2 / ((2.0 * std::f64::consts::PI).powf(1.5) * b.1.powi(3))
            * (-(x - b.0).length_squared() / (2.0 * b.1 * b.1)).exp()
    };
    let rho = |x: DVec3| blobs.iter().map(|b| density(x, b)).sum::<f64>();
    let far = |x: DVec3| {
        blobs
            .iter()
            .map(|b| (b.0 - x).length() + 8.0 * b.1)
            .fold(0.0, f64::max)
    };
    let shadow = |x: DVec3, l: DVec3, len: f64| -> DVec3 {
        if !list.shadows {
            return DVec3::ONE;
        }
        if object_shadows && twin_blocked(&list.objects, x, l, len) {
            return DVec3::ZERO;
        }
        let end = len.min(far(x));
        let n = 300;
        let ds = end / n as f64;
        let col: f64 = (0..n)
            .map(|i| rho(x + l * ((i as f64 + 0.5) * ds)) * ds)
            .sum();
        (-kappa * col).exp()
    };
    let lights: Vec<(Option<DVec3>, DVec3, DVec3)> = list
        .lights
        .iter()
        .map(|l| match l {
            windfield::scene::blob_list::Light::Point { position, color } => (
                Some(DVec3::from_array(position.map(f64::from))),
                DVec3::ZERO,
                DVec3::from_array(color.map(f64::from)),
            ),
            windfield::scene::blob_list::Light::Directional { direction, color } => (
                None,
                -DVec3::from_array(direction.map(f64::from)).normalize(),
                DVec3::from_array(color.map(f64::from)),
            ),
        })
        .collect();
    let towards = |x: DVec3, l: &(Option<DVec3>, DVec3, DVec3)| match l.0 {
        Some(p) => ((p - x).normalize(), (p - x).length()),
        None => (l.1, f64::INFINITY),
    };
    let phase = |cos: f64| match list.medium.phase {
        windfield::scene::blob_list::Phase::Isotropic {} => 1.0,
        windfield::scene::blob_list::Phase::HenyeyGreenstein { g } => {
            let g = g as f64;
            (1.0 - g * g) / (1.0 + g * g - 2.0 * g * cos).powf(1.5)
        }
    };
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let aspect = w as f64 / h as f64;
            let x = ((i as f64 + 0.5) / w as f64 * 2.0 - 1.0) * th * aspect;
            let y = (1.0 - (j as f64 + 0.5) / h as f64 * 2.0) * th;
            let d = (fwd + right * x + up * y).normalize();
            // Nearest opaque object.
            let mut hit: Option<(f64, DVec3, DVec3)> = None;
            for obj in &list.objects {
                let cand = match obj {
                    Object::Sphere {
                        center,
                        radius,
                        color,
                        ..
                    } => {
                        let c = DVec3::from_array(center.map(f64::from));
                        let oc = o - c;
                        let b = oc.dot(d);
                        let disc = b * b - (oc.length_squared() - (*radius as f64).powi(2));
                        (disc >= 0.0).then(|| {
                            let s = -b - disc.sqrt();
                            (
                                s,
                                (o + d * s - c).normalize(),
                                DVec3::from_array(color.map(f64::from)),
                            )
                        })
                    }
                    Object::Plane {
                        point,
                        normal,
                        color,
                        ..
                    } => {
                        let n = DVec3::from_array(normal.map(f64::from)).normalize();
                        let s = (DVec3::from_array(point.map(f64::from)) - o).dot(n) / d.dot(n);
                        Some((s, n, DVec3::from_array(color.map(f64::from))))
                    }
                    Object::Cylinder {
                        base,
                        axis,
                        radius,
                        height,
                        color,
                        ..
                    } => {
                        let cyl = TwinCylinder::of(*base, *axis, *radius, *height);
                        cyl.first_inside(o, d, f64::INFINITY).map(|s| {
                            (
                                s,
                                cyl.normal(o + d * s),
                                DVec3::from_array(color.map(f64::from)),
                            )
                        })
                    }
                };
                if let Some(c) = cand {
                    if c.0 > 1e-4 && hit.is_none_or(|h| c.0 < h.0) {
                        hit = Some(c);
                    }
                }
            }
            let end = hit.map_or(far(o), |h| h.0);
            let n = 600;
            let ds = end / n as f64;
            let mut t = DVec3::ONE;
            let mut rad = DVec3::ZERO;
            for k in 0..n {
                let p = o + d * ((k as f64 + 0.5) * ds);
                let dens: Vec<f64> = blobs.iter().map(|b| density(p, b)).collect();
                let total: f64 = dens.iter().sum();
                if total < 1e-12 {
                    continue;
                }
                let mut l_in = DVec3::ZERO;
                for l in &lights {
                    let (dir_l, len) = towards(p, l);
                    l_in += l.2 * shadow(p, dir_l, len) * phase(d.dot(dir_l));
                }
                let mut c = DVec3::ZERO;
                for (b, r) in blobs.iter().zip(&dens) {
                    c += (b.3 * l_in + (DVec3::ONE - b.3) * b.4) * *r;
                }
                c /= total;
                let a = DVec3::ONE - (-kappa * total * ds).exp();
                rad += t * a * c;
                t *= DVec3::ONE - a;
            }
            match hit {
                Some((s, n, color)) => {
                    let n = if n.dot(d) > 0.0 { -n } else { n };
                    // Just off the surface, on the side the ray came from.
                    let p = o + d * s + n * 1e-6;
                    let mut lam = DVec3::ZERO;
                    for l in &lights {
                        let (dir_l, len) = towards(p, l);
                        lam += l.2 * shadow(p, dir_l, len) * n.dot(dir_l).max(0.0);
                    }
                    rad += t * color * lam;
                }
                None => rad += t * DVec3::from_array(list.background.radiance().map(f64::from)),
            }
            out.extend_from_slice(&rad.to_array());
        }
    }
    out
}

fn encode(data: &[f64], enc: Encoding) -> Vec<u8> {
    let img = windfield::render::LinearImage {
        width: 0,
        height: 0,
        data: data.iter().map(|&v| v as f32).collect(),
        alpha: None,
    };
    img.to_rgb8(enc)
}

fn list(v: serde_json::Value) -> BlobList {
    BlobList::from_value(v).unwrap()
}

fn blobs() -> serde_json::Value {
    json!([
        {"center": [0.0, 0.0, 0.0], "sigma": 0.25, "mass": 0.6},
        {"center": [0.35, 0.2, -0.1], "sigma": 0.18, "mass": 0.3, "albedo": [0.9, 0.6, 0.3]},
        {"center": [-0.4, -0.1, 0.2], "sigma": 0.3, "mass": 0.5},
        {"center": [0.1, 0.45, 0.3], "sigma": 0.12, "mass": 0.15, "albedo": [0.3, 0.8, 0.9]},
        {"center": [-0.2, -0.4, -0.3], "sigma": 0.2, "mass": 0.4}
    ])
}

fn base(extra: serde_json::Value) -> serde_json::Value {
    let mut v = json!({
        "camera": {"position": [0, 0.3, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40},
        "image": {"width": 24, "height": 18, "encoding": "srgb"},
        "medium": {"extinction": 4, "albedo": [0.9, 0.9, 0.9], "phase": {"type": "isotropic"}},
        "lights": [{"type": "directional", "direction": [-0.5, -1, -0.4], "color": [1, 1, 1]}],
        "shadows": false, "background": [0.1, 0.12, 0.2], "objects": [], "blobs": blobs()
    });
    v.as_object_mut()
        .unwrap()
        .extend(extra.as_object().unwrap().clone());
    v
}

fn compare(name: &str, v: serde_json::Value) {
    let l = list(v);
    let ours = Renderer::new(&l, None, RenderOptions::default())
        .unwrap()
        .render();
    let a = ours.to_rgb8(l.image.encoding);
    let b = encode(&twin(&l), l.image.encoding);
    let p = psnr(&a, &b);
    eprintln!("{name}: PSNR {p:.1} dB against the brute-force twin");
    assert!(
        p >= 40.0,
        "{name}: PSNR {p:.1} dB against the brute-force twin"
    );
    // The scene is not trivially flat.
    let spread =
        a.iter().map(|&x| x as i32).max().unwrap() - a.iter().map(|&x| x as i32).min().unwrap();
    assert!(spread > 40, "{name}: image too flat to test anything");
}

#[test]
fn plain_matches_the_twin() {
    compare("plain", base(json!({})));
}

#[test]
fn shadowed_matches_the_twin() {
    compare(
        "shadowed",
        base(json!({
            "shadows": true,
            "lights": [{"type": "point", "position": [1.5, 2, 1], "color": [1.5, 1.4, 1.3]}]
        })),
    );
}

#[test]
fn henyey_greenstein_with_two_lights_matches_the_twin() {
    compare(
        "hg",
        base(json!({
            "shadows": true,
            "medium": {"extinction": [3, 4, 6], "albedo": [0.95, 0.9, 0.85], "phase": {"type": "henyey-greenstein", "g": 0.5}},
            "lights": [{"type": "point", "position": [-1, 1.5, -2], "color": [1.2, 1, 0.8]},
                       {"type": "directional", "direction": [0.3, -1, -0.6], "color": [0.3, 0.4, 0.6]}]
        })),
    );
}

#[test]
fn emissive_matches_the_twin() {
    let mut b = blobs();
    for (k, blob) in b.as_array_mut().unwrap().iter_mut().enumerate() {
        let o = blob.as_object_mut().unwrap();
        o.insert("albedo".into(), json!([0.0, 0.0, 0.0]));
        o.insert(
            "emission".into(),
            json!(
                [
                    [1.0, 0.4, 0.1],
                    [0.2, 0.9, 0.3],
                    [0.3, 0.3, 1.0],
                    [1.0, 1.0, 1.0],
                    [0.8, 0.1, 0.6]
                ][k]
            ),
        );
    }
    b.as_array_mut().unwrap()[2]
        .as_object_mut()
        .unwrap()
        .insert("albedo".into(), json!([0.8, 0.8, 0.8]));
    compare(
        "emissive",
        base(
            json!({"blobs": b, "background": [0, 0, 0], "medium": {"extinction": 6, "albedo": [0.5, 0.5, 0.5], "phase": {"type": "isotropic"}}}),
        ),
    );
}

#[test]
fn opaque_objects_match_the_twin() {
    compare(
        "objects",
        base(json!({
            "shadows": true,
            "lights": [{"type": "point", "position": [1, 2.5, 1.5], "color": [1.3, 1.3, 1.3]}],
            "objects": [{"type": "sphere", "center": [0.7, -0.3, -0.6], "radius": 0.35, "color": [0.8, 0.3, 0.2]},
                        {"type": "plane", "point": [0, -0.7, 0], "normal": [0, 1, 0], "color": [0.6, 0.6, 0.6]}]
        })),
    );
}

/// [`compare`], and the objects' shadows matter in the scene: the twin without them is far from
/// the twin with them, so a renderer that ignored them would fail the comparison.
fn compare_shadowed(name: &str, v: serde_json::Value) {
    let l = list(v.clone());
    let with = encode(&twin(&l), l.image.encoding);
    let without = encode(&twin_with(&l, false), l.image.encoding);
    let p = psnr(&with, &without);
    eprintln!("{name}: the twin without the objects' shadows is {p:.1} dB from the twin with them");
    assert!(
        p < 30.0,
        "{name}: the objects' shadows hardly show ({p:.1} dB)"
    );
    compare(name, v);
}

#[test]
fn a_sphere_shadows_the_gas_and_the_floor() {
    // A sphere between a point light and the gas; the floor beneath catches both shadows.
    compare_shadowed(
        "sphere over gas",
        base(json!({
            "shadows": true,
            "medium": {"extinction": 2.5, "albedo": [0.9, 0.9, 0.9], "phase": {"type": "isotropic"}},
            "lights": [{"type": "point", "position": [1.2, 2.6, 1.4], "color": [1.5, 1.4, 1.3]}],
            "objects": [{"type": "sphere", "center": [0.45, 1.0, 0.55], "radius": 0.28, "color": [0.8, 0.3, 0.2]},
                        {"type": "plane", "point": [0, -0.75, 0], "normal": [0, 1, 0], "color": [0.7, 0.7, 0.7]}]
        })),
    );
}

#[test]
fn objects_shadow_each_other_and_the_gas_under_a_directional_light() {
    // A sphere hovering over the floor and a cylinder standing on it, the gas beside them, a low
    // sun: the sphere shadows the floor, the cylinder the floor and the gas behind it.
    let gas = json!([
        {"center": [0.45, -0.25, -0.55], "sigma": 0.2, "mass": 0.12},
        {"center": [0.75, -0.1, -0.4], "sigma": 0.15, "mass": 0.06, "albedo": [0.9, 0.6, 0.3]},
        {"center": [0.3, 0.1, -0.7], "sigma": 0.25, "mass": 0.1}
    ]);
    compare_shadowed(
        "sphere and cylinder on a floor",
        base(json!({
            "shadows": true,
            "blobs": gas,
            "camera": {"position": [0, 0.9, 3], "target": [0, -0.2, 0], "up": [0, 1, 0], "fov_y_deg": 45},
            "lights": [{"type": "directional", "direction": [0.8, -0.7, -0.5], "color": [1.3, 1.25, 1.2]}],
            "objects": [{"type": "sphere", "center": [-0.6, -0.1, 0.3], "radius": 0.25, "color": [0.3, 0.5, 0.8]},
                        {"type": "cylinder", "base": [-0.15, -0.6, -0.35], "axis": [0, 1, 0], "radius": 0.15, "height": 0.7, "color": [0.8, 0.4, 0.3]},
                        {"type": "plane", "point": [0, -0.6, 0], "normal": [0, 1, 0], "color": [0.6, 0.6, 0.55]}]
        })),
    );
}

#[test]
fn single_blob_transparency_is_the_closed_form() {
    let (sigma, mass, kappa) = (0.3f64, 0.8f64, 2.0f64);
    let l = list(json!({
        "camera": {"position": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 30},
        "image": {"width": 33, "height": 33, "encoding": "linear"},
        "medium": {"extinction": kappa, "albedo": [0, 0, 0]},
        "lights": [], "shadows": false, "background": [1, 1, 1], "objects": [],
        "blobs": [{"center": [0, 0, 0], "sigma": sigma, "mass": mass}]
    }));
    let r = Renderer::new(&l, None, RenderOptions::default()).unwrap();
    let rays = windfield::render::CameraRays::new(&l.camera, 33, 33);
    for (i, j) in [(16, 16), (20, 16), (16, 25), (3, 7), (28, 30)] {
        let d = rays.direction(i, j).as_dvec3();
        let o = DVec3::new(0.0, 0.0, 4.0);
        let s_mid = -o.dot(d);
        let r2 = (o + d * s_mid).length_squared();
        // Chord through the truncation sphere: m/(4πσ²)·e^{−r²/2σ²}·2 erf(h/(σ√2)).
        let radius = TRUNCATION as f64 * sigma;
        let h = (radius * radius - r2).max(0.0).sqrt();
        let column = mass / (4.0 * std::f64::consts::PI * sigma * sigma)
            * (-r2 / (2.0 * sigma * sigma)).exp()
            * 2.0
            * libm::erf(h / (sigma * std::f64::consts::SQRT_2));
        let expected = (-kappa * column).exp();
        let got = r.radiance(o.as_vec3(), d.as_vec3()).x as f64;
        assert!(
            (got - expected).abs() < 2e-6,
            "pixel ({i},{j}): {got} vs {expected}"
        );
        // And the untruncated Gaussian, m/(2πσ²)·e^{−r²/2σ²}, within the truncation's share.
        let full = (-kappa * mass / (2.0 * std::f64::consts::PI * sigma * sigma)
            * (-r2 / (2.0 * sigma * sigma)).exp())
        .exp();
        assert!(
            (got - full).abs() < 2e-3,
            "pixel ({i},{j}): {got} vs untruncated {full}"
        );
    }
}

#[test]
fn the_tree_and_brute_force_give_the_same_image() {
    let scene = Scene::from_value(json!({
        "version": 1, "seed": 5,
        "field": {"size": [16, 16, 16, 16], "period": [1.5, 1.5, 1.5], "amplitude": 1},
        "wind": [{"type": "uniform", "velocity": [0, 0.4, 0]}],
        "emitters": [{"shape": "disk", "radius": 0.1, "rate": 150, "sigma0": 0.03, "mass0": 0.05}],
        "gas": {"diffusion": 0.002, "dissipation": 0.1},
        "render": {"camera": {"position": [0, 0.8, 2.5], "target": [0, 0.8, 0], "up": [0, 1, 0], "fov_y_deg": 45},
                   "image": {"width": 48, "height": 36},
                   "medium": {"extinction": 10},
                   "lights": [{"type": "point", "position": [1, 2, 1], "color": [1, 1, 1]}], "shadows": true}
    }))
    .unwrap();
    let mut sim = Simulation::new(scene).unwrap();
    sim.run(240);
    let l = sim.blob_list();
    assert!(l.blobs.len() > 300);
    let tree = Renderer::new(&l, None, RenderOptions::default())
        .unwrap()
        .render();
    let brute = Renderer::new(
        &l,
        None,
        RenderOptions {
            use_tree: false,
            ..Default::default()
        },
    )
    .unwrap()
    .render();
    let worst = tree
        .data
        .iter()
        .zip(&brute.data)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-5, "largest difference {worst}");
    assert!(tree.data.iter().any(|&v| v > 0.2));
}
