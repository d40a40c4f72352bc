// What a newcomer meets: the playground opens on smoke, the picker loads every preset, edits keep
// the gas, the pointer stirs it, the camera stays above the floor, the status line tells the
// truth, notices stay, and no page overflows on a phone.
import { readFileSync } from 'node:fs';
import { expect, test, canvasLuminance, collectErrors, holdClock, nextFrame, openFolder, presetFile, setNumber, toSegment, worldAt } from './helpers.js';

const root = new URL('../', import.meta.url);
const catalog = JSON.parse(readFileSync(new URL('public/presets.json', root), 'utf8')).presets;

async function open(page, url = './?view=points') {
  await page.goto(url);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

/**
 * Holds back the page's requests for `pattern` until `release()`: `asked` resolves when the page
 * asks for the file; `release` lets the request through and resolves once the page has the
 * whole answer and two frames have passed (time for its handlers to run).
 */
async function holdFile(page, pattern) {
  let asked;
  let go;
  const askedP = new Promise((r) => { asked = r; });
  const released = new Promise((r) => { go = r; });
  await page.route(pattern, async (route) => {
    asked();
    await released;
    await route.continue();
  });
  const release = async () => {
    const answered = page.waitForResponse((r) => r.url().includes(pattern.replace('**/', '')));
    go();
    await (await answered).finished();
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  };
  return { asked: askedP, release };
}

/** Whether every value `want` gives is in `have` (a scene normalised by the core adds defaults). */
function holds(have, want, path = 'scene') {
  if (Array.isArray(want) || (want && typeof want === 'object')) {
    return Object.entries(want).every(([k, v]) => have && holds(have[k], v, `${path}.${k}`));
  }
  return have === want;
}

test('the playground opens on smoke: at least 20,000 blobs by t = 4 s, from the default scene', async ({ page }) => {
  const errors = collectErrors(page);
  await open(page);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    await w.pause();
    const scene = w.getScene();
    const { time } = w.stats();
    await w.step(Math.round((4 - time) / scene.simulation.dt));
    return { scene, stats: w.stats() };
  });
  expect(holds(out.scene, presetFile('default'))).toBe(true);
  expect(out.stats.time).toBeCloseTo(4, 1);
  expect(out.stats.blobs).toBeGreaterThanOrEqual(20_000);
  // Many small blobs, slow diffusion, a floor and a light: the presets' lessons.
  expect(out.scene.emitters[0].sigma0).toBeLessThan(0.01);
  expect(out.scene.gas.diffusion).toBeLessThan(1e-4);
  expect(out.scene.render.objects.some((o) => o.type === 'plane')).toBe(true);
  expect(out.scene.render.lights.length).toBeGreaterThan(0);
  expect(errors).toEqual([]);
});

test('the picker loads each preset by click or keyboard and puts it in the URL', async ({ page }) => {
  const errors = collectErrors(page);
  await open(page);
  await page.evaluate(() => window.windfield.pause());
  const cards = page.locator('#picker [role="radio"]');
  await expect(cards).toHaveCount(catalog.length);
  for (const [i, { name, title }] of catalog.entries()) {
    const card = cards.nth(i);
    await expect(card).toContainText(title);
    if (i % 2) {
      await card.click();
    } else {
      await card.focus();
      await page.keyboard.press('Enter');
    }
    await expect(card).toHaveAttribute('aria-checked', 'true');
    await expect.poll(() => page.evaluate(() => window.windfield.getScene().seed)).toBe(presetFile(name).seed);
    const scene = await page.evaluate(() => window.windfield.getScene());
    expect(holds(scene, presetFile(name)), name).toBe(true);
    const url = new URL(page.url());
    expect(url.searchParams.get('preset')).toBe(name === 'default' ? null : name);
  }
  // A card chosen before the last one's scene was ready: the later scene loads, and nothing
  // says a load failed.
  await cards.nth(1).click();
  await cards.nth(2).click();
  await expect.poll(() => page.evaluate(() => window.windfield.getScene().seed)).toBe(presetFile(catalog[2].name).seed);
  await expect(page.locator('#message')).toBeHidden();
  // A card whose file arrives after the next card's scene is shown: the later choice stays.
  const slow = catalog[3].name;
  const held = await holdFile(page, `**/scenes/${slow}.json`);
  await cards.nth(3).click();
  await held.asked;
  await cards.nth(4).click();
  await expect.poll(() => page.evaluate(() => window.windfield.getScene().seed)).toBe(presetFile(catalog[4].name).seed);
  await held.release();
  // Had the late file been loaded, its scene's poster would show at once, before the load.
  expect(await page.locator('#poster').getAttribute('src')).not.toContain(`thumbs/${slow}.png`);
  expect(await page.evaluate(() => window.windfield.getScene().seed)).toBe(presetFile(catalog[4].name).seed);
  await expect(cards.nth(4)).toHaveAttribute('aria-checked', 'true');
  await expect(page.locator('#message')).toBeHidden();
  expect(new URL(page.url()).searchParams.get('preset')).toBe(catalog[4].name);
  // Arrow keys move between the cards.
  await cards.nth(0).focus();
  await page.keyboard.press('ArrowRight');
  await expect(cards.nth(1)).toBeFocused();
  expect(errors).toEqual([]);
});

