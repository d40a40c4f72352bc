// The pages' shared status widgets: a transient message (#message) and a progress bar
// (#progress with .bar and .label).

const $ = (selector) => document.querySelector(selector);
let messageTimer = 0;

/** Shows `text` in #message for eight seconds. */
export function showMessage(text) {
  const box = $('#message');
  box.textContent = text;
  box.hidden = false;
  clearTimeout(messageTimer);
  messageTimer = setTimeout(() => { box.hidden = true; }, 8000);
}

/** Shows `progress` (0..1) with `label` in #progress; hides it at 1. */
export function showProgress(progress, label) {
  const box = $('#progress');
  box.hidden = progress >= 1;
  box.querySelector('.bar').style.width = `${Math.round(progress * 100)}%`;
  box.querySelector('.label').textContent = `${label} (${Math.round(progress * 100)} %)`;
}
