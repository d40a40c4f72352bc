// The playground's status line, in words: the simulated time and the blobs, the frames drawn
// per second and what limits them, the step's time, the flow's step where the scene has a flow,
// the field's synthesis, and the real-time view's resolution and volume.

const LIMITS = {
  worker: 'limited by the worker’s step',
  view: 'limited by drawing the view',
  display: 'as fast as the display',
  paused: 'paused',
};

/** Frames a second as the status line shows them: one decimal below 10 (0.2 stays 0.2), whole above. */
function fpsText(fps) {
  return fps < 10 ? fps.toFixed(1) : String(Math.round(fps));
}

/** The time of the flow's last step (`stats().flowMs`), where the scene has a flow (`flowStepper`); else empty. */
function flowText(stats) {
  return stats.flowStepper ? `flow ${(stats.flowMs ?? 0).toFixed(1)} ms` : '';
}

/** The blob cap the scene runs under, and whose it is: the memory budget's or the lighter version's. */
function capText(stats) {
  if (!stats.sceneBlobCap) return '';
  const whose = stats.sceneBlobCap === stats.memoryBudget?.blobCap ? 'memory budget' : 'lighter version';
  return ` (${whose}: at most ${stats.sceneBlobCap.toLocaleString('en')})`;
}

/**
 * The status text for `stats` (the player's `stats()`) in view `mode`, with the real-time
 * view's volume (`[nx, ny, nz]` voxels, or null) and whether the pointer stirs.
 */
export function statusText(stats, { mode, volume = null, stirring = false }) {
  const parts = [
    `t = ${stats.time.toFixed(2)} s`,
    `${stats.blobs.toLocaleString('en')} blobs${capText(stats)}`,
    `${fpsText(stats.fps)} fps (${LIMITS[stats.limitedBy] ?? stats.limitedBy})`,
    `step ${stats.stepMs.toFixed(2)} ms (${stats.stepper === 'gpu' ? 'GPU' : `worker${stats.stepperReason ? `: ${stats.stepperReason}` : ''}`})`,
    flowText(stats),
    `field ${stats.fieldMs.toFixed(0)} ms`,
  ].filter(Boolean);
  if (mode !== 'points') parts.push(`resolution ${Math.round(stats.scale * 100)} %`);
  if (volume) parts.push(`volume ${volume.join('×')}`);
  if (stirring) parts.push('stirring: drag over the view');
  return parts.join(' · ');
}