test('a card chosen while the link\'s preset is still on its way: the card\'s scene is shown, and nothing says a load failed', async ({ page }) => {
  const errors = collectErrors(page);
  const [linked, chosen] = [catalog[2].name, catalog[5].name];
  const held = await holdFile(page, `**/scenes/${linked}.json`);
  await page.goto(`./?view=points&preset=${linked}`);
  await held.asked;
  const card = page.locator('#picker [role="radio"]').nth(5);
  await card.click();
  await expect.poll(() => page.evaluate(() => window.windfield.getScene()?.seed)).toBe(presetFile(chosen).seed);
  await held.release();
  // The page's first scene settled (its controls are built then): the card's scene stays.
  await page.evaluate(() => window.windfield.ready);
  expect(await page.evaluate(() => window.windfield.getScene()?.seed)).toBe(presetFile(chosen).seed);
  await expect(card).toHaveAttribute('aria-checked', 'true');
  await expect(page.locator('#message')).toBeHidden();
  expect(new URL(page.url()).searchParams.get('preset')).toBe(chosen);
  expect(errors).toEqual([]);
});

test('a card chosen while the last scene\'s link is still being written keeps its preset in the URL', async ({ page }) => {
  // Each scene shown is compressed into the URL's hash; the test holds each compression until it
  // lets it go, in turn.
  await page.addInitScript(() => {
    const Real = window.CompressionStream;
    window.heldCompressions = [];
    window.CompressionStream = class {
      constructor(format) {
        const real = new Real(format);
        const gate = window.holdCompressions ? new Promise((r) => window.heldCompressions.push(r)) : null;
        this.writable = real.writable;
        this.readable = real.readable.pipeThrough(new TransformStream({ flush: () => gate }));
      }
    };
  });
  const errors = collectErrors(page);
  await open(page);
  await page.evaluate(() => window.windfield.pause());
  const before = new URL(page.url()).hash;
  const chosen = catalog[1].name;
  // An edit of the default scene: its hash is being written when the card is chosen.
  await page.evaluate(() => {
    window.holdCompressions = true;
    const scene = window.windfield.getScene();
    window.editShown = window.windfield.setScene({ ...scene, seed: scene.seed + 1 });
  });
  await expect.poll(() => page.evaluate(() => window.heldCompressions.length)).toBe(1);
  await page.locator('#picker [role="radio"]').nth(1).click();
  expect(new URL(page.url()).searchParams.get('preset')).toBe(chosen);
  // The edit's hash arrives after the card was chosen; then the card's scene loads, its own hash
  // held: the card's preset stays in the URL meanwhile.
  await page.evaluate(() => window.heldCompressions[0]());
  await expect.poll(() => page.evaluate(() => window.windfield.getScene().seed)).toBe(presetFile(chosen).seed);
  await expect.poll(() => page.evaluate(() => window.heldCompressions.length)).toBe(2);
  expect(new URL(page.url()).searchParams.get('preset')).toBe(chosen);
  // Then the card's own scene is written.
  await page.evaluate(() => window.heldCompressions[1]());
  await expect.poll(() => new URL(page.url()).hash).not.toBe('');
  const url = new URL(page.url());
  expect(url.searchParams.get('preset')).toBe(chosen);
  expect(url.hash).not.toBe(before);
  expect(errors).toEqual([]);
});

