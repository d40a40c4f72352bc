// <wind-field>: several players per page, each with the methods of the browser API (docs/FORMATS.md); the built
// dist/embed.js is a small loader that fetches the player's code only when a player nears the
// viewport (once for all of them); without autoplay a player shows its scene at poster-time
// with a play button; ready/error events; attributes mirrored as properties and live changes.
import { gzipSync } from 'node:zlib';
import { test as lighterTest } from '@playwright/test';
import { expect, test, canvasLuminance, bare, collectErrors } from './helpers.js';

/** Records every script and WASM response: {url, gzip (bytes gzipped)}. */
function recordCode(page) {
  const fetched = [];
  page.on('response', async (response) => {
    const url = response.url();
    if (!/^https?:/.test(url) || !/\.(m?js|wasm)(\?|$)/.test(url)) return;
    const body = await response.body().catch(() => Buffer.alloc(0));
    fetched.push({ url, gzip: gzipSync(body, { level: 9 }).length });
  });
  return fetched;
}

test('two embedded players on the docs page both run', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./embed.html');
  const counts = await page.evaluate(async () => {
    const players = [...document.querySelectorAll('#a, #b')];
    for (const p of players) p.scrollIntoView();
    await Promise.all(players.map((p) => p.ready));
    for (const p of players) p.pause();
    await players[0].step(30);
    await players[1].step(60);
    return players.map((p) => p.stats().blobs);
  });
  expect(counts[0]).toBeGreaterThan(10);
  expect(counts[1]).toBeGreaterThan(counts[0]);
  const url = await page.evaluate(() => document.querySelector('#b').captureGPU({ mode: 'points', width: 80, height: 60 }));
  expect(url.startsWith('data:image/png;base64,')).toBe(true);
  expect(errors).toEqual([]);
});

test('a lazy player 5,000 px below the fold fetches only the loader until scrolled to, then runs', async ({ page }) => {
  const errors = collectErrors(page);
  const fetched = recordCode(page);
  const posters = [];
  page.on('request', (r) => { if (r.url().includes('?poster')) posters.push(r.url()); });
  await bare(page, 'lazy', `<p style="height: 5000px">Text above the player.</p>
    <wind-field id="far" preset="default" autoplay poster="./favicon.svg?poster" style="width: 320px"></wind-field>`);
  await page.waitForLoadState('networkidle');
  // Nor its poster image: that too waits until the element nears the viewport.
  expect(posters).toEqual([]);
  const before = fetched.map((f) => ({ ...f }));
  const kib = before.reduce((sum, f) => sum + f.gzip, 0) / 1024;
  test.info().annotations.push({ type: 'code before scrolling', description: `${kib.toFixed(1)} KiB gzipped: ${before.map((f) => f.url.split('/').pop()).join(', ')}` });
  expect(before.map((f) => new URL(f.url).pathname)).toEqual(['/embed.js']);
  expect(kib).toBeLessThanOrEqual(50);
  expect(await page.evaluate(() => document.querySelector('#far').loaded)).toBe(false);
  expect(page.workers()).toHaveLength(0);

  await page.evaluate(() => document.querySelector('#far').scrollIntoView());
  await page.evaluate(() => document.querySelector('#far').ready);
  await expect.poll(() => page.evaluate(() => document.querySelector('#far').stats().blobs)).toBeGreaterThan(0);
  const after = fetched.map((f) => new URL(f.url).pathname);
  expect(after.some((p) => /^\/wind-field\/player-.*\.js$/.test(p))).toBe(true);
  expect(errors).toEqual([]);
});

