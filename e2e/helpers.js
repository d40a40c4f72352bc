// Shared e2e helpers: the test fixture, console-error capture, canvas pixel statistics, the
// panel's folders, and the page's clock held so that tests count frames instead of timing them.

import { readFileSync } from 'node:fs';
import { test as base, expect as baseExpect } from '@playwright/test';

/**
 * An init script that opens the page in the full version (`page.addInitScript(fullVersion)`, or
 * a context's): the choice a visitor makes in the panel, kept for the visit.
 */
export function fullVersion() {
  try {
    sessionStorage.setItem('windfield.choices', JSON.stringify({ full: true }));
  } catch {
    // A page without storage (about:blank): nothing to choose there.
  }
}

/** The preset `name` as shipped (`public/scenes/NAME.json`), parsed. */
export function presetFile(name) {
  return JSON.parse(readFileSync(new URL(`../public/scenes/${name}.json`, import.meta.url), 'utf8'));
}

/**
 * The tests' `test`: every page opens in the full version, as on a machine with a GPU (these
 * tests run on SwiftShader, which would get the lighter version: `web/src/player/machine.js`);
 * `e2e/any-machine.spec.js` tests the lighter version itself with Playwright's own `test`.
 */
export const test = base.extend({
  page: async ({ page }, use) => {
    await page.addInitScript(fullVersion);
    await use(page);
  },
});
/**
 * The tests' `expect`: Playwright's, whose `expect.poll` asks again after 50 ms, 100 ms and then
 * every 200 ms instead of after 100, 250, 500 ms and then every second, so a state that takes
 * 300 ms to arrive is seen within 350 ms rather than 850 (a call's own `intervals` still win).
 */
export const expect = baseExpect.configure({});
/** The waits of `expect.poll` (ms), the last repeated. */
const POLL_INTERVALS = [50, 100, 200];
const poll = expect.poll;
expect.poll = (fn, options = {}) => poll(fn, { intervals: POLL_INTERVALS, ...options });

/** Collects console errors and uncaught page errors into an array. */
export function collectErrors(page) {
  const errors = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(msg.text());
  });
  page.on('pageerror', (err) => errors.push(err.message));
  return errors;
}

/**
 * Luminance statistics of a canvas (by selector; `shadow`: the canvas inside that element's
 * shadow root), over a 128 × 128 resampling: mean, standard deviation, and the spread
 * (max − min).
 */
export async function canvasLuminance(page, selector, { shadow = false } = {}) {
  return page.evaluate(({ sel, inShadow }) => {
    const host = document.querySelector(sel);
    const src = inShadow ? host.shadowRoot.querySelector('canvas') : host;
    const c = document.createElement('canvas');
    c.width = 128;
    c.height = 128;
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0, 128, 128);
    const d = ctx.getImageData(0, 0, 128, 128).data;
    let sum = 0;
    let sum2 = 0;
    let min = 255;
    let max = 0;
    const n = d.length / 4;
    for (let i = 0; i < d.length; i += 4) {
      const y = 0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2];
      sum += y;
      sum2 += y * y;
      min = Math.min(min, y);
      max = Math.max(max, y);
    }
    const mean = sum / n;
    return { mean, std: Math.sqrt(Math.max(sum2 / n - mean * mean, 0)), spread: max - min };
  }, { sel: selector, inShadow: shadow });
}

/** The lil-gui folder titled `title` (exactly). */
export function folder(page, title) {
  return page.locator(`xpath=//div[contains(@class,"lil-gui")][./*[contains(@class,"lil-title")][normalize-space()="${title}"]]`);
}

/** Opens the lil-gui folder titled `title` (if closed) and returns it. */
export async function openFolder(page, title) {
  const f = folder(page, title);
  if (await f.evaluate((el) => el.classList.contains('lil-closed'))) await f.locator('.lil-title').first().click();
  return f;
}

/** Types `value` into the number field named `name` in folder `f`, and commits it. */
export async function setNumber(f, name, value) {
  const input = f.locator('.lil-controller', { has: f.page().locator(`.lil-name:text-is("${name}")`) }).locator('input').first();
  await input.fill(String(value));
  await input.press('Enter');
}