test('an edit of a wind primitive and of an emitter keeps the blob count and the time', async ({ page }) => {
  await open(page);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    w.pause();
    await w.step(90);
    const before = w.stats();
    const scene = w.getScene();
    scene.wind[0].velocity = [0.3, 0.1, 0];
    await w.editScene(scene);
    const afterWind = w.stats();
    scene.emitters[0].center = [0.2, 0.62, 0];
    await w.editScene(scene);
    const afterEmitter = w.stats();
    return { before, afterWind, afterEmitter, scene: w.getScene() };
  });
  for (const after of [out.afterWind, out.afterEmitter]) {
    expect(after.blobs).toBe(out.before.blobs);
    expect(after.time).toBe(out.before.time);
  }
  expect(out.scene.wind[0].velocity).toEqual([0.3, 0.1, 0]);
  expect(out.scene.emitters[0].center).toEqual([0.2, 0.62, 0]);
  // The same from the panel: an emitter's rate typed in the scene editor.
  await openFolder(page, 'Emitters');
  await setNumber(await openFolder(page, 'emitters 1: sphere'), 'rate', 5000);
  await expect.poll(() => page.evaluate(() => window.windfield.getScene().emitters[0].rate)).toBe(5000);
  const afterPanel = await page.evaluate(() => window.windfield.stats());
  expect(afterPanel.blobs).toBe(out.before.blobs);
  expect(afterPanel.time).toBe(out.before.time);
});

test('a pointer stir moves blobs near it more than blobs far from it', async ({ page }) => {
  await open(page);
  const box = await page.locator('#canvas').boundingBox();
  const y = box.height / 2;
  const x0 = box.width / 2 - 30;
  let x1 = x0;
  /** Blob centres after 240 steps and 12 more, stirring meanwhile (a drag to the right) or not. */
  const run = async (stir) => {
    await page.evaluate(async () => {
      const w = window.windfield;
      w.pause();
      await w.setScene(w.getScene());
      await w.step(240);
    });
    if (!stir) return page.evaluate(async () => { await window.windfield.step(12); return window.windfield.exportBlobs({ width: 32, height: 24 }); });
    await page.mouse.move(box.x + x0, box.y + y);
    await page.mouse.down();
    for (let k = 0; k < 3; k++) {
      x1 += 2;
      await page.mouse.move(box.x + x1, box.y + y);
      await page.waitForTimeout(15);
    }
    // The steps are taken while the pointer moves on.
    const steps = page.evaluate(() => window.windfield.step(12));
    {
      let done = false;
      steps.then(() => { done = true; });
      while (!done && x1 < x0 + 120) {
        x1 += 2;
        await page.mouse.move(box.x + x1, box.y + y);
        await page.waitForTimeout(15);
      }
      await steps;
      await page.mouse.up();
    }
    return page.evaluate(async () => window.windfield.exportBlobs({ width: 32, height: 24 }));
  };
  const calm = await run(false);
  await page.keyboard.press('s');
  await expect(page.locator('#stir')).toHaveAttribute('aria-pressed', 'true');
  const stirred = await run(true);
  expect(stirred.blobs.length).toBe(calm.blobs.length);
  const a = worldAt(calm.camera, box.width, box.height, x0, y);
  const b = worldAt(calm.camera, box.width, box.height, x1, y);
  const near = [];
  const far = [];
  calm.blobs.forEach(({ center }, i) => {
    const d = toSegment(center, a, b);
    const moved = Math.hypot(...center.map((v, k) => v - stirred.blobs[i].center[k]));
    if (d < 0.1) near.push(moved);
    else if (d > 0.6) far.push(moved);
  });
  const mean = (list) => list.reduce((s, v) => s + v, 0) / list.length;
  expect(near.length).toBeGreaterThan(100);
  expect(far.length).toBeGreaterThan(100);
  expect(mean(near)).toBeGreaterThan(0.005);
  expect(mean(near)).toBeGreaterThan(10 * mean(far));
});

