// Good on any machine: these tests run where the browser draws WebGL in software (SwiftShader),
// as on GPU-blocked laptops, virtual machines and remote desktops, and check what a visitor
// there gets: the lighter version and its notice, frames that keep coming with as many steps as
// their time allows, input handled while the worker steps, every scene's gas after its click,
// stirring at any frame rate, an honest status line, a phone's layout, a clean console, reduced
// motion and hidden tabs. Frames and their times are counted on Playwright's clock, not timed
// (helpers.js): `npm run bench` measures the rates and delays (docs/BENCHMARKS.md, "The page's
// pace"). Most use Playwright's own `test` (no full-version fixture: see helpers.js).
import { test } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { expect, test as fullTest, collectErrors, holdClock, nextFrame, presetFile, toSegment, worldAt } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const root = new URL('../', import.meta.url);
const catalog = JSON.parse(readFileSync(new URL('public/presets.json', root), 'utf8')).presets;
const smallPlume = JSON.parse(readFileSync(new URL('tests/fixtures/small-plume.json', root), 'utf8'));

async function open(page, url = './') {
  await page.goto(url);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

/**
 * The small plume of the unit tests as a playground link (`query` first). Its steps take about
 * 0.1 ms each in the worker here, a hundredth of what the budget of a frame 250 ms long on the
 * page's clock allows them (0.8 of its time, over its 15 steps): what a frame takes depends on
 * the frame's time alone, on any machine.
 */
const smallPlumeLink = async (query) => `./${query}#${await encodeScene(smallPlume)}`;

test('in software, the default scene gets the lighter version, says so, and its frames keep coming with the steps in them', async ({ page }) => {
  await page.clock.install();
  await open(page);
  const notice = page.locator('#message');
  await expect(notice).toContainText('This browser draws 3-D in software: showing a lighter version.');
  await expect(notice.locator('summary')).toHaveText('Details');
  const info = await page.evaluate(() => window.windfield.stats());
  expect(info.software).toBe(true);
  expect(info.lighter.reason).toBe('software');
  expect(info.lighter.gaveUp.length).toBeGreaterThan(0);
  expect(info.stepper).toBe('cpu');
  // On the page's clock: every tenth of a second, a frame, and simulated time in it.
  await holdClock(page);
  let last = await page.evaluate(() => window.windfield.stats());
  for (let k = 0; k < 5; k++) {
    const s = await nextFrame(page, 100);
    expect(s.time).toBeGreaterThan(last.time);
    last = s;
  }
});

test('a frame takes as many steps as its time allows: at 4 frames a second the simulated time keeps up with the clock; at 1 a second each frame takes the most a frame may and the rest is let go', async ({ page }) => {
  await page.clock.install();
  const { dt } = smallPlume.simulation;
  /**
   * The steps each frame took over `frames` frames `ms` apart on the page's clock (its animation
   * frames coming as the frames are drawn), after `warm` frames.
   */
  const stepsPerFrame = async (fps, ms, frames, warm) => {
    await open(page, await smallPlumeLink(`?fps=${fps}`));
    await holdClock(page);
    for (let k = 0; k < warm; k++) await nextFrame(page, ms, { jump: true });
    let before = await page.evaluate(() => window.windfield.stats());
    const steps = [];
    for (let k = 0; k < frames; k++) {
      const s = await nextFrame(page, ms, { jump: true });
      expect(s.frames, 'one frame each time it is due').toBe(before.frames + 1);
      steps.push(Math.round((s.time - before.time) / dt));
      before = s;
    }
    return steps;
  };
  // 4 a second: 15 steps of 1/60 s a frame.
  const quarter = await stepsPerFrame(4, 250, 20, 3);
  console.log(`4 frames a second: steps ${quarter.join(' ')}`);
  const taken = quarter.reduce((a, b) => a + b, 0);
  expect(Math.abs(taken * dt - (20 * 250) / 1000)).toBeLessThanOrEqual(dt);
  for (const n of quarter) expect([15, 16]).toContain(n);
  // 1 a second: the most a frame may take, 30 steps, half a second; the rest of each second is
  // let go, not owed to the next.
  const second = await stepsPerFrame(1, 1000, 3, 1);
  console.log(`1 frame a second: steps ${second.join(' ')}`);
  expect(second).toEqual([30, 30, 30]);
});

test('a pointer event is handled while the worker steps', async ({ page }) => {
  await open(page);
  await page.evaluate(() => window.windfield.pause());
  await page.evaluate(() => {
    window.stepping = false;
    window.handled = [];
    document.querySelector('#canvas').addEventListener('pointermove', () => window.handled.push(window.stepping));
    // Steps enough to outlast a few pointer moves wherever they run (a second or so here).
    window.stepping = true;
    window.stepped = window.windfield.step(600).then(() => { window.stepping = false; });
  });
  const box = await page.locator('#canvas').boundingBox();
  for (let k = 0; k < 3; k++) await page.mouse.move(box.x + 100 + 20 * k, box.y + box.height / 2);
  const handled = await page.evaluate(() => window.handled);
  await page.evaluate(() => window.stepped);
  expect(handled).toEqual([true, true, true]);
});

test('a picker click shows gas for every preset: the scene\'s own, in a frame drawn after the click', async ({ page }) => {
  test.setTimeout(240_000);
  await open(page);
  for (const { name } of catalog) {
    const card = page.locator(`#picker [data-preset="${name}"]`);
    const before = await page.evaluate(() => window.windfield.stats().frames);
    await card.click();
    // The first frame drawn after the click with gas in it (the scene's own, not the poster and
    // not the scene before, whose frames go on until the new one is ready; each preset's seed
    // differs from the one before it in the picker). The wait is a guard against a hang only:
    // `npm run bench` times it (`preset_first_gas_ms_max`).
    await page.waitForFunction(({ frames, preset, seed }) => {
      const s = window.windfield.stats();
      return new URLSearchParams(location.search).get('preset') === (preset === 'default' ? null : preset)
        && window.windfield.getScene()?.seed === seed && s.frames > frames && s.blobs > 0;
    }, { frames: before, preset: name, seed: presetFile(name).seed }, { timeout: 60_000, polling: 50 });
  }
});

test('stirring at 2 frames a second pushes the gas aside, and a drag while paused is used by the next steps', async ({ page }) => {
  await open(page, './?fps=2');
  await page.locator('#stir').click();
  const box = await page.locator('#canvas').boundingBox();
  const [y, x0, x1] = [box.height * 0.4, box.width * 0.3, box.width * 0.6];
  /** The drag's ends in the world, on the plane through the camera's target. */
  const { camera } = await page.evaluate(() => window.windfield.exportBlobs({ width: 32, height: 24 }));
  const [a, b] = [worldAt(camera, box.width, box.height, x0, y), worldAt(camera, box.width, box.height, x1, y)];
  /** Along the drag (m) on average, for the blobs within 0.15 m of its line; and their count. */
  const band = async () => {
    const list = await page.evaluate(() => window.windfield.exportBlobs({ width: 32, height: 24 }));
    const dir = b.map((v, i) => v - a[i]);
    const len = Math.hypot(...dir);
    const near = list.blobs.filter((blob) => toSegment(blob.center, a, b) < 0.15);
    const along = near.reduce((sum, blob) => sum + blob.center.reduce((d, v, i) => d + (v - a[i]) * dir[i], 0) / len, 0);
    return { along: along / Math.max(near.length, 1), n: near.length };
  };
  /** A drag from `from` to `to` (canvas pixels) along the line at height y. */
  const drag = async (from = x0, to = x1) => {
    await page.mouse.move(box.x + from, box.y + y);
    await page.mouse.down();
    for (let k = 1; k <= 20; k++) {
      await page.mouse.move(box.x + from + ((to - from) * k) / 20, box.y + y);
      await page.waitForTimeout(25);
    }
    await page.mouse.up();
  };
  /**
   * Until the scene's time has reached `from` + `seconds`: as long as it takes in real time on a
   * fast machine, longer where the steps do not keep up (the gas moves with the simulated time).
   */
  const until = (from, seconds) => page.waitForFunction((t) => window.windfield.stats().time >= t, from + seconds, { timeout: 30_000, polling: 50 });
  /**
   * The band and the scene's time, read paused so the two agree: at two frames a second a
   * window's end may fall half a second either way, so the windows are measured, not assumed.
   * step(0) waits for a frame still in flight when the pause came, so the time read is final.
   */
  const pausedBand = async () => {
    const time = await page.evaluate(async () => {
      await window.windfield.pause();
      await window.windfield.step(0);
      return window.windfield.stats().time;
    });
    return { ...(await band()), time };
  };
  const play = () => page.evaluate(() => window.windfield.play());
  // A plume to stir, then frames at two a second.
  await page.evaluate(async () => { await window.windfield.pause(); await window.windfield.step(200); });
  const calm0 = await pausedBand();
  await play();
  await until(calm0.time, 1);
  const calm1 = await pausedBand();
  await play();
  await drag();
  await until(calm1.time, 0.5);
  const stirred = await pausedBand();
  /** The band's drift without the drag, m/s of simulated time, and what it makes in the stirred window. */
  const calmRate = Math.abs(calm1.along - calm0.along) / (calm1.time - calm0.time);
  const calmShift = calmRate * (stirred.time - calm1.time);
  const stirShift = stirred.along - calm1.along;
  console.log(`2 fps: the gas by the drag moved ${stirShift.toFixed(3)} m along it in ${(stirred.time - calm1.time).toFixed(2)} s, ${calmShift.toFixed(3)} m in as long without it (${calm1.n} blobs; calm window ${(calm1.time - calm0.time).toFixed(2)} s)`);
  expect(calm1.n).toBeGreaterThan(200);
  expect(stirShift).toBeGreaterThan(0.05);
  // Twice the drift the plume makes in as long.
  expect(stirShift).toBeGreaterThan(2 * calmShift);
  // Paused: the drag's motion waits for the steps, which give it to the gas. First the steps
  // give the gas all of the first drag's motion (what was left over would move it here too);
  // then a drag back the other way, over the gas the first piled at the far end.
  await play();
  await until(calm1.time, 1.25);
  const { time: still, ...before } = await pausedBand();
  await drag(x1, x0);
  await page.waitForTimeout(500);
  expect(await page.evaluate(() => window.windfield.stats().time)).toBe(still);
  await page.evaluate(() => window.windfield.step(10));
  const after = await band();
  console.log(`paused: the drag back moved the gas ${(before.along - after.along).toFixed(3)} m back along it in the next 10 steps (${before.n} blobs)`);
  expect(before.along - after.along).toBeGreaterThan(0.05);
});

test('the status line counts the frames drawn: 0.2 a second shows as 0.2', async ({ page }) => {
  await page.clock.install();
  await open(page, './?fps=0.2');
  await holdClock(page);
  // Four frames 5 s apart on the page's clock.
  for (let k = 0; k < 4; k++) await nextFrame(page, 5000, { jump: true });
  const { fps } = await page.evaluate(() => window.windfield.stats());
  expect(fps).toBeCloseTo(0.2, 6);
  await expect(page.locator('#status')).toContainText(/ 0\.2 fps/);
});

fullTest('four scene switches leave no notice that contradicts the status line', async ({ page }) => {
  const errors = collectErrors(page);
  await open(page);
  for (const name of ['steam-mug', 'cigarette', 'default', 'sphere-smoke']) {
    await page.locator(`#picker [data-preset="${name}"]`).click();
    await page.waitForFunction((n) => new URLSearchParams(location.search).get('preset') === (n === 'default' ? null : n), name);
    await page.evaluate(() => window.windfield.ready);
    await page.waitForTimeout(1500);
  }
  await expect(page.locator('#message')).toBeHidden();
  expect(errors).toEqual([]);
});

test('a view and a quality the link asks for are neither given up nor told as given up', async ({ page }) => {
  await open(page, './?view=exact&quality=high');
  const notice = page.locator('#message');
  await expect(notice).toContainText('showing a lighter version');
  const { lighter } = await page.evaluate(() => window.windfield.stats());
  expect(lighter.gaveUp.length).toBeGreaterThan(0);
  const told = await notice.textContent();
  for (const g of lighter.gaveUp) expect(told).toContain(`Given up: ${g}.`);
  expect(told).not.toContain('points view');
  expect(told).not.toContain('draft quality');
});

test('a choice made in the panel holds for the rest of the visit; the full version is one click away', async ({ page }) => {
  await open(page);
  expect(await page.evaluate(() => window.windfield.stats().lighter?.gaveUp.some((g) => g.includes('points')))).toBe(true);
  await page.keyboard.press('v');
  await page.reload();
  await open(page, page.url());
  const chosen = await page.evaluate(() => window.windfield.stats());
  expect(chosen.lighter.gaveUp.some((g) => g.includes('points'))).toBe(false);
  await page.locator('#message').getByRole('button', { name: 'Show the full version' }).click();
  await expect.poll(() => page.evaluate(() => window.windfield.stats().lighter)).toBe(null);
  await page.reload();
  await open(page, page.url());
  expect(await page.evaluate(() => window.windfield.stats().lighter)).toBe(null);
  await expect(page.locator('#message')).toBeHidden();
});

test('a hidden page neither steps nor draws', async ({ page }) => {
  await page.clock.install();
  await open(page);
  const hide = (state) => page.evaluate((s) => {
    Object.defineProperty(document, 'visibilityState', { value: s, configurable: true });
    document.dispatchEvent(new Event('visibilitychange'));
  }, state);
  await holdClock(page);
  await nextFrame(page, 100, { jump: true });
  await hide('hidden');
  const a = await page.evaluate(() => window.windfield.stats());
  // Two seconds of a 60 Hz display's frames on the page's clock, each a turn of the loop.
  for (let k = 0; k < 20; k++) await page.clock.runFor(100);
  const b = await page.evaluate(() => window.windfield.stats());
  expect(b.time).toBe(a.time);
  expect(b.frames).toBe(a.frames);
  await hide('visible');
  expect((await nextFrame(page, 100, { jump: true })).time).toBeGreaterThan(a.time);
});

test('under reduced motion the playground starts paused on the scene at its render.time, with a Play button', async ({ page }) => {
  await page.emulateMedia({ reducedMotion: 'reduce' });
  await page.clock.install();
  await open(page);
  await expect.poll(() => page.evaluate(() => window.windfield.stats().time), { timeout: 60_000 }).toBeCloseTo(4, 1);
  const play = page.locator('#play');
  await expect(play).toBeVisible();
  await expect(play).toHaveText('Play');
  await holdClock(page);
  const t = await page.evaluate(() => window.windfield.stats().time);
  // A second of the display's frames on the page's clock: the scene stays where it is.
  for (let k = 0; k < 10; k++) await page.clock.runFor(100);
  expect(await page.evaluate(() => window.windfield.stats().time)).toBe(t);
  await play.click();
  expect((await nextFrame(page, 100)).time).toBeGreaterThan(t);
});

test.describe('on a phone', () => {
  test.use({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  test('the view is in the first screenful, the status line beside the picture, the cards\' texts whole lines', async ({ page }) => {
    await open(page);
    await page.evaluate(() => window.windfield.pause());
    const canvas = await page.locator('#canvas').boundingBox();
    expect(canvas.y).toBeGreaterThanOrEqual(0);
    expect(canvas.y + canvas.height).toBeLessThanOrEqual(844);
    expect(canvas.height).toBeGreaterThan(240);
    await expect(page.locator('.keyboard-hint').first()).toBeHidden();
    const status = await page.locator('#status').boundingBox();
    const overlaps = status.y < canvas.y + canvas.height && status.y + status.height > canvas.y
      && status.x < canvas.x + canvas.width && status.x + status.width > canvas.x;
    expect(overlaps).toBe(false);
    const cut = await page.locator('.picker-quote').evaluateAll((quotes) => quotes.map((q) => {
      const line = parseFloat(getComputedStyle(q).lineHeight);
      const lines = q.clientHeight / line;
      return Math.abs(lines - Math.round(lines));
    }));
    for (const fraction of cut) expect(fraction).toBeLessThan(0.05);
  });
});

test('no warnings or errors in the console while the playground and a player load and draw', async ({ page }) => {
  const messages = [];
  page.on('console', (m) => { if (m.type() === 'warning' || m.type() === 'error') messages.push(m.text()); });
  page.on('pageerror', (e) => messages.push(e.message));
  await open(page, './?view=raymarch');
  await page.evaluate(() => window.windfield.step(30));
  await page.goto('./embed.html');
  const player = page.locator('wind-field').first();
  await player.evaluate((el) => el.ready);
  // Three frames drawn after it was ready.
  const drawn = await player.evaluate((el) => el.stats().frames);
  await player.evaluate((el) => el.play());
  await expect.poll(() => player.evaluate((el) => el.stats().frames)).toBeGreaterThanOrEqual(drawn + 3);
  expect(messages).toEqual([]);
});
