// A simulated Olive module's own page, laid out on the real firmware's menus: System Status
// (device fields, live charts of the module's process, Network Settings, Device Control), Debug
// GUI (modules with an IMU: Euler angles and a 3D view) and Log Monitor. Live data is pushed by
// the module over the page's one WebSocket (owl_web's OwlSocket): channels "system", "orientation"
// and "log", each subscribed only while its menu page is shown.
import { showKitPages } from '../owl/links.js';
import { OwlSocket } from '../owl/socket.js';

const CHART_SECONDS = 120;
const $ = (id) => document.getElementById(id);

// What the tests read (page.evaluate) and the page shows.
const state = { device: null, boot: null, samples: [], orientation: null, logLines: 0, restarts: 0,
                page: null, uptime: null };
window.modulePage = state;

const socket = new OwlSocket((connected, detail) => {
  $('connection').textContent = detail || (connected ? 'connected' : 'disconnected');
});

// ---- device fields and menu ------------------------------------------------------------------
async function api(method, path, body) {
  const response = await fetch(path, {
    method, headers: body ? { 'Content-Type': 'application/json' } : {},
    body: body ? JSON.stringify(body) : undefined,
  });
  const data = await response.json();
  return [response.ok, data];
}

async function loadDevice() {
  const [ok, data] = await api('GET', 'api/device');
  if (!ok) return;
  state.device = data;
  state.boot = data.boot;
  const name = `${data.device['Device Type']} ${data.device.Namespace}`;
  document.title = `Olive ${name} — ${data.network.address}`;
  $('title').textContent = `Olive ${name} at ${data.network.address}`;
  $('brand-type').textContent = data.device['Device Type'];
  $('menu-debug').hidden = !data.debug;
  showDevice();
  const form = $('network');
  for (const field of ['address', 'mask', 'gateway']) form.elements[field].value = data.network[field];
  showPage();
}

function showDevice() {
  if (!state.device) return;
  const last = state.samples[state.samples.length - 1];
  const rows = {
    ...state.device.device,
    'Uptime': state.uptime === null ? '–' : formatUptime(state.uptime),
    'Core temperature (°C)': state.temperature ?? '–',
    'Memory (%)': last ? `${last.memory.toFixed(2)} (${last.memory_mb} MB)` : '–',
  };
  const table = $('device');
  table.replaceChildren(...Object.entries(rows).map(([key, value]) => {
    const row = document.createElement('tr');
    const th = document.createElement('th');
    const td = document.createElement('td');
    th.textContent = key;
    td.textContent = value;
    row.append(th, td);
    return row;
  }));
}

function formatUptime(seconds) {
  const h = Math.floor(seconds / 3600);
  const m = Math.floor((seconds % 3600) / 60);
  return `${h}:${String(m).padStart(2, '0')}:${String(seconds % 60).padStart(2, '0')}`;
}

// A new boot id: the module has started again (Restart Services, Reboot Device).
function seenBoot(boot) {
  if (state.boot !== null && boot !== state.boot) {
    state.restarts += 1;
    state.boot = boot;
    state.samples = [];
    result('control-result', `module started again at ${new Date().toLocaleTimeString()}`, true);
    loadDevice();
  }
  state.boot = boot;
}

// ---- pages (menu) ------------------------------------------------------------------------------
const channels = {
  status: ['system', onSystem],
  debug: ['orientation', onOrientation],
  log: ['log', onLog],
};
let subscription = null;

function showPage() {
  let page = location.hash.slice(1) || 'status';
  if (!(page in channels) || (page === 'debug' && state.device && !state.device.debug)) page = 'status';
  for (const link of document.querySelectorAll('nav a')) link.classList.toggle('active', link.dataset.page === page);
  for (const name of Object.keys(channels)) $(`page-${name}`).hidden = name !== page;
  if (state.page === page) return;
  state.page = page;
  if (subscription !== null) socket.unsubscribe(subscription);
  const [channel, onUpdate] = channels[page];
  subscription = socket.subscribe(channel, {}, onUpdate, (line) => {
    $('connection').textContent = line;
  });
  if (page === 'debug') startView();
}
window.addEventListener('hashchange', showPage);