test('an upward orbit drag of 300 px leaves a view that is not black; the camera stays above the floor', async ({ page }) => {
  await open(page, './');
  await page.evaluate(async () => { window.windfield.pause(); await window.windfield.step(120); });
  const box = await page.locator('#canvas').boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height - 40;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let k = 1; k <= 10; k++) await page.mouse.move(x, y - 30 * k);
  await page.mouse.up();
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.waitForTimeout(300);
  const camera = (await page.evaluate(() => window.windfield.exportBlobs({ width: 32, height: 24 }))).camera;
  expect(camera.position[1]).toBeGreaterThan(0);
  const lum = await canvasLuminance(page, '#canvas');
  expect(lum.mean).toBeGreaterThan(10);
  expect(lum.std).toBeGreaterThan(3);
  // The keyboard orbits and zooms too, within the same limits.
  await page.locator('#canvas').focus();
  for (let k = 0; k < 40; k++) await page.keyboard.press('ArrowDown');
  for (let k = 0; k < 30; k++) await page.keyboard.press('-');
  const after = (await page.evaluate(() => window.windfield.exportBlobs({ width: 32, height: 24 }))).camera;
  expect(after.position[1]).toBeGreaterThan(0);
  const distance = Math.hypot(...after.position.map((v, a) => v - after.target[a]));
  // Zoom stays within four times the scene's camera distance of the target.
  const { position, target } = (await page.evaluate(() => window.windfield.getScene())).render.camera;
  expect(distance).toBeLessThanOrEqual(4 * Math.hypot(...position.map((v, a) => v - target[a])) + 1e-6);
});

test('the status line\'s frames per second agree with frames counted over its five seconds', async ({ page }) => {
  await page.clock.install();
  await open(page);
  await page.evaluate(() => window.windfield.play());
  await holdClock(page);
  // Frames at an uneven pace on the page's clock, each the moment the one before it was drawn
  // plus a gap from this list (ms): 10 frames a second on average.
  const gaps = [40, 90, 160, 60, 130, 120];
  const begun = [];
  let clock = await page.evaluate(() => performance.now());
  for (let k = 0; clock - (begun[0] ?? clock) < 6500; k++) {
    await nextFrame(page, gaps[k % gaps.length], { jump: true });
    clock += gaps[k % gaps.length];
    begun.push(clock);
  }
  const out = await page.evaluate(() => ({ reported: window.windfield.stats().fps, text: document.querySelector('#status').textContent }));
  // The frames begun in the last five seconds, over them.
  const counted = begun.filter((t) => t > clock - 5000).length / 5;
  console.log(`status line ${out.reported.toFixed(3)} frames a second, ${counted.toFixed(3)} counted`);
  expect(Math.abs(out.reported - counted)).toBeLessThanOrEqual(0.05 * counted);
  expect(out.text).toMatch(/\d+ fps \((limited by the worker’s step|limited by drawing the view|as fast as the display)\)/);
  expect(out.text).toMatch(/step \d+\.\d+ ms/);
  await expect(page.locator('#status')).toBeInViewport();
});

test('a damaged link\'s notice names the scene shown and stays until dismissed', async ({ page }) => {
  // The page's clock is Playwright's: it runs as real time does, and jumps ahead past every
  // timer that would hide a notice (a transient one goes after 4 s) without waiting for them.
  await page.clock.install();
  await open(page, './?preset=steam-mug#scene=1.garbage!!');
  const notice = page.locator('#message');
  await expect(notice).toContainText('could not be read');
  await expect(notice).not.toContainText('atob');
  await expect(notice).toContainText('the link is damaged or cut short');
  await page.clock.fastForward(10_500);
  await expect(notice).toBeVisible();
  const shown = await page.evaluate(() => window.windfield.getScene().seed);
  const named = (await notice.textContent()).match(/Showing (.*) instead/)[1];
  // The notice names the scene the view shows.
  expect(named).toContain('steam from a mug');
  expect(shown).toBe(presetFile('steam-mug').seed);
  await notice.getByRole('button', { name: /dismiss/i }).click();
  await expect(notice).toBeHidden();
});

