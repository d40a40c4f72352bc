// The pages' shared status widgets: a notice (#message) and a progress bar (#progress with .bar
// and .label).

const $ = (selector) => document.querySelector(selector);
let noticeTimer = 0;

/**
 * Shows `text` in the notice (#message), which stays until its Dismiss button is pressed or
 * another notice replaces it; a `transient` one (a confirmation, such as "Link copied") goes
 * by itself after four seconds.
 */
export function showMessage(text, { transient = false } = {}) {
  const box = $('#message');
  if (!box) return;
  const words = document.createElement('span');
  words.className = 'message-text';
  words.textContent = text;
  const dismiss = document.createElement('button');
  dismiss.type = 'button';
  dismiss.className = 'message-dismiss';
  dismiss.textContent = '×';
  dismiss.setAttribute('aria-label', 'Dismiss this notice');
  dismiss.addEventListener('click', () => { box.hidden = true; });
  box.replaceChildren(words, dismiss);
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