// ---- System Status -------------------------------------------------------------------------------
function onSystem(data) {
  seenBoot(data.boot);
  state.uptime = data.uptime;
  state.temperature = data.temperature;
  state.samples.push(...data.samples);
  const cutoff = Date.now() / 1000 - CHART_SECONDS;
  state.samples = state.samples.filter((s) => s.time >= cutoff);
  const last = state.samples[state.samples.length - 1];
  if (last) {
    $('cpu-now').textContent = `${last.cpu.toFixed(1)}`;
    $('memory-now').textContent = `${last.memory.toFixed(2)}`;
    $('network-now').textContent = `Rx ${formatBytes(last.rx)} Tx ${formatBytes(last.tx)}`;
  }
  chart($('chart-cpu'), [['cpu', '#2563eb']], 5);
  chart($('chart-memory'), [['memory', '#7c3aed']], 0.5);
  chart($('chart-network'), [['rx', '#16a34a'], ['tx', '#ea580c']], 1000);
  showDevice();
}

function formatBytes(perSecond) {
  if (perSecond >= 1e6) return `${(perSecond / 1e6).toFixed(1)} MB/s`;
  if (perSecond >= 1e3) return `${(perSecond / 1e3).toFixed(1)} kB/s`;
  return `${perSecond} B/s`;
}

// A line chart of the last CHART_SECONDS of samples; the y axis grows with the data.
function chart(canvas, series, smallestTop) {
  const context = canvas.getContext('2d');
  const { width, height } = canvas;
  const left = 44;
  const bottom = height - 16;
  context.clearRect(0, 0, width, height);
  let top = smallestTop;
  for (const sample of state.samples) for (const [key] of series) top = Math.max(top, sample[key] * 1.15);
  context.font = '10px sans-serif';
  context.fillStyle = '#6b7280';
  context.strokeStyle = '#e5e7eb';
  for (let i = 0; i <= 4; i++) {
    const y = 4 + (bottom - 4) * i / 4;
    context.beginPath();
    context.moveTo(left, y);
    context.lineTo(width, y);
    context.stroke();
    const value = top * (4 - i) / 4;
    context.fillText(value >= 1000 ? `${(value / 1000).toFixed(1)}k` : value.toFixed(value < 10 ? 1 : 0), 2, y + 3);
  }
  context.fillText(`−${CHART_SECONDS} s`, left, height - 3);
  context.fillText('now', width - 22, height - 3);
  const now = Date.now() / 1000;
  const x = (t) => left + (width - left) * (1 - (now - t) / CHART_SECONDS);
  const y = (v) => bottom - (bottom - 4) * v / top;
  for (const [key, color] of series) {
    context.strokeStyle = color;
    context.lineWidth = 1.5;
    context.beginPath();
    state.samples.forEach((sample, i) => {
      if (i === 0) context.moveTo(x(sample.time), y(sample[key]));
      else context.lineTo(x(sample.time), y(sample[key]));
    });
    context.stroke();
  }
}

function result(id, text, ok) {
  const line = $(id);
  line.textContent = text;
  line.className = `result ${ok ? 'ok' : 'error'}`;
}

$('network').addEventListener('submit', async (event) => {
  event.preventDefault();
  const form = event.target;
  const body = {};
  for (const field of ['address', 'mask', 'gateway']) {
    const value = form.elements[field].value.trim();
    if (value !== state.device.network[field]) body[field] = value;
  }
  if (Object.keys(body).length === 0) {
    result('network-result', 'nothing changed', true);
    return;
  }
  let ok;
  let data;
  try {
    [ok, data] = await api('POST', 'api/network', body);
  } catch (error) {
    result('network-result', `the module did not answer: ${error.message}`, false);
    return;
  }
  if (!ok) {
    result('network-result', data.error, false);
    return;
  }
  const before = new URL(state.device.url).host;
  state.device.network = data.network;
  state.device.url = data.url;
  if (new URL(data.url).host === before) {
    result('network-result', 'saved', true);
  } else if (location.host === before) {  // opened at the module's own address, which stops answering
    result('network-result', `saved: the module now answers at ${data.url}`, true);
    location.href = data.url + location.hash;
  } else {  // through the front door (or a proxy), which follows the module to its new address
    result('network-result', `saved: the module now answers at ${data.url}; this page follows it`, true);
    loadDevice();
  }
});

