// Hostile links and real faults: every request answers, a scene that stops the engine is not
// reloaded into a loop, budgets hold before any work, zero-size views do not hang, slow frames
// do not starve a call, and the pages and the standalone player run under a strict Content
// Security Policy.
import { readFileSync } from 'node:fs';
import { expect, test, collectErrors, holdClock, nextFrame } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const smallPlume = JSON.parse(readFileSync(new URL('../tests/fixtures/small-plume.json', import.meta.url), 'utf8'));

async function open(page, url) {
  await page.goto(url);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

const linkTo = async (scene, query = '?view=points') => `./${query}#${await encodeScene(scene)}`;

test('a scene that stops the engine twice is not reloaded: back to the last scene that ran', async ({ page }) => {
  await open(page, await linkTo(smallPlume));
  await page.evaluate(async () => { window.windfield.pause(); await window.windfield.step(150); });
  const other = { ...structuredClone(smallPlume), seed: 99 };
  await page.evaluate((s) => window.windfield.setScene(s), other);
  /** The core traps, as it would on running out of memory. */
  const crash = async () => {
    const worker = page.workers().at(-1);
    await worker.evaluate(() => self.postMessage({ type: 'crashed', error: 'the WASM core stopped (unreachable)' }));
  };
  await crash();
  // The first time, the scene is reloaded from its start.
  await expect.poll(() => page.evaluate(() => window.windfield.getScene()?.seed)).toBe(99);
  // The restarted engine has the scene again (a step waits for the reload) before it crashes again.
  await page.evaluate(() => window.windfield.step(1));
  await crash();
  // The second time, the page says so and goes back to the scene that ran before.
  await expect(page.locator('#message')).toContainText('stopped the engine twice');
  await expect.poll(() => page.evaluate(() => window.windfield.getScene()?.seed)).toBe(smallPlume.seed);
  const workers = page.workers().length;
  await page.waitForTimeout(1500);
  // No loop of restarts: the engine runs on, on the good scene.
  expect(page.workers().length).toBe(workers);
  await page.evaluate(() => window.windfield.step(5));
  expect((await page.evaluate(() => window.windfield.stats())).blobs).toBeGreaterThan(0);
});

test('a flood of emitters is refused by its budget before any work; the panel stays small', async ({ page }) => {
  const errors = collectErrors(page);
  const flood = structuredClone(smallPlume);
  flood.emitters = Array.from({ length: 20_000 }, (_, i) => ({ ...smallPlume.emitters[0], center: [i * 1e-4, 0, 0] }));
  await open(page, await linkTo(flood));
  await expect(page.locator('#message')).toContainText('emitters');
  expect((await page.evaluate(() => window.windfield.getScene())).emitters.length).toBeLessThan(10);
  // A long but valid list builds folders for the first items only.
  const many = structuredClone(smallPlume);
  many.emitters = Array.from({ length: 200 }, (_, i) => ({ ...smallPlume.emitters[0], rate: 1, center: [i * 1e-3, 0, 0] }));
  await page.evaluate((s) => window.windfield.setScene(s), many);
  await expect.poll(() => page.locator('.lil-controller').count()).toBeLessThan(1500);
  await expect(page.locator('.lil-controller', { hasText: '176 more' })).toHaveCount(1);
  // Births per step over their budget: refused with the budget's name, nothing allocated.
  const births = await page.evaluate(async (s) => {
    const scene = structuredClone(s);
    scene.emitters = Array.from({ length: 100 }, () => ({ ...s.emitters[0], rate: 1e6 }));
    scene.simulation.dt = 1;
    scene.render.time = 1;
    return window.windfield.setScene(scene).then(() => 'accepted', (e) => e.message);
  }, smallPlume);
  expect(births).toMatch(/birth/);
  const health = await page.evaluate(() => window.windfield.health());
  expect(health.wasmBytes).toBeLessThan(512 * 2 ** 20);
  expect(errors).toEqual([]);
});

test('a scene nested thousands deep is refused with a message, not a hang', async ({ page }) => {
  await open(page, await linkTo(smallPlume));
  const message = await page.evaluate(async () => {
    let deep = {};
    for (let i = 0; i < 3000; i++) deep = { a: deep };
    const scene = { ...window.windfield.getScene(), deep };
    return window.windfield.setScene(scene).then(() => 'accepted', (e) => e.message);
  });
  expect(message).toMatch(/scene/);
  expect(message).not.toBe('accepted');
});

test('a worker that quits without a word: the request times out with a message and the engine restarts', async ({ page }) => {
  // The request's 3 s pass on the page's clock, moved on by the test once the request is out.
  await page.clock.install();
  await open(page, await linkTo(smallPlume, '?view=points&timeout=3'));
  await page.evaluate(async () => { window.windfield.pause(); await window.windfield.step(10); });
  await page.workers().at(-1).evaluate(() => setTimeout(() => self.close()));
  await holdClock(page, { idle: false });
  await page.evaluate(() => {
    window.outcome = window.windfield.step(1).then(() => 'answered', (e) => e.message);
  });
  await page.clock.runFor(2900);
  expect(await page.evaluate(() => Promise.race([window.outcome, 'waiting']))).toBe('waiting');
  await page.clock.runFor(200);
  expect(await page.evaluate(() => window.outcome)).toMatch(/did not answer for 3 s/);
  await page.clock.resume();
  await expect(page.locator('#message')).toContainText('restarting the engine');
  // The restarted engine reloads the scene; it runs on.
  await expect.poll(() => page.evaluate(() => window.windfield.step(2).then(() => 'ok', (e) => e.message)), { timeout: 20_000 }).toBe('ok');
});

test('a 1×1 window neither hangs nor freezes the page: frames and the page\'s timers go on', async ({ page }) => {
  await page.clock.install();
  await open(page, await linkTo(smallPlume, '?view=raymarch'));
  await page.setViewportSize({ width: 1, height: 1 });
  await holdClock(page);
  // Frames with steps in them, a tenth of a second apart on the page's clock, and a timer set by
  // the page between each two.
  let last = await page.evaluate(() => window.windfield.stats());
  for (let k = 0; k < 5; k++) {
    await page.evaluate(() => { window.timerRan = false; setTimeout(() => { window.timerRan = true; }, 50); });
    const s = await nextFrame(page, 100);
    expect(s.time).toBeGreaterThan(last.time);
    expect(await page.evaluate(() => window.timerRan)).toBe(true);
    last = s;
  }
  await page.clock.resume();
  await page.setViewportSize({ width: 1100, height: 720 });
  const shot = await page.evaluate(() => window.windfield.captureGPU({ mode: 'points', width: 64, height: 48 }));
  expect(shot).toMatch(/^data:image\/png/);
});

test('frames slower than the display do not starve a call: each runs after at most the frame in flight', async ({ page }) => {
  // `?profile` waits for the GPU after every pass: each frame of the playing default scene
  // takes longer than the display's interval, so the next animation frame is always due when
  // one ends. A call that waits for its turn must still get it.
  await open(page, './?profile');
  await page.waitForFunction(() => window.windfield.stats().frames >= 3);
  const drawnDuring = await page.evaluate(async () => {
    const w = window.windfield;
    const out = [];
    for (const call of [() => w.setStepper('cpu'), () => w.step(1), () => w.setStepper('auto'), () => w.step(1)]) {
      const before = w.stats().frames;
      await call();
      out.push(w.stats().frames - before);
    }
    return out;
  });
  for (const n of drawnDuring) expect(n).toBeLessThanOrEqual(1);
});

/** A tiny scene (no field, a few blobs) as a data URL, for many players at once. */
const tinyScene = () => {
  const s = structuredClone(smallPlume);
  s.field.amplitude = 0;
  s.emitters[0].rate = 30;
  s.render.time = 0.2;
  return `data:application/json,${encodeURIComponent(JSON.stringify(s))}`;
};

/** A page with the site's `<wind-field>` (the standalone loader) and `body`. */
async function playerPage(page, body) {
  await page.route('**/players-test.html', (route) => route.fulfill({
    contentType: 'text/html',
    body: `<!doctype html><html><head><script type="module" src="./embed.js"></script></head><body>${body}</body></html>`,
  }));
  await page.goto('./players-test.html');
}

test('a playing player in a 0×0 box answers captureGPU', async ({ page }) => {
  await playerPage(page, `<wind-field id="p" autoplay loading="eager" view="points" src="${tinyScene()}" style="width:0;height:0"></wind-field>`);
  const out = await page.evaluate(async () => {
    await customElements.whenDefined('wind-field');
    const el = document.querySelector('#p');
    await el.ready;
    return el.captureGPU({ mode: 'points', width: 32, height: 24 }).then((u) => u.slice(0, 22), (e) => e.message);
  });
  expect(out).toBe('data:image/png;base64,');
});

test('more players than GPU contexts: the ones that lose theirs say so and fire error; none claims to be ready', async ({ page }) => {
  test.setTimeout(120_000);
  const src = tinyScene();
  const players = Array.from({ length: 18 }, (_, i) => `<wind-field id="p${i}" loading="eager" view="points" src="${src}" style="width:80px;height:60px"></wind-field>`).join('');
  await playerPage(page, players);
  const states = await page.evaluate(async () => {
    await customElements.whenDefined('wind-field');
    const all = [...document.querySelectorAll('wind-field')];
    const errors = new Map();
    for (const el of all) el.addEventListener('error', (e) => errors.set(el.id, e.detail.message));
    await Promise.allSettled(all.map((el) => el.ready));
    // The browser takes back the oldest contexts past its limit; the players notice.
    await new Promise((r) => setTimeout(r, 6000));
    return Promise.all(all.map(async (el) => ({
      id: el.id,
      loaded: el.loaded,
      error: errors.get(el.id) ?? null,
      capture: await el.captureGPU({ mode: 'points', width: 16, height: 12 }).then(() => 'captured', (e) => e.message),
    })));
  });
  const failed = states.filter((s) => s.error);
  expect(failed.length).toBeGreaterThan(0);
  for (const s of states) {
    if (s.error) {
      expect(s.error).toMatch(/GPU context/);
      expect(s.loaded).toBe(false);
      expect(s.capture).toMatch(/GPU context/);
    } else {
      expect(s.loaded).toBe(true);
      expect(s.capture).toBe('captured');
    }
  }
});

/** The policy the docs promise the pages run under, exactly. */
const CSP = "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'";

test('the pages and the standalone player run under a strict Content Security Policy', async ({ page }) => {
  test.setTimeout(60_000);
  const violations = [];
  page.on('console', (m) => { if (/Content Security Policy|Refused to/.test(m.text())) violations.push(m.text()); });
  await page.route('**/*', async (route) => {
    if (route.request().resourceType() !== 'document') return route.continue();
    if (route.request().url().endsWith('/csp-player.html')) {
      return route.fulfill({
        contentType: 'text/html',
        headers: { 'content-security-policy': CSP },
        body: '<!doctype html><html><head><script type="module" src="./embed.js"></script></head><body><wind-field id="p" loading="eager" view="points"></wind-field></body></html>',
      });
    }
    const response = await route.fetch();
    return route.fulfill({ response, headers: { ...response.headers(), 'content-security-policy': CSP } });
  });
  await open(page, './?view=points');
  await page.evaluate(() => window.windfield.step(3));
  // The CPU still is shown (drawn on a canvas: a data: or blob: image would be refused).
  // The folder opens from its title when it is closed (it starts open on a wide screen).
  await page.locator('#panel .lil-title', { hasText: 'Share and export' }).evaluate((title) => {
    if (title.parentElement.classList.contains('lil-closed')) title.click();
  });
  await page.locator('.lil-controller', { hasText: 'render still (CPU)' }).click();
  await expect(page.locator('#still-figure')).toBeVisible({ timeout: 60_000 });
  const still = await page.locator('#still').evaluate((c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let lit = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] + d[i + 1] + d[i + 2] > 0) lit += 1;
    return { width: c.width, height: c.height, lit };
  });
  expect(still).toMatchObject({ width: 480, height: 360 });
  expect(still.lit).toBeGreaterThan(480 * 360 * 0.5);
  // The panel is styled (lil-gui's stylesheet is linked, not injected).
  expect(await page.locator('.lil-gui.lil-root').evaluate((el) => getComputedStyle(el).fontSize)).not.toBe('');
  expect(await page.locator('.lil-gui.lil-root').evaluate((el) => getComputedStyle(el).backgroundColor)).not.toBe('rgba(0, 0, 0, 0)');
  await page.goto('./csp-player.html');
  const player = await page.evaluate(async () => {
    await customElements.whenDefined('wind-field');
    const el = document.querySelector('#p');
    await el.ready;
    const canvas = el.shadowRoot.querySelector('canvas');
    return { loaded: el.loaded, position: getComputedStyle(canvas).position, blobs: el.stats().blobs };
  });
  expect(player.loaded).toBe(true);
  expect(player.position).toBe('absolute');
  expect(player.blobs).toBeGreaterThan(0);
  for (const path of ['./classroom.html', './field.html', './embed.html']) {
    await page.goto(path);
    await page.waitForLoadState('load');
  }
  expect(violations).toEqual([]);
});
