// GLSL: the error function, for the exact line and voxel integrals of a Gaussian blob (the
// direct splat's voxel averages, the exact march's chords).

/** `erf1(x)`: erf by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7). */
export const ERF_GLSL = /* glsl */ `
float erf1(float x) {
  float s = sign(x);
  x = abs(x);
  float t = 1.0 / (1.0 + 0.3275911 * x);
  float y = 1.0 - (((((1.061405429 * t - 1.453152027) * t) + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t * exp(-x * x);
  return s * y;
}
`;
