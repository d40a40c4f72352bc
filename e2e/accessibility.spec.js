// Accessibility: axe-core finds no serious or critical violation on any page, with its players
// and panels loaded (the playground also with its panel collapsed, as on a phone); the
// canvases carry text alternatives naming their scenes.
import { test, expect } from './helpers.js';
import AxeBuilder from '@axe-core/playwright';

/** The page's serious and critical violations, one line each (rule, impact, the first targets). */
async function violations(page) {
  // The players paused first: axe reads the page, which frames drawn in software would hold up.
  await page.evaluate(() => {
    window.windfield?.pause?.();
    for (const el of document.querySelectorAll('wind-field')) el.pause?.();
  });
  const { violations: found } = await new AxeBuilder({ page }).analyze();
  return found
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.id} (${v.impact}): ${v.help} at ${v.nodes.slice(0, 3).map((n) => n.target.join(' > ')).join(', ')}`);
}

const pages = {
  'playground (index.html)': {
    path: './',
    ready: async (page) => {
      await page.waitForFunction(() => window.windfield !== undefined);
      await page.evaluate(() => window.windfield.ready);
      await expect(page.locator('.lil-gui.lil-root')).toBeVisible();
    },
  },
  'field explorer (field.html)': {
    path: './field.html',
    ready: async (page) => {
      await page.waitForFunction(() => window.windfield !== undefined);
      await page.evaluate(() => window.windfield.ready);
    },
  },
  'classroom (classroom.html)': {
    path: './classroom.html',
    ready: async (page) => {
      await page.waitForFunction(() => window.classroom?.ready);
      await page.evaluate(() => window.classroom.ready);
      await page.evaluate(() => document.querySelector('#carried').scrollIntoView());
      await page.evaluate(() => window.classroom.sideBySide);
    },
  },
  'embedding guide (embed.html)': {
    path: './embed.html',
    ready: async (page) => {
      await page.evaluate(() => Promise.all([...document.querySelectorAll('wind-field')].map((p) => p.ready)));
    },
  },
};

for (const [name, { path, ready }] of Object.entries(pages)) {
  test(`axe: no serious or critical violation on the ${name}`, async ({ page }) => {
    await page.goto(path);
    await ready(page);
    expect(await violations(page)).toEqual([]);
  });
}

test('axe: the playground on a phone, panel collapsed and opened', async ({ page }) => {
  await page.setViewportSize({ width: 390, height: 844 });
  await page.goto('./');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  expect(await violations(page)).toEqual([]);
  await page.locator('.lil-gui.lil-root > .lil-title').click();
  await expect(page.locator('.lil-gui.lil-root > .lil-title')).toHaveAttribute('aria-expanded', 'true');
  // lil-gui fades the panel in from the next frame on, over 300 ms: axe checks the colours once
  // it has ended (mid-fade, the half-transparent text fails color-contrast now and then).
  await page.evaluate(async () => {
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    const children = document.querySelector('.lil-gui.lil-root > .lil-children');
    // An animation replaced before its end rejects `finished` (AbortError): the next one counts.
    await Promise.all(children.getAnimations().map((a) => a.finished.catch(() => {})));
  });
  await expect(page.locator('.lil-gui.lil-root')).not.toHaveClass(/\blil-transition\b/);
  expect(await violations(page)).toEqual([]);
});

test('canvases name what they show; players\' controls are labelled', async ({ page }) => {
  await page.goto('./?preset=cigarette');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await expect(page.locator('#canvas')).toHaveAttribute('aria-label', /the cigarette smoke scene/);
  await expect(page.locator('#canvas')).toHaveRole('img');
  await page.goto('./embed.html');
  const b = page.locator('#b');
  await expect(b.locator('canvas')).toHaveAccessibleName('Gas in a turbulent wind: the scene default');
  for (const label of ['Play', 'Step once', 'Play the scene default']) {
    await expect(b.getByRole('button', { name: label, exact: true })).toBeVisible();
  }
  // The view button names the view shown: the volume, or the lighter version's points.
  await expect(b.getByRole('button', { name: /^View: (volume|points)$/ })).toBeVisible();
});