async function control(path, what) {
  try {
    const [ok, data] = await api('POST', path, {});
    result('control-result', ok ? `${what}: the module is restarting…` : data.error, ok);
  } catch (error) {
    result('control-result', `the module did not answer: ${error.message}`, false);
  }
}
// Both stop the module's services for a while: each asks first, on the page (no browser dialog).
const CONTROLS = {
  restart: ['api/restart', 'Restart Services', 'stops and starts this module\'s services: its topics and '
            + 'services are gone for a moment, and nodes using them may need to be restarted.'],
  reboot: ['api/reboot', 'Reboot Device', 'stops the whole module while it boots again (several seconds): '
           + 'its topics, services and this page are away meanwhile.'],
};
let confirming = null;  // the control waiting for its confirmation
function ask(name) {
  const [, what, consequence] = CONTROLS[name];
  confirming = name;
  $('control-question').textContent = `${what} ${consequence} Go on?`;
  $('control-yes').textContent = `Yes, ${what.toLowerCase()}`;
  $('control-confirm').hidden = false;
  $('control-no').focus();
}
function closeConfirmation() {
  confirming = null;
  $('control-confirm').hidden = true;
}
$('restart').addEventListener('click', () => ask('restart'));
$('reboot').addEventListener('click', () => ask('reboot'));
$('control-no').addEventListener('click', closeConfirmation);
$('control-yes').addEventListener('click', () => {
  const [path, what] = CONTROLS[confirming];
  closeConfirmation();
  control(path, what);
});

// ---- Debug GUI -------------------------------------------------------------------------------
const DEGREES = 180 / Math.PI;
let view = null;

function onOrientation(data) {
  if (!data.quaternion) return;
  state.orientation = data;
  for (const angle of ['roll', 'pitch', 'yaw']) {
    $(angle).textContent = `${(data[angle] * DEGREES).toFixed(1)}°`;
  }
  if (view && view.imu) {  // the 3D view is ready
    const q = data.quaternion;
    view.imu.quaternion.set(q.x, q.y, q.z, q.w);
    view.render();
  }
}

// The IMU module as a 40 x 40 x 18 mm block with its axes, in ROS's frame (z up), drawn when an
// orientation arrives (no animation loop: nothing runs while nothing changes).
async function startView() {
  if (view) return;
  view = {};
  const THREE = await import('three');
  const container = $('view3d');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(container.clientWidth, container.clientHeight, false);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf3f4f6);
  const camera = new THREE.PerspectiveCamera(35, container.clientWidth / container.clientHeight, 0.01, 10);
  camera.up.set(0, 0, 1);
  camera.position.set(-0.16, -0.2, 0.12);
  camera.lookAt(0, 0, 0);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.0));
  const sun = new THREE.DirectionalLight(0xffffff, 1.5);
  sun.position.set(-1, -2, 3);
  scene.add(sun);
  const grid = new THREE.GridHelper(0.2, 10, 0x9ca3af, 0xd1d5db);
  grid.rotation.x = Math.PI / 2;  // GridHelper lies in x-z; ours is the x-y floor
  grid.position.z = -0.03;
  scene.add(grid);
  const imu = new THREE.Group();
  const body = new THREE.Mesh(new THREE.BoxGeometry(0.04, 0.04, 0.018),
                              new THREE.MeshStandardMaterial({ color: 0x374151, roughness: 0.5 }));
  const lid = new THREE.Mesh(new THREE.BoxGeometry(0.034, 0.034, 0.002),
                             new THREE.MeshStandardMaterial({ color: 0x9be15d, roughness: 0.5 }));
  lid.position.z = 0.0095;
  const axes = new THREE.AxesHelper(0.045);  // x red (forward), y green (left), z blue (up)
  imu.add(body, lid, axes);
  scene.add(imu);
  view.imu = imu;
  view.render = () => renderer.render(scene, camera);
  // The canvas follows its card's size (the window's width, a phone's turn).
  new ResizeObserver(() => {
    if (!container.clientWidth || !container.clientHeight) return;  // hidden with its page
    renderer.setSize(container.clientWidth, container.clientHeight, false);
    camera.aspect = container.clientWidth / container.clientHeight;
    camera.updateProjectionMatrix();
    view.render();
  }).observe(container);
  view.render();
  state.viewReady = true;
}

// ---- Log Monitor -------------------------------------------------------------------------------
let logBoot = null;
let lastLine = 0;

function onLog(data) {
  const log = $('log');
  if (logBoot !== null && data.boot !== logBoot) {
    lastLine = 0;
    const line = document.createElement('div');
    line.className = 'boot';
    line.textContent = '— the module started again —';
    log.append(line);
  }
  logBoot = data.boot;
  for (const entry of data.lines) {
    if (entry.n <= lastLine) continue;
    lastLine = entry.n;
    const line = document.createElement('div');
    line.className = entry.level;
    const time = new Date(entry.time * 1000).toLocaleTimeString();
    line.textContent = `${time} [${entry.level.toUpperCase()}] ${entry.message}`;
    log.append(line);
    state.logLines += 1;
  }
  while (log.childElementCount > 1000) log.firstElementChild.remove();
  if ($('log-follow').checked) log.scrollTop = log.scrollHeight;
}

loadDevice();
showKitPages();