/**
 * The world point (m) under the view's pixel (px, py) (CSS pixels from the canvas's top left)
 * on the plane through the camera's target facing it, for a canvas of `width × height`.
 */
export function worldAt(camera, width, height, px, py) {
  const sub = (a, b) => a.map((v, i) => v - b[i]);
  const norm = (a) => a.map((v) => v / Math.hypot(...a));
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const forward = norm(sub(camera.target, camera.position));
  const right = norm(cross(forward, camera.up));
  const up = cross(right, forward);
  const d = Math.hypot(...sub(camera.target, camera.position));
  const half = d * Math.tan((camera.fov_y_deg * Math.PI) / 360);
  const u = ((px - width / 2) / (height / 2)) * half;
  const v = -((py - height / 2) / (height / 2)) * half;
  return camera.target.map((t, i) => t + u * right[i] + v * up[i]);
}

/** Distance (m) from `p` to the segment from `a` to `b`. */
export function toSegment(p, a, b) {
  const ab = b.map((v, i) => v - a[i]);
  const s = Math.min(Math.max(p.reduce((sum, v, i) => sum + (v - a[i]) * ab[i], 0) / ab.reduce((sum, v) => sum + v * v, 0), 0), 1);
  return Math.hypot(...p.map((v, i) => v - (a[i] + s * ab[i])));
}

/**
 * Holds the page's clock still: Playwright's (`page.clock.install()` before the page loads),
 * which stands in for `performance.now`, `Date`, the timers and the animation frames. From then
 * on the page's time moves only when the test moves it (`nextFrame`, `page.clock.runFor`), so
 * the frames a test counts come at the times it chose, however loaded the machine: the worker
 * keeps its own clock, and a frame's steps take what they take there. Unless `idle` is false,
 * returns once no frame of the playground's player is in flight: a `step(0)` takes its turn
 * after the frame in flight, and no frame begins while a call waits for its turn.
 */
export async function holdClock(page, { idle = true } = {}) {
  for (;;) {
    // A moment just ahead of the page's clock, which runs on until it is held.
    const at = await page.evaluate(() => Date.now() + 100);
    try {
      await page.clock.pauseAt(at);
      break;
    } catch (e) {
      if (!/past/.test(e.message)) throw e;
    }
  }
  if (!idle) return;
  await page.evaluate(() => {
    window.heldClockTurn = null;
    window.windfield.step(0).then(() => { window.heldClockTurn = 'taken'; }, (e) => { window.heldClockTurn = e.message; });
  });
  // The turn waits on the page's timers (naps of 5 ms) while a frame is in flight.
  for (;;) {
    const turn = await page.evaluate(() => window.heldClockTurn);
    if (turn === 'taken') return;
    if (turn !== null) throw new Error(`holdClock: step(0) failed: ${turn}`);
    await page.clock.runFor(5);
  }
}

/**
 * Moves the held page clock on by `ms` (`runFor`: every animation frame and timer due on the way,
 * as a display's; `jump`: `fastForward`, as on a machine whose animation frames come as fast as
 * the frames are drawn, one at the end of each half second at most, so that no turn of the
 * player's loop counts more time than it does, half a second), then waits until the playground's
 * player has drawn a frame more: the frame its loop began in that time. Returns its stats.
 */
export async function nextFrame(page, ms, { jump = false } = {}) {
  const stats = () => page.evaluate(() => window.windfield.stats());
  const before = (await stats()).frames;
  if (!jump) await page.clock.runFor(ms);
  for (let left = jump ? ms : 0; left > 0; left -= 500) await page.clock.fastForward(Math.min(left, 500));
  await expect.poll(async () => (await stats()).frames).toBeGreaterThan(before);
  return stats();
}

/** Serves `body` as ./NAME.html, a bare page beside the built embed.js, and opens it. */
export async function bare(page, name, body) {
  await page.route(`**/${name}.html`, (route) => route.fulfill({
    contentType: 'text/html',
    body: `<!doctype html><html lang="en"><meta charset="utf-8"><title>${name}</title><link rel="icon" href="data:,">
      <script type="module" src="./embed.js"></script><body style="margin: 0">${body}</body></html>`,
  }));
  await page.goto(`./${name}.html`);
  await page.waitForFunction(() => customElements.get('wind-field') !== undefined);
}
