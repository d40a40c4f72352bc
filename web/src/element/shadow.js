// The <wind-field> element's shadow DOM: one constructed stylesheet shared by every element (no
// inline <style>, so pages with a strict CSP style it too) and the parts.

const STYLE = `
:host { display: block; position: relative; width: 100%; aspect-ratio: 4 / 3; background: #0b0e11; color: #e6e9ec;
        font: 13px system-ui, sans-serif; overflow: hidden; border-radius: 6px; contain: content; }
:host([hidden]) { display: none; }
canvas, .poster { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
.poster { object-fit: cover; }
.bar { position: absolute; left: 0; bottom: 0; height: 3px; background: #7cc4ff; width: 0; transition: width 60ms linear; }
.status { position: absolute; left: 8px; top: 8px; padding: 2px 6px; border-radius: 4px; background: rgba(0, 0, 0, 0.6); }
.message { position: absolute; left: 8px; right: 8px; top: 8px; padding: 6px 8px; background: #5a1d1d; color: #fff; border-radius: 4px; }
.controls { position: absolute; left: 8px; bottom: 8px; display: flex; gap: 4px; }
button { font: inherit; color: inherit; background: rgba(0, 0, 0, 0.7); border: 1px solid #6b7785; border-radius: 4px; padding: 3px 8px; cursor: pointer; }
button:hover { background: rgba(20, 28, 36, 0.85); }
button:focus-visible { outline: 3px solid #7cc4ff; outline-offset: 2px; }
.play { position: absolute; left: 50%; top: 50%; width: 64px; height: 64px; margin: -32px 0 0 -32px; padding: 0;
        border-radius: 50%; border: 2px solid #e6e9ec; display: grid; place-items: center; }
.play svg { width: 26px; height: 26px; margin-left: 4px; fill: currentColor; }
[hidden] { display: none !important; }
`;

const TEMPLATE = `<canvas part="canvas" role="img"></canvas>
<img class="poster" part="poster" alt="" hidden>
<div class="bar" part="progress"></div>
<div class="status" part="status" role="status" hidden></div>
<button class="play" part="play-button" type="button" hidden><svg viewBox="0 0 24 24" aria-hidden="true"><path d="M5 3l16 9-16 9z"/></svg></button>
<div class="controls" part="controls" hidden>
  <button type="button" data-action="toggle">Play</button>
  <button type="button" data-action="step" aria-label="Step once">Step</button>
  <button type="button" data-action="view"></button>
</div>
<div class="message" part="message" role="alert" hidden></div>`;

let sheet = null;
/** The element's styles, one constructed stylesheet adopted by every element's shadow root. */
function styleSheet() {
  if (!sheet) {
    sheet = new CSSStyleSheet();
    sheet.replaceSync(STYLE);
  }
  return sheet;
}

/** Attaches the shadow DOM to `host`; returns its parts. */
export function attachParts(host) {
  const root = host.attachShadow({ mode: 'open' });
  root.adoptedStyleSheets = [styleSheet()];
  root.innerHTML = TEMPLATE;
  const $ = (s) => root.querySelector(s);
  return {
    canvas: $('canvas'), poster: $('.poster'), bar: $('.bar'), status: $('.status'),
    play: $('.play'), controls: $('.controls'), message: $('.message'),
    toggle: $('[data-action="toggle"]'), step: $('[data-action="step"]'), view: $('[data-action="view"]'),
  };
}