test('off-screen players wait; players share one import of the player code', async ({ page }) => {
  const errors = collectErrors(page);
  const fetched = recordCode(page);
  await bare(page, 'two', `<wind-field id="near" preset="default" autoplay style="width: 320px"></wind-field>
    <div style="height: 4000px"></div>
    <wind-field id="far" preset="default" autoplay style="width: 320px"></wind-field>
    <wind-field id="eager" preset="default" loading="eager" style="width: 320px"></wind-field>`);
  await page.evaluate(() => Promise.all(['#near', '#eager'].map((s) => document.querySelector(s).ready)));
  // The near and the eager player run (the eager one off-screen, paused at its poster time);
  // the far lazy one has not even started a worker.
  expect(await page.evaluate(() => document.querySelector('#far').loaded)).toBe(false);
  expect(page.workers()).toHaveLength(2);
  await expect.poll(() => page.evaluate(() => document.querySelector('#near').stats().blobs)).toBeGreaterThan(0);
  expect(await page.evaluate(() => document.querySelector('#far').stats().blobs)).toBe(0);
  await page.evaluate(() => document.querySelector('#far').scrollIntoView());
  await page.evaluate(() => document.querySelector('#far').ready);
  await expect.poll(() => page.evaluate(() => document.querySelector('#far').stats().blobs)).toBeGreaterThan(0);
  const chunks = fetched.filter((f) => /\/wind-field\/player-.*\.js$/.test(f.url));
  expect(chunks).toHaveLength(1);
  expect(errors).toEqual([]);
});

test('without autoplay a player shows its scene at poster-time with a play button', async ({ page }) => {
  const errors = collectErrors(page);
  await bare(page, 'poster', `<wind-field id="p" preset="default" style="width: 320px"></wind-field>
    <wind-field id="one" preset="default" poster-time="1" style="width: 160px"></wind-field>`);
  const ready = await page.evaluate(async () => {
    const els = ['#p', '#one'].map((s) => document.querySelector(s));
    await Promise.all(els.map((e) => e.ready));
    return els.map((e) => ({ time: e.stats().time, dt: e.getScene().simulation.dt, blobs: e.stats().blobs }));
  });
  // Without poster-time the poster shows the scene's render.time.
  const renderTime = await page.evaluate(() => document.querySelector('#p').getScene().render.time);
  expect(renderTime).toBe(4);
  expect(ready[0].time).toBeCloseTo(Math.round(renderTime / ready[0].dt) * ready[0].dt, 6);
  expect(ready[1].time).toBeCloseTo(Math.round(1 / ready[1].dt) * ready[1].dt, 6);
  expect(ready[0].blobs).toBeGreaterThan(ready[1].blobs);
  // The poster frame is drawn: the gas, not an empty box.
  expect((await canvasLuminance(page, '#p', { shadow: true })).spread).toBeGreaterThan(30);
  // Paused at its poster time until asked to play.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  expect(await page.evaluate(() => document.querySelector('#p').stats().time)).toBe(ready[0].time);
  const play = page.locator('#p').locator('button.play');
  await expect(play).toBeVisible();
  await expect(play).toHaveAccessibleName('Play the default scene');
  // Reached by the keyboard: the first tab stop of the page, started with Enter.
  await page.keyboard.press('Tab');
  await expect(play).toBeFocused();
  await page.keyboard.press('Enter');
  await expect(play).toBeHidden();
  await expect.poll(() => page.evaluate(() => document.querySelector('#p').stats().time)).toBeGreaterThan(ready[0].time);
  expect(errors).toEqual([]);
});

test('a poster image shows until the scene is ready', async ({ page }) => {
  const errors = collectErrors(page);
  await bare(page, 'image', `<p style="height: 3000px">Text.</p>
    <wind-field id="p" preset="default" poster="./favicon.svg" style="width: 320px"></wind-field>`);
  const poster = page.locator('#p').locator('img.poster');
  await expect(poster).toHaveAttribute('src', /favicon\.svg$/);
  // Scrolled to 800 px short of it: the image is fetched as it nears (the browser's lazy
  // images start farther out than that) and shown, before the player starts (400 px out).
  await page.evaluate(() => {
    const top = document.querySelector('#p').getBoundingClientRect().top + scrollY;
    scrollTo(0, top - innerHeight - 800);
  });
  await expect.poll(() => poster.evaluate((img) => img.complete && img.naturalWidth > 0)).toBe(true);
  expect(await poster.evaluate((img) => !img.hidden)).toBe(true);
  expect(await page.evaluate(() => document.querySelector('#p').loaded)).toBe(false);
  await page.evaluate(() => document.querySelector('#p').scrollIntoView());
  await page.evaluate(() => document.querySelector('#p').ready);
  await expect(poster).toBeHidden();
  expect(errors).toEqual([]);
});

