// owl windows: the list of windows (channel 'windows'), one frame subscription per shown window
// (channel 'window'), and the keys pressed on a focused window as 'key' commands.
import { showKitPages } from '../owl/links.js';
import { OwlSocket } from '../owl/socket.js';

const list = document.getElementById('windows');
const none = document.getElementById('none');
const status = document.getElementById('status');
const errors = document.getElementById('errors');
const shown = new Map();  // window id -> {card, image, subscription, url, frames}

// A refused key command's line comes here too (connected, with a detail).
// Connection lost: the windows shown are frozen, and greyed out to say so.
const socket = new OwlSocket((connected, detail) => {
  document.body.classList.toggle('stale', !connected);
  status.textContent = connected ? 'connected' : `${detail}. The windows below are frozen; run owl windows again.`;
  if (connected && detail) showError(detail);
});

function showError(line) {
  errors.textContent = line;
}

// KeyboardEvent -> the pygame key name the programs' keys file takes, or null.
const NAMED = {
  ArrowLeft: 'left', ArrowRight: 'right', ArrowUp: 'up', ArrowDown: 'down', ' ': 'space',
  Enter: 'return', Escape: 'escape', Backspace: 'backspace', Tab: 'tab', Delete: 'delete',
  Home: 'home', End: 'end', PageUp: 'page up', PageDown: 'page down', Insert: 'insert',
  CapsLock: 'caps lock',
};
export function keyName(event) {
  if (event.key in NAMED) return NAMED[event.key];
  const side = event.location === 2 ? 'right' : 'left';
  if (event.key === 'Shift') return `${side} shift`;
  if (event.key === 'Control') return `${side} ctrl`;
  if (event.key === 'Alt') return `${side} alt`;
  if (/^F([1-9]|1[0-2])$/.test(event.key)) return event.key.toLowerCase();
  if (event.key.length === 1) return event.key.toLowerCase();
  return null;
}

function sendKey(id, event, kind) {
  const key = keyName(event);
  if (key === null) return;
  event.preventDefault();
  if (kind === 'down' && event.repeat) return;  // a held key is one down and one up, as in pygame
  socket.command('key', { window: id, event: kind, key });
}

// On-screen arrows for touch screens (and mice): held down as a key is held, released as it is.
const ARROWS = [['up', '▲'], ['left', '◀'], ['down', '▼'], ['right', '▶']];
function arrowPad(id) {
  const pad = document.createElement('div');
  pad.className = 'arrows';
  for (const [key, label] of ARROWS) {
    const button = document.createElement('button');
    button.type = 'button';
    button.className = `arrow ${key}`;
    button.textContent = label;
    button.setAttribute('aria-label', `${key} arrow key`);
    let held = false;
    const release = () => {
      if (!held) return;
      held = false;
      button.classList.remove('held');
      socket.command('key', { window: id, event: 'up', key });
    };
    button.addEventListener('pointerdown', (event) => {
      event.preventDefault();
      button.setPointerCapture(event.pointerId);  // the up comes here even if the finger slides off
      held = true;
      button.classList.add('held');
      socket.command('key', { window: id, event: 'down', key });
    });
    button.addEventListener('pointerup', release);
    button.addEventListener('pointercancel', release);
    button.addEventListener('lostpointercapture', release);
    pad.append(button);
  }
  return pad;
}

function addWindow(window) {
  const card = document.createElement('section');
  card.className = 'window';
  card.tabIndex = 0;
  card.dataset.window = window.id;
  const title = document.createElement('h2');
  title.textContent = `${window.program} (${window.pid}) — ${window.kind === 'pygame' ? 'pygame window' : `'${window.name}'`} `;
  const keys = document.createElement('span');
  keys.className = 'keys';
  title.append(keys);
  const image = document.createElement('img');
  image.alt = `${window.program}: ${window.name}`;
  card.append(title, image, arrowPad(window.id));
  card.addEventListener('keydown', (event) => sendKey(window.id, event, 'down'));
  card.addEventListener('keyup', (event) => sendKey(window.id, event, 'up'));
  card.addEventListener('focus', () => { keys.textContent = '(keys go to it)'; });
  card.addEventListener('blur', () => { keys.textContent = ''; });
  card.addEventListener('click', () => card.focus());
  list.append(card);
  const entry = { card, image, url: null, frames: 0 };
  entry.subscription = socket.subscribe('window', { window: window.id }, (data, payload) => {
    if (payload === undefined) return;  // {closed: true}: the list update removes the card
    const url = URL.createObjectURL(new Blob([payload], { type: data.content_type }));
    image.onload = () => { if (entry.url && entry.url !== url) URL.revokeObjectURL(entry.url); entry.url = url; };
    image.src = url;
    entry.frames += 1;
    card.dataset.frames = String(entry.frames);
  }, showError);
  shown.set(window.id, entry);
}

function removeWindow(id) {
  const entry = shown.get(id);
  socket.unsubscribe(entry.subscription);
  if (entry.url) URL.revokeObjectURL(entry.url);
  entry.card.remove();
  shown.delete(id);
}

socket.subscribe('windows', {}, (data) => {
  const ids = new Set(data.windows.map((w) => w.id));
  for (const id of [...shown.keys()]) if (!ids.has(id)) removeWindow(id);
  for (const window of data.windows) if (!shown.has(window.id)) addWindow(window);
  none.hidden = data.windows.length > 0;
  document.body.dataset.windows = String(data.windows.length);
}, showError);
showKitPages();
