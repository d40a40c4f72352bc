// The playground's scene picker: every preset of `presets.json` as a card with its
// thumbnail, its title and its line from the paper, chosen by click or from the keyboard (a
// radio group: arrow keys move, Enter or Space choose).

/** Preset names are file names in `scenes/`: lower-case letters, digits and hyphens. */
export const PRESET_NAME = /^[a-z0-9-]+$/;

/** The presets' catalogue (`presets.json`): [{name, title, quote, section}]. */
export async function presetCatalog(base = document.baseURI) {
  const response = await fetch(new URL('./presets.json', base));
  if (!response.ok) throw new Error(`the list of scenes could not be loaded (${response.status})`);
  const { presets } = await response.json();
  return presets;
}

/**
 * Fills `container` with a card per preset; `choose(name)` runs when one is chosen. Returns
 * `{select(name)}`, which marks the card of `name` (none for a scene that is not a preset).
 */
export function scenePicker(container, presets, choose) {
  const group = document.createElement('div');
  group.className = 'picker-cards';
  group.setAttribute('role', 'radiogroup');
  group.setAttribute('aria-label', 'Scenes');
  const cards = presets.map((preset) => {
    const card = document.createElement('button');
    card.type = 'button';
    card.className = 'picker-card';
    card.dataset.preset = preset.name;
    card.setAttribute('role', 'radio');
    card.setAttribute('aria-checked', 'false');
    card.tabIndex = -1;
    const image = document.createElement('img');
    image.src = new URL(`./scenes/thumbs/${preset.name}.png`, document.baseURI).href;
    image.alt = '';
    image.width = 96;
    image.height = 72;
    image.loading = 'lazy';
    const title = document.createElement('span');
    title.className = 'picker-title';
    title.textContent = preset.title;
    const quote = document.createElement('span');
    quote.className = 'picker-quote';
    quote.textContent = `“${preset.quote}” (${preset.section})`;
    card.title = `${preset.title}: “${preset.quote}” (${preset.section})`;
    card.append(image, title, quote);
    card.addEventListener('click', () => choose(preset.name));
    return card;
  });
  group.append(...cards);
  container.replaceChildren(group);
  group.addEventListener('keydown', (event) => {
    const step = { ArrowRight: 1, ArrowDown: 1, ArrowLeft: -1, ArrowUp: -1 }[event.key];
    if (!step) return;
    event.preventDefault();
    const at = cards.indexOf(document.activeElement);
    const next = cards[(at + step + cards.length) % cards.length];
    next.focus();
    next.scrollIntoView({ block: 'nearest', inline: 'nearest' });
  });
  const select = (name) => {
    for (const card of cards) {
      const on = card.dataset.preset === name;
      card.setAttribute('aria-checked', String(on));
      card.tabIndex = on ? 0 : -1;
    }
    // A scene that is no preset: the first card takes the keyboard's focus stop.
    if (!cards.some((c) => c.dataset.preset === name) && cards[0]) cards[0].tabIndex = 0;
  };
  return { select };
}