test('ready and error events; methods wait for the scene or reject clearly', async ({ page }) => {
  const errors = collectErrors(page);
  await page.route('**/bad-scene.json', (route) => route.fulfill({
    contentType: 'application/json',
    body: JSON.stringify({ version: 1, field: { size: [32, 33, 32, 32] } }),
  }));
  await bare(page, 'events', '<p style="height: 3000px">Text.</p>');
  const out = await page.evaluate(async () => {
    const make = (attrs) => {
      const el = document.createElement('wind-field');
      for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
      const events = [];
      el.addEventListener('ready', (e) => events.push({ type: 'ready', version: e.detail.scene.version }));
      el.addEventListener('error', (e) => events.push({ type: 'error', message: e.detail.message }));
      document.body.append(el);
      return { el, events };
    };
    const settle = (p) => p.then(() => 'resolved', (e) => `rejected: ${e.message}`);
    const good = make({ preset: 'default', loading: 'eager', 'poster-time': '0' });
    const missing = make({ src: './no-such-scene.json', loading: 'eager' });
    const bad = make({ src: './bad-scene.json', loading: 'eager' });
    const results = await Promise.all([good, missing, bad].map((x) => settle(x.el.ready)));
    // A method on a failed player rejects with its error.
    const step = await settle(missing.el.step(1));
    // A player far below the fold: step() waits until it is scrolled to, then runs.
    const lazy = make({ preset: 'default', 'poster-time': '0' });
    let stepped = false;
    const waiting = lazy.el.step(5).then(() => { stepped = true; });
    await new Promise((r) => setTimeout(r, 300));
    const before = { stepped, loaded: lazy.el.loaded, scene: lazy.el.getScene() };
    lazy.el.scrollIntoView();
    await waiting;
    // A detached element rejects at once.
    const detached = await settle(document.createElement('wind-field').step(1));
    return {
      results, step, before, after: { stepped, time: lazy.el.stats().time },
      events: [good.events, missing.events, bad.events],
      message: missing.el.shadowRoot.querySelector('[role=alert]').textContent,
      loaded: good.el.loaded,
      detached,
    };
  });
  expect(out.results[0]).toBe('resolved');
  expect(out.loaded).toBe(true);
  expect(out.events[0]).toEqual([{ type: 'ready', version: 1 }]);
  // (vite preview answers a missing file with its index page: not JSON.)
  expect(out.results[1]).toMatch(/^rejected: .*no-such-scene\.json/);
  expect(out.events[1]).toEqual([{ type: 'error', message: out.results[1].replace('rejected: ', '') }]);
  expect(out.message).toContain('no-such-scene.json');
  expect(out.step).toBe(out.results[1]);
  expect(out.results[2]).toContain('field.size[1]');
  expect(out.events[2].map((e) => e.type)).toEqual(['error']);
  expect(out.before).toEqual({ stepped: false, loaded: false, scene: null });
  expect(out.after.stepped).toBe(true);
  expect(out.after.time).toBeGreaterThan(0);
  expect(out.detached).toMatch(/^rejected: <wind-field> is not in a document/);
  // The only console errors: a host's report of a missing file.
  expect(errors.filter((e) => !/404/.test(e))).toEqual([]);
});

