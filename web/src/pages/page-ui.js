// The pages' shared status widgets: a notice (#message) and a progress bar (#progress with .bar
// and .label).

const $ = (selector) => document.querySelector(selector);
let noticeTimer = 0;

/**
 * Shows `text` in the notice (#message), which stays until its Dismiss button is pressed or
 * another notice replaces it; a `transient` one (a confirmation, such as "Link copied") goes
 * by itself after four seconds. `details` (lines of text) fold under a "Details" disclosure;
 * `actions` ([{label, run}]) are buttons that run and then dismiss the notice. An `info` notice
 * tells of a choice made for the visitor, not of something that went wrong (a calmer colour).
 */
export function showMessage(text, { transient = false, details = [], actions = [], info = false } = {}) {
  const box = $('#message');
  if (!box) return;
  box.dataset.kind = info ? 'info' : 'problem';
  const words = document.createElement('span');
  words.className = 'message-text';
  words.textContent = text;
  const parts = [words];
  if (details.length) {
    const more = document.createElement('details');
    more.className = 'message-details';
    const summary = document.createElement('summary');
    summary.textContent = 'Details';
    const list = document.createElement('ul');
    list.append(...details.map((line) => {
      const item = document.createElement('li');
      item.textContent = line;
      return item;
    }));
    more.append(summary, list);
    parts.push(more);
  }
  for (const { label, run } of actions) {
    const button = document.createElement('button');
    button.type = 'button';
    button.className = 'message-action';
    button.textContent = label;
    button.addEventListener('click', () => {
      box.hidden = true;
      run();
    });
    parts.push(button);
  }
  const dismiss = document.createElement('button');
  dismiss.type = 'button';
  dismiss.className = 'message-dismiss';
  dismiss.textContent = '×';
  dismiss.setAttribute('aria-label', 'Dismiss this notice');
  dismiss.addEventListener('click', () => { box.hidden = true; });
  box.replaceChildren(...parts, dismiss);
  box.hidden = false;
  clearTimeout(noticeTimer);
  if (transient) noticeTimer = setTimeout(() => { box.hidden = true; }, 4000);
}

/** Shows `progress` (0..1) with `label` in #progress; hides it at 1. */
export function showProgress(progress, label) {
  const box = $('#progress');
  if (!box) return;
  box.hidden = progress >= 1;
  box.querySelector('.bar').style.width = `${Math.round(progress * 100)}%`;
  box.querySelector('.label').textContent = `${label} (${Math.round(progress * 100)} %)`;
}
