// The classroom's large scales, kinematic and physical (§7): one scene twice, a plume in an
// updraft under a solid ceiling, left without a flow and right with one. Both players load as
// they near the viewport; only the right one has a flow's grid; and what the text says to look
// for is there: after 3 s the right one's smoke runs out along the ceiling, the left one's
// gathers over the source. The steps are fixed ones, the players paused. The page runs under
// the strict Content Security Policy the docs promise (faults.spec.js), its scenes fetched from
// the site itself.
import { expect, test, collectErrors } from './helpers.js';

/** The policy the docs promise the pages run under. */
const CSP = "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'";

/** The rms distance from the axis (m) of the blobs 0.8–1 m up, and how many there are. */
function underCeiling(blobs) {
  const band = blobs.filter((b) => b.center[1] > 0.8 && b.center[1] < 1);
  const r2 = band.reduce((s, b) => s + b.center[0] ** 2 + b.center[2] ** 2, 0) / band.length;
  return { spread: Math.sqrt(r2), n: band.length };
}

test('classroom: the large scales side by side, the kinematic without a flow and the physical with one, whose smoke runs out along the ceiling', async ({ page }) => {
  test.setTimeout(180_000);
  const errors = collectErrors(page);
  const violations = [];
  page.on('console', (m) => { if (/Content Security Policy|Refused to/.test(m.text())) violations.push(m.text()); });
  await page.route('**/*', async (route) => {
    if (route.request().resourceType() !== 'document') return route.continue();
    const response = await route.fetch();
    return route.fulfill({ response, headers: { ...response.headers(), 'content-security-policy': CSP } });
  });
  await page.goto('./classroom.html');
  await page.waitForFunction(() => window.classroom?.largeScales !== undefined);
  // Far down the page, they wait for the reader.
  expect(await page.evaluate(() => document.querySelector('#physical').loaded)).toBe(false);
  await page.evaluate(() => document.querySelector('#physical').scrollIntoView());
  await page.evaluate(() => window.classroom.largeScales);
  const loaded = await page.evaluate(async () => {
    const [left, right] = ['kinematic', 'physical'].map((id) => document.getElementById(id));
    return {
      loaded: [left.loaded, right.loaded],
      flows: [left.getScene().flow ?? null, right.getScene().flow],
      grids: await Promise.all([left, right].map(async (p) => {
        const grid = await p.exportFlow();
        return grid && { cells: Array.from(grid.cells), cellsIn: grid.velocity.length / 3 };
      })),
      flowStepper: [left.stats().flowStepper, right.stats().flowStepper],
    };
  });
  expect(loaded.loaded).toEqual([true, true]);
  expect(loaded.flows[0]).toBe(null);
  expect(loaded.flows[1].cells).toEqual([24, 12, 24]);
  expect(loaded.grids[0]).toBe(null);
  expect(loaded.grids[1]).toEqual({ cells: [24, 12, 24], cellsIn: 24 * 12 * 24 });
  expect(loaded.flowStepper).toEqual([null, 'cpu']);
  // Each from its start, 3 s of fixed steps.
  const spreads = await page.evaluate(async () => Promise.all(['kinematic', 'physical'].map(async (id) => {
    const p = document.getElementById(id);
    p.pause();
    await p.setScene(p.getScene());
    await p.step(180);
    return { time: p.stats().time, blobs: (await p.exportBlobs()).blobs.map((b) => ({ center: b.center })) };
  })));
  const [kinematic, physical] = spreads.map((s) => ({ time: s.time, ...underCeiling(s.blobs), top: Math.max(...s.blobs.map((b) => b.center[1])) }));
  console.log(`under the ceiling after 3 s: kinematic ${kinematic.spread.toFixed(3)} m (${kinematic.n} blobs), physical ${physical.spread.toFixed(3)} m (${physical.n})`);
  for (const run of [kinematic, physical]) {
    expect(Math.abs(run.time - 3)).toBeLessThan(0.01);
    expect(run.n).toBeGreaterThan(300);
    expect(run.top).toBeLessThanOrEqual(1);
  }
  expect(physical.spread).toBeGreaterThan(3 * kinematic.spread);
  expect(violations).toEqual([]);
  expect(errors).toEqual([]);
});
