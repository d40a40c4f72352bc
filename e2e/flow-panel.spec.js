// The playground's panel edits the flow (paper §7, the large scales solved on a coarse grid):
// switching it on adds a flow round the emitters, its cells, cooling and faces change the
// scene the page reports, an emitter's temperature is edited with the emitter, and switching
// it off keeps it in the scene without effect. The presets that carry a flow load with it, and
// their flow goes to the GPU with their gas.
import { readFileSync } from 'node:fs';
import { expect, test, collectErrors, openFolder, presetFile, setNumber } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const smallPlume = JSON.parse(readFileSync(new URL('../tests/fixtures/small-plume.json', import.meta.url), 'utf8'));

/** The presets with a flow. */
const FLOW_PRESETS = ['candle', 'ceiling-smoke', 'cylinder-wake'];

async function open(page, url) {
  await page.goto(url);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

const sidesPerCell = (flow) => flow.cells.map((n, a) => (flow.box[a + 3] - flow.box[a]) / n);

test('the panel switches the flow on and off and edits its cells, cooling, faces and an emitter\'s temperature', async ({ page }) => {
  const errors = collectErrors(page);
  await open(page, `./?view=points#${await encodeScene(smallPlume)}`);
  await page.evaluate(() => window.windfield.pause());
  const scene = () => page.evaluate(() => window.windfield.getScene());
  expect((await scene()).flow).toBeUndefined();

  const toggle = async (on) => {
    const f = await openFolder(page, 'Flow (§7)');
    const box = f.locator('.lil-controller', { hasText: 'flow (physical large scales)' }).locator('input');
    await (on ? box.check() : box.uncheck());
  };
  await toggle(true);
  await expect.poll(async () => (await scene()).flow?.enabled).toBe(true);
  const added = (await scene()).flow;
  const [cx, cy, cz] = smallPlume.emitters[0].center;
  expect(added.box[0] < cx && cx < added.box[3] && added.box[2] < cz && cz < added.box[5]).toBe(true);
  expect(added.box[1] <= cy && cy < added.box[4]).toBe(true);
  const h = sidesPerCell(added);
  for (const s of h) expect(Math.abs(s - h[0])).toBeLessThanOrEqual(0.01 * h[0]);

  await setNumber(await openFolder(page, 'Flow (§7)'), 'cooling (1/s)', 1.5);
  await expect.poll(async () => (await scene()).flow.cooling).toBe(1.5);

  await (await openFolder(page, 'Flow (§7)')).locator('.lil-controller', { hasText: 'cells (longest side)' }).locator('select').selectOption('16');
  await expect.poll(async () => Math.max(...(await scene()).flow.cells)).toBe(16);
  const refit = (await scene()).flow;
  const h16 = sidesPerCell(refit);
  for (const s of h16) expect(Math.abs(s - h16[0])).toBeLessThanOrEqual(0.01 * h16[0]);
  expect(refit.cooling).toBe(1.5);

  // The faces across y alone closed, then all three: one word where the three agree.
  const faces = async (axis) => (await openFolder(page, 'Flow (§7)')).locator('.lil-controller', { hasText: `faces across ${axis}` }).locator('select');
  await (await faces('y')).selectOption('closed');
  await expect.poll(async () => (await scene()).flow.faces).toEqual({ x: 'open', y: 'closed', z: 'open' });
  await (await faces('x')).selectOption('closed');
  await (await faces('z')).selectOption('closed');
  await expect.poll(async () => (await scene()).flow.faces).toBe('closed');

  await openFolder(page, 'Emitters');
  await setNumber(await openFolder(page, 'emitters 1: disk'), 'temperature (K over the air)', 40);
  await expect.poll(async () => (await scene()).emitters[0].temperature).toBe(40);

  await toggle(false);
  await expect.poll(async () => (await scene()).flow?.enabled).toBe(false);
  expect((await scene()).flow.cooling).toBe(1.5);
  await toggle(true);
  await expect.poll(async () => (await scene()).flow?.enabled).toBe(true);
  await page.evaluate(() => window.windfield.step(5));
  expect(errors).toEqual([]);
});

for (const name of FLOW_PRESETS) {
  test(`preset ${name} loads with its flow and steps without an error, in the worker and on the GPU`, async ({ page }) => {
    const errors = collectErrors(page);
    await open(page, `./?preset=${name}&view=points`);
    await page.evaluate(() => window.windfield.pause());
    const loaded = await page.evaluate(async () => {
      const w = window.windfield;
      await w.step(30);
      // The GPU takes the gas and its flow, and steps both.
      const stepper = await w.setStepper('gpu');
      await w.step(5);
      const grid = await w.exportFlow();
      const onGpu = { stepper, flowStepper: w.stats().flowStepper, finite: grid.velocity.every(Number.isFinite), blobs: w.stats().blobs };
      return { scene: w.getScene(), blobs: w.stats().blobs, onGpu };
    });
    expect(loaded.onGpu).toEqual({ stepper: 'gpu', flowStepper: 'gpu', finite: true, blobs: loaded.blobs });
    const file = presetFile(name);
    expect(loaded.scene.seed).toBe(file.seed);
    expect(loaded.scene.flow.box).toEqual(file.flow.box);
    expect(loaded.scene.flow.cells).toEqual(file.flow.cells);
    expect(loaded.blobs).toBeGreaterThan(0);
    expect(errors).toEqual([]);
  });
}
