// GLSL: what a pass over a voxel grid includes, in this order: the grid and its sampling, the
// atlas addressing of its slices, and the box exit (each its own chunk).

import { ATLAS_GLSL } from './atlas.js';
import { BOX_EXIT_GLSL } from './box-exit.js';
import { GRID_GLSL } from './grid.js';

/** `Grid`, `sampleVolume`, `atlasVoxel`, `atlasTexel`, `exitDistance`. */
export const VOXEL_GRID_GLSL = `\n${[GRID_GLSL, ATLAS_GLSL, BOX_EXIT_GLSL].map((chunk) => chunk.trim()).join('\n')}\n`;