test('an unknown preset\'s notice lists the scenes there are', async ({ page }) => {
  await open(page, './?preset=../scene.schema');
  const notice = page.locator('#message');
  await expect(notice).toContainText('There is no scene named "../scene.schema"');
  for (const { name } of catalog) await expect(notice).toContainText(name);
  expect((await page.evaluate(() => window.windfield.getScene())).seed).toBe(presetFile('default').seed);
});

test('the exported PNG of the view leaves the wind guides out', async ({ page }) => {
  await open(page);
  await page.evaluate(() => window.windfield.pause());
  // At full resolution, whatever pace the view kept in software while it loaded: the guides then
  // cover enough pixels to be seen.
  const sim = await openFolder(page, 'Simulation');
  await sim.locator('.lil-controller', { hasText: 'resolution' }).locator('select').selectOption({ label: '100 %' });
  await expect.poll(() => page.evaluate(() => window.windfield.stats().scale)).toBe(1);
  const shot = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r(document.querySelector('#canvas').toDataURL('image/png'))))));
  const withGuides = await shot();
  const [download] = await Promise.all([
    page.waitForEvent('download'),
    (async () => {
      await openFolder(page, 'Share and export');
      await page.locator('.lil-controller', { hasText: 'export PNG of view' }).click();
    })(),
  ]);
  const exported = `data:image/png;base64,${(await (await download.createReadStream()).toArray()).map((b) => Buffer.from(b)).reduce((a, b) => Buffer.concat([a, b])).toString('base64')}`;
  await page.keyboard.press('g');
  const withoutGuides = await shot();
  /** Pixels that differ between two PNG data URLs of one size. */
  const differing = (a, b) => page.evaluate(async (urls) => {
    const [p, q] = await Promise.all(urls.map(async (u) => {
      const img = new Image();
      img.src = u;
      await img.decode();
      const g = new OffscreenCanvas(img.width, img.height).getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, img.width, img.height).data;
    }));
    let n = 0;
    for (let i = 0; i < p.length; i += 4) if (p[i] !== q[i] || p[i + 1] !== q[i + 1] || p[i + 2] !== q[i + 2]) n += 1;
    return n;
  }, [a, b]);
  expect(await differing(exported, withGuides)).toBeGreaterThan(100);
  expect(await differing(exported, withoutGuides)).toBe(0);
});

test('the reference still is labelled with what it is', async ({ page }) => {
  await open(page);
  const time = await page.evaluate(async () => {
    window.windfield.pause();
    await window.windfield.setScene(window.windfield.getScene());
    await window.windfield.step(6);
    return window.windfield.stats().time;
  });
  await openFolder(page, 'Share and export');
  await page.locator('.lil-controller', { hasText: 'render still (CPU)' }).click();
  const figure = page.locator('#still-figure');
  await expect(figure).toBeVisible({ timeout: 60_000 });
  await expect(figure.locator('figcaption')).toContainText(`Reference still (CPU renderer), t = ${time.toFixed(2)} s, 480 × 360`);
  await figure.getByRole('button', { name: 'Close' }).click();
  await expect(figure).toBeHidden();
});

test.describe('on a phone', () => {
  test.use({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true });
  for (const path of ['./', './classroom.html', './field.html', './embed.html']) {
    test(`${path} does not overflow at 390×844`, async ({ page }) => {
      await page.goto(path);
      await page.waitForLoadState('load');
      await page.waitForTimeout(500);
      const { scroll, width } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, width: innerWidth }));
      expect(scroll).toBeLessThanOrEqual(width);
    });
  }
});
