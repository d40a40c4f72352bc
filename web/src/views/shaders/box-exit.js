// GLSL: leaving a box along a ray (`frame::light_volume::exit_distance` in the core).

/** `exitDistance(x, d, lo, hi)`: distance from x (inside the box) along unit d to its boundary. */
export const BOX_EXIT_GLSL = /* glsl */ `
// Distance from x (inside the box) along unit d to the box's boundary.
float exitDistance(vec3 x, vec3 d, vec3 lo, vec3 hi) {
  vec3 far = mix(lo, hi, step(vec3(0.0), d));
  vec3 t = (far - x) / d;
  t = mix(t, vec3(1e30), equal(d, vec3(0.0)));
  return max(min(t.x, min(t.y, t.z)), 0.0);
}
`;
