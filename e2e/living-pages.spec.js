// Players in living pages and inputs read before they are trusted: documentation sites built
// with React, Vue or Svelte mount, move and unmount elements all the time; a removed player
// answers every call at once and leaves nothing running, a moved one goes on; a bad `timeout`
// in a link cannot stop the playground; recordings do not mix scenes; and every argument of
// the browser API is checked like a scene's numbers.
import { readFileSync } from 'node:fs';
import { expect, test, bare, collectErrors, holdClock, openFolder } from './helpers.js';

const smallPlume = JSON.parse(readFileSync(new URL('../tests/fixtures/small-plume.json', import.meta.url), 'utf8'));

/** Serves the small plume as ./tiny.json and `body` as ./NAME.html (`bare` of helpers.js). */
async function bareWithPlume(page, name, body) {
  await page.route('**/tiny.json', (route) => route.fulfill({ contentType: 'application/json', body: JSON.stringify(smallPlume) }));
  await bare(page, name, body);
}

async function openPlayground(page, url = './?view=points') {
  await page.goto(url);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

test('a removed player rejects every pending call at once with an AbortError, and 20 mounts leave no worker behind', async ({ page }) => {
  test.setTimeout(120_000);
  const errors = collectErrors(page);
  // The page's clock held at the removal: the calls settle on the turn after it (the element
  // waits one task, in case it is put back), with no time on that clock for anything to take.
  await page.clock.install();
  await bareWithPlume(page, 'mounts', '<div id="host"></div>');
  // Calls waiting for the scene, and a long step in flight, when the element goes.
  await page.evaluate(async () => {
    const el = document.createElement('wind-field');
    for (const [k, v] of Object.entries({ loading: 'eager', view: 'points', src: './tiny.json', 'poster-time': '0' })) el.setAttribute(k, v);
    document.querySelector('#host').append(el);
    await el.ready;
    el.pause();
    const calls = {
      // Long enough to be in flight whoever steps (the worker steps this tiny scene fast).
      step: el.step(300_000),
      ready: Promise.resolve(el.ready),
      setScene: el.setScene(el.getScene()),
      editScene: el.editScene(el.getScene()),
      setStepper: el.setStepper('cpu'),
      exportBlobs: el.exportBlobs({ width: 8, height: 8 }),
      renderReference: el.renderReference({ width: 8, height: 8 }),
    };
    window.removed = null;
    window.settled = [];
    window.outcomes = Object.entries(calls).map(([name, p]) => p.then(
      () => ({ name, outcome: 'resolved', early: window.removed === null, ms: performance.now() - window.removed }),
      (e) => ({ name, outcome: e.name, early: window.removed === null, message: e.message, ms: performance.now() - window.removed }),
    ).then((r) => { window.settled.push(r.name); return r; }));
    await new Promise((r) => setTimeout(r, 50));
  });
  await holdClock(page, { idle: false });
  await page.evaluate(() => {
    window.removed = performance.now();
    document.querySelector('wind-field').remove();
  });
  // The element's one task: every call has settled after it, the page's clock still at the removal.
  await page.clock.runFor(1);
  expect((await page.evaluate(() => window.settled)).length).toBe(7);
  const pending = await page.evaluate(() => Promise.all(window.outcomes));
  await page.clock.resume();
  // The step and the calls queued behind it were still waiting when the element went; a call
  // the worker answered beside the step (a blob list) may have resolved before.
  for (const name of ['step', 'setScene', 'editScene', 'setStepper']) {
    expect(pending.find((c) => c.name === name).early, `${name} still pending at the removal`).toBe(false);
  }
  for (const call of pending) {
    if (call.early) {
      expect(call.outcome, `${call.name}, settled before the removal`).toBe('resolved');
      continue;
    }
    expect(call.outcome, call.name).toBe('AbortError');
    expect(call.message, call.name).toBe('the player was removed from the page');
    expect(call.ms, call.name).toBeLessThanOrEqual(1);
  }
  // Twenty mounts and unmounts, as a framework's route changes do.
  // No player on the page, no worker: the removed one's has ended.
  await expect.poll(() => page.workers().length, { timeout: 10_000 }).toBe(0);
  for (let k = 0; k < 20; k++) {
    await page.evaluate(async () => {
      const el = document.createElement('wind-field');
      for (const [k, v] of Object.entries({ loading: 'eager', view: 'points', src: './tiny.json', 'poster-time': '0' })) el.setAttribute(k, v);
      document.querySelector('#host').append(el);
      await el.ready;
      el.remove();
      await new Promise((r) => setTimeout(r, 20));
    });
  }
  await expect.poll(() => page.workers().length, { timeout: 10_000 }).toBe(0);
  expect(errors).toEqual([]);
});

for (const view of ['points', 'exact', 'raymarch']) {
  test(`a ready player moved in the page keeps running (${view})`, async ({ page }) => {
    const errors = collectErrors(page);
    await bareWithPlume(page, `move-${view}`, `<div id="a"><wind-field loading="eager" view="${view}" src="./tiny.json" poster-time="0" style="width: 160px"></wind-field></div><div id="b"></div>`);
    const r = await page.evaluate(async () => {
      const el = document.querySelector('wind-field');
      await el.ready;
      el.pause();
      const t0 = el.stats().time;
      document.querySelector('#b').append(el);
      // A framework's reorder: out and back in within one task.
      document.querySelector('#a').append(el);
      await el.step(3);
      return { t0, t1: el.stats().time, loaded: el.loaded };
    });
    expect(r.loaded).toBe(true);
    expect(r.t1).toBeGreaterThan(r.t0);
    expect(errors).toEqual([]);
  });
}

for (const value of ['3000000', '1e308', '0.001', 'abc']) {
  test(`?timeout=${value} cannot keep the playground from loading`, async ({ page }) => {
    await openPlayground(page, `./?view=points&timeout=${value}`);
    expect(await page.evaluate(() => window.windfield.stats().blobs)).toBeGreaterThanOrEqual(0);
    await page.evaluate(() => window.windfield.step(2));
    await expect(page.locator('#message')).toContainText('timeout was not used');
  });
}

test('a recording neither mixes scenes nor takes steps asked for meanwhile', async ({ page }) => {
  test.setTimeout(90_000);
  await openPlayground(page);
  const r = await page.evaluate(async (plume) => {
    const w = window.windfield;
    await w.pause();
    const t0 = w.stats().time;
    const load = w.setScene(plume);
    await new Promise((res) => setTimeout(res, 20));
    const video = w.recordWebM({ frames: 8, width: 64, height: 48, fps: 8 });
    // Asked for once the recording has been: refused, however soon the engine answers.
    const step = w.step(50).then(() => 'stepped', (e) => e.message);
    const late = w.setScene({ ...plume, seed: plume.seed + 1 }).then(() => 'loaded', (e) => e.message);
    const [loaded, recorded, stepped, lateLoad] = await Promise.all([
      load.then(() => 'loaded', (e) => e.message),
      video.then((v) => v.size, (e) => e.message),
      step,
      late,
    ]);
    return { t0, loaded, recorded, stepped, lateLoad, t1: w.stats().time, dt: w.getScene().simulation.dt, seed: w.getScene().seed };
  }, smallPlume);
  expect(typeof r.recorded === 'number' || /VP8|encode/.test(r.recorded)).toBe(true);
  expect(r.stepped).toMatch(/a recording is under way: take steps once it has ended/);
  expect(r.lateLoad).toMatch(/a recording is under way: load the scene once it has ended/);
  expect(r.seed).not.toBe(smallPlume.seed + 1);
  // Loaded before the recording (which then recorded seven steps of it) or after it (the scene
  // at t = 0), or refused during it: never in the middle.
  if (r.loaded === 'loaded') expect([0, 7 * r.dt].some((t) => Math.abs(r.t1 - t) < 1e-9)).toBe(true);
  else expect(r.loaded).toMatch(/a recording is under way/);
});

test('every argument of the API is checked, and refused with its name and range', async ({ page }) => {
  await openPlayground(page);
  const messages = await page.evaluate(async () => {
    const w = window.windfield;
    const refused = async (f) => {
      try {
        await f();
        return 'accepted';
      } catch (e) {
        return e.message;
      }
    };
    const scene = w.getScene();
    scene.field.amplitude = NaN;
    const infinite = w.getScene();
    infinite.wind[0].velocity[1] = Infinity;
    return {
      exportZero: await refused(() => w.exportBlobs({ width: 0, height: 10 })),
      exportNaN: await refused(() => w.exportBlobs({ width: NaN, height: 10 })),
      exportHuge: await refused(() => w.exportBlobs({ width: 1e5, height: 10 })),
      captureHuge: await refused(() => w.captureGPU({ mode: 'points', width: 20000, height: 20000 })),
      captureNegative: await refused(() => w.captureGPU({ mode: 'points', width: -5, height: 10 })),
      captureZero: await refused(() => w.captureGPU({ mode: 'points', width: 0, height: 0 })),
      captureMode: await refused(() => w.captureGPU({ mode: 'bogus', width: 10, height: 10 })),
      captureQuality: await refused(() => w.captureGPU({ mode: 'points', quality: 'ultra', width: 10, height: 10 })),
      referenceZero: await refused(() => w.renderReference({ width: 0, height: 10 })),
      recordFps: await refused(() => w.recordWebM({ frames: 2, fps: 0 })),
      stepHalf: await refused(() => w.step(1.5)),
      statsEpsilon: await refused(() => w.fieldStats({ law: 'kolmogorov', epsilon: -1, k_inertial: 4, sigma: 1 })),
      nan: await refused(() => w.setScene(scene)),
      infinity: await refused(() => w.editScene(infinite)),
      shapes: JSON.stringify(w.getScene().shapes),
    };
  });
  expect(messages.exportZero).toBe('exportBlobs: width must be a whole number from 1 to 8,192 (got 0)');
  expect(messages.exportNaN).toBe('exportBlobs: width must be a whole number from 1 to 8,192 (got NaN)');
  expect(messages.exportHuge).toMatch(/exportBlobs: width must be a whole number from 1 to 8,192 \(got 100000\)/);
  expect(messages.captureHuge).toMatch(/^captureGPU: width must be a whole number from 1 to \d/);
  expect(messages.captureNegative).toMatch(/^captureGPU: width must be a whole number from 1 .* \(got -5\)/);
  expect(messages.captureZero).toMatch(/^captureGPU: width must be/);
  expect(messages.captureMode).toBe("captureGPU: mode must be one of 'raymarch', 'points', 'exact' (got \"bogus\")");
  expect(messages.captureQuality).toMatch(/^captureGPU: quality must be one of 'draft', 'standard', 'high'/);
  expect(messages.referenceZero).toMatch(/^renderReference: width must be a whole number from 1/);
  expect(messages.recordFps).toBe('recordWebM: fps must be a number greater than 0 and at most 240 (got 0)');
  expect(messages.stepHalf).toMatch(/^steps: must be a whole number of at least 0 \(got 1.5\)/);
  expect(messages.statsEpsilon).toMatch(/spectrum\.epsilon/);
  expect(messages.nan).toBe('field.amplitude: must be a finite number (got NaN)');
  expect(messages.infinity).toBe('wind[0].velocity[1]: must be a finite number (got Infinity)');
  expect(messages.shapes).toBe('[]');
});

test('a seed typed as 0x10 in the panel is refused with what was typed, and a typed −1 is sent as −1', async ({ page }) => {
  await openPlayground(page);
  await page.evaluate(() => window.windfield.pause());
  const field = await openFolder(page, 'Small-scale field (§3)');
  const input = (name) => field.locator('.lil-controller', { has: page.locator(`.lil-name:text-is("${name}")`) }).locator('input').first();
  const seed = input('seed');
  const before = await page.evaluate(() => window.windfield.getScene().seed);
  await seed.fill('0x10');
  await seed.press('Enter');
  await expect(page.locator('#message')).toContainText('seed must be a number written in decimal');
  await expect(page.locator('#message')).toContainText('0x10');
  expect(await page.evaluate(() => window.windfield.getScene().seed)).toBe(before);
  const amplitude = input('amplitude');
  await amplitude.fill('-1');
  await amplitude.press('Enter');
  await expect(page.locator('#message')).toContainText('got -1');
});
