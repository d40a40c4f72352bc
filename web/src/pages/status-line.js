// The playground's status line, in words: the simulated time and the blobs, the frames drawn
// per second and what limits them, the step's time, the field's synthesis, and the real-time
// view's resolution and volume.

const LIMITS = {
  worker: 'limited by the worker’s step',
  view: 'limited by drawing the view',
  display: 'as fast as the display',
  paused: 'paused',
};

/**
 * The status text for `stats` (the player's `stats()`) in view `mode`, with the real-time
 * view's volume (`[nx, ny, nz]` voxels, or null) and whether the pointer stirs.
 */
export function statusText(stats, { mode, volume = null, stirring = false }) {
  const parts = [
    `t = ${stats.time.toFixed(2)} s`,
    `${stats.blobs.toLocaleString('en')} blobs`,
    `${Math.round(stats.fps)} fps (${LIMITS[stats.limitedBy] ?? stats.limitedBy})`,
    `step ${stats.stepMs.toFixed(2)} ms (${stats.stepper === 'gpu' ? 'GPU' : `worker${stats.stepperReason ? `: ${stats.stepperReason}` : ''}`})`,
    `field ${stats.fieldMs.toFixed(0)} ms`,
  ];
  if (mode !== 'points') parts.push(`resolution ${Math.round(stats.scale * 100)} %`);
  if (volume) parts.push(`volume ${volume.join('×')}`);
  if (stirring) parts.push('stirring: drag over the view');
  return parts.join(' · ');
}