test('attributes are mirrored as properties; changing preset or src loads the new scene', async ({ page }) => {
  const errors = collectErrors(page);
  await bare(page, 'live', '<wind-field id="p" preset="default" loading="eager" poster-time="0" style="width: 240px"></wind-field>');
  const out = await page.evaluate(async () => {
    const el = document.querySelector('#p');
    await el.ready;
    const props = {
      preset: el.preset, src: el.src, loading: el.loading, posterTime: el.posterTime, view: el.view,
      autoplay: el.autoplay, controls: el.controls,
    };
    el.controls = true;
    el.posterTime = 0.5;
    el.view = 'points';
    const reflected = ['controls', 'poster-time', 'view'].map((a) => el.getAttribute(a));
    const loadedScene = new Promise((r) => el.addEventListener('ready', (e) => r(e.detail.scene), { once: true }));
    el.preset = 'cigarette';
    const cigarette = await loadedScene;
    await el.ready;
    const afterPreset = { emitters: el.getScene().emitters.length, object: el.getScene().render.objects[0]?.type, time: el.stats().time };
    el.src = './scenes/default.json';
    await new Promise((r) => el.addEventListener('ready', r, { once: true }));
    return {
      props, reflected, cigarette: cigarette.emitters.length, afterPreset,
      afterSrc: { emitters: el.getScene().emitters.length, objects: el.getScene().render.objects.length },
      label: el.shadowRoot.querySelector('canvas').getAttribute('aria-label'),
      viewButton: el.shadowRoot.querySelector('.controls [data-action="view"]').textContent,
    };
  });
  expect(out.props).toEqual({ preset: 'default', src: null, loading: 'eager', posterTime: 0, view: 'raymarch', autoplay: false, controls: false });
  expect(out.reflected).toEqual(['', '0.5', 'points']);
  expect(out.cigarette).toBe(2);
  expect(out.afterPreset.emitters).toBe(2);
  expect(out.afterPreset.object).toBe('cylinder');
  expect(out.afterSrc).toEqual({ emitters: 1, objects: 3 });
  expect(out.label).toBe('Gas in a turbulent wind: the scene default');
  expect(out.viewButton).toBe('View: points');
  expect(errors).toEqual([]);
});

// Playwright's own `test`: the page as a machine that draws in software opens it, in the lighter version.
lighterTest('the view button names the view shown: in software the lighter version\'s points, and a click brings the volume', async ({ page }) => {
  const errors = collectErrors(page);
  await bare(page, 'view-button', '<wind-field id="p" preset="default" controls loading="eager" style="width: 320px"></wind-field>');
  await page.evaluate(() => document.querySelector('#p').ready);
  const button = page.locator('#p').getByRole('button', { name: /^View: / });
  await expect(button).toHaveText('View: points');
  await button.click();
  await expect(button).toHaveText('View: volume');
  expect(await page.evaluate(() => document.querySelector('#p').view)).toBe('raymarch');
  expect(errors).toEqual([]);
});

test('with reduced motion an autoplay player waits at its poster time with its play button', async ({ page }) => {
  const errors = collectErrors(page);
  await page.emulateMedia({ reducedMotion: 'reduce' });
  await bare(page, 'calm', '<wind-field id="p" preset="default" autoplay poster-time="0.5" style="width: 240px"></wind-field>');
  const time = await page.evaluate(async () => {
    const el = document.querySelector('#p');
    await el.ready;
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    return el.stats().time;
  });
  expect(time).toBeCloseTo(30 * 0.016666, 6);
  await expect(page.locator('#p').locator('button.play')).toBeVisible();
  await page.locator('#p').locator('button.play').click();
  await expect.poll(() => page.evaluate(() => document.querySelector('#p').stats().time)).toBeGreaterThan(time);
  expect(errors).toEqual([]);
});

test('without WebGL a player reports an error instead of an endless wait', async ({ page }) => {
  await page.addInitScript(() => {
    HTMLCanvasElement.prototype.getContext = () => null;
    // Listening from the start: the player may fail before the test's code runs.
    window.playerErrors = [];
    document.addEventListener('error', (e) => e.detail && window.playerErrors.push(e.detail.message), true);
  });
  await bare(page, 'nogl', '<wind-field id="p" preset="default" loading="eager" style="width: 240px"></wind-field>');
  const out = await page.evaluate(async () => {
    const el = document.querySelector('#p');
    const ready = await el.ready.then(() => 'resolved', (e) => e.message);
    return { ready, event: window.playerErrors[0], alert: el.shadowRoot.querySelector('[role=alert]').textContent };
  });
  expect(out.ready).toMatch(/^could not start the player/);
  expect(out.event).toBe(out.ready);
  expect(out.alert).toBe(out.ready);
});
