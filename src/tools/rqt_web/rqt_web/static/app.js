// The page of rqt_web: four plugins over the JSON API of the rqt node (see the package README);
// the graph and image frames come pushed over the page's WebSocket (owl_web's OwlSocket), and the
// graph is laid out here with elkjs (loaded by index.html as the global ELK).
import { showKitPages } from '../owl/links.js';
import { OwlSocket } from '../owl/socket.js';

const $ = (id) => document.getElementById(id);
const SVG = 'http://www.w3.org/2000/svg';

// Connection lost: what the plugins show is frozen, and greyed out to say so.
const socket = new OwlSocket((connected, detail) => {
  document.body.classList.toggle('stale', !connected);
  $('connection').textContent = connected ? '' : 'not connected';
  $('connection').title = detail;
  if (detail) showError('page-error', detail);
  else if (connected) showError('page-error');
});

async function api(method, path, body) {
  const options = { method, headers: {} };
  if (body !== undefined) {
    options.headers['Content-Type'] = 'application/json';
    options.body = JSON.stringify(body);
  }
  let response;
  try {
    response = await fetch(path, options);
  } catch (error) {
    throw new Error('rqt is not answering (was it stopped?)');
  }
  const data = await response.json().catch(() => ({}));
  if (!response.ok) throw new Error(data.error || `HTTP ${response.status}`);
  return data;
}

function showError(id, error) {
  $(id).textContent = error ? String(error.message || error) : '';
}

function element(tag, attributes = {}, text) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

function fillDatalist(id, values) {
  const list = $(id);
  list.replaceChildren(...values.map((value) => element('option', { value })));
}

// ---- tabs ----------------------------------------------------------------------------------

const tabs = {};  // name -> {enter, leave}: what a plugin does when its tab is shown or hidden
// The plugins shown: one, or two side by side (rqt's docked plugins): [left, right]. The URL's hash
// keeps them: #node-graph, or #node-graph+message-publisher.
let shown = [];

function isPlugin(name) {
  return Boolean(name) && document.getElementById(name)?.classList.contains('plugin');
}

function showPlugins(names) {
  const wanted = [...new Set(names.filter(isPlugin))].slice(0, 2);
  if (!wanted.length) wanted.push('node-graph');
  for (const name of shown) if (!wanted.includes(name) && tabs[name]?.leave) tabs[name].leave();
  const entered = wanted.filter((name) => !shown.includes(name));
  shown = wanted;
  for (const button of document.querySelectorAll('#tabs button')) {
    button.classList.toggle('active', shown.includes(button.dataset.tab));
  }
  for (const section of document.querySelectorAll('.plugin')) {
    section.classList.toggle('active', shown.includes(section.id));
    section.style.order = String(shown.indexOf(section.id));
  }
  document.body.classList.toggle('split', shown.length === 2);
  $('split').setAttribute('aria-pressed', String(shown.length === 2));
  const hash = '#' + shown.join('+');
  if (location.hash !== hash) history.replaceState(null, '', hash);
  for (const name of entered) if (tabs[name]?.enter) tabs[name].enter();
}

// A tab shows its plugin; side by side, it replaces the right-hand one.
function selectTab(name) {
  showPlugins(shown.length === 2 ? [shown[0], name === shown[0] ? shown[1] : name] : [name]);
}

for (const button of document.querySelectorAll('#tabs button')) {
  button.addEventListener('click', () => selectTab(button.dataset.tab));
}
$('split').addEventListener('click', () => {
  if (shown.length === 2) {
    showPlugins([shown[0]]);
  } else {
    const next = [...document.querySelectorAll('#tabs button')].map((b) => b.dataset.tab).find((t) => t !== shown[0]);
    showPlugins([shown[0], next]);
  }
});

// ---- field forms (Message Publisher, Service Caller) --------------------------------------

const NUMERIC = /^(u?int(8|16|32|64)|float|double|long double|byte|octet|char)$/;

function cellText(value) {
  return typeof value === 'string' ? value : JSON.stringify(value);
}

// Rows of a table for a field template; values override the defaults by field name.
function fieldRows(template, values, prefix, depth, readOnly) {
  const rows = [];
  for (const field of template) {
    const path = prefix ? `${prefix}.${field.name}` : field.name;
    const value = values && typeof values === 'object' ? values[field.name] : undefined;
    const row = element('tr');
    const name = element('td', {}, field.name);
    name.style.paddingLeft = `${6 + depth * 16}px`;
    row.append(name, element('td', { class: 'type' }, field.type));
    const cell = element('td');
    if (field.fields) {
      rows.push(row, ...fieldRows(field.fields, value, path, depth + 1, readOnly));
      row.append(cell);
      continue;
    }
    const shown = value === undefined ? field.default : value;
    if (readOnly) {
      cell.textContent = cellText(shown);
      cell.className = 'type';
    } else {
      const input = element('input', { 'data-path': path, 'data-type': field.type });
      if (field.sequence) input.dataset.sequence = '1';
      input.value = cellText(shown);
      cell.append(input);
    }
    row.append(cell);
    rows.push(row);
  }
  return rows;
}

function fieldTable(template, values, readOnly = false) {
  const table = element('table', { class: 'fields' });
  const head = element('tr');
  head.append(element('th', {}, 'field'), element('th', {}, 'type'),
    element('th', {}, 'value'));  // upstream's column says "expression": ours takes plain values
  table.append(head, ...fieldRows(template, values, '', 0, readOnly));
  return table;
}

// A cell's text as the value the API expects: numbers, booleans and lists as JSON, other text
// as it is (the server names the field when a value does not fit).
function cellValue(input) {
  const text = input.value.trim();
  const type = input.dataset.type;
  if (input.dataset.sequence) {
    try { return JSON.parse(text); } catch (error) { return input.value; }
  }
  if (type === 'boolean' && /^(true|false)$/i.test(text)) return text.toLowerCase() === 'true';
  if (NUMERIC.test(type) && type !== 'char' && text !== '' && !isNaN(Number(text))) return Number(text);
  return input.value;
}

function formValues(container) {
  const values = {};
  for (const input of container.querySelectorAll('input[data-path]')) {
    const parts = input.dataset.path.split('.');
    let target = values;
    for (const part of parts.slice(0, -1)) target = target[part] = target[part] || {};
    target[parts[parts.length - 1]] = cellValue(input);
  }
  return values;
}

// ---- Node Graph -----------------------------------------------------------------------------

const elk = new ELK();
const BOX_PADDING = 24;  // px around a topic's label
const ELLIPSE_PADDING = 44;  // px around a node's label: an ellipse is narrower at the label's ends
const BOX_HEIGHT = 30;
const LAYOUT = {
  'elk.algorithm': 'layered',
  'elk.direction': 'RIGHT',  // publishers left of their topics, subscribers right, as rqt_graph
  'elk.edgeRouting': 'SPLINES',
  'elk.spacing.nodeNode': '16',
  'elk.layered.spacing.nodeNodeBetweenLayers': '48',
  'elk.padding': '[top=16,left=16,bottom=16,right=16]',
  // A long chain of layers (the kit's: IMU, imu_control_robot, servos, camera) goes on in a second
  // row rather than ever wider: fitted into the page's width, one row was drawn at 24-47 % with
  // labels of 3-6 px.
  'elk.layered.wrapping.strategy': 'MULTI_EDGE',
};

// The shape the graph should take: its box's width over the height the window leaves for it.
function graphAspect() {
  const box = $('graph-svg').parentElement;
  const height = Math.max(window.innerHeight - box.getBoundingClientRect().top - 16, 200);
  return Math.min(Math.max(box.clientWidth / height, 1), 4);
}
const measure = document.createElement('canvas').getContext('2d');
let graphSubscription = null;
let graphDrawing = Promise.resolve();

function svg(tag, attributes = {}, text) {
  const node = document.createElementNS(SVG, tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

// Label widths come from the font the page draws with, measured here (no guessed metrics).
function boxWidth(label, padding) {
  measure.font = getComputedStyle($('graph-svg')).getPropertyValue('--label-font').trim();
  return Math.ceil(measure.measureText(label).width) + padding;
}

// A section of an ELK edge as an SVG path: its points are cubic Bezier control points with
// spline routing (1 + 3n of them), else the corners of a polyline.
function edgePath(section) {
  const points = [section.startPoint, ...(section.bendPoints || []), section.endPoint];
  const xy = (point) => `${point.x} ${point.y}`;
  if ((points.length - 1) % 3 === 0) {
    let d = `M ${xy(points[0])}`;
    for (let i = 1; i < points.length; i += 3) d += ` C ${xy(points[i])}, ${xy(points[i + 1])}, ${xy(points[i + 2])}`;
    return d;
  }
  return `M ${points.map(xy).join(' L ')}`;
}

async function drawGraph(graph) {
  const topics = Object.fromEntries(graph.topics.map((topic) => [topic.name, topic.types]));
  const boxes = [...graph.nodes, ...graph.topics.map((topic) => topic.name)];
  const laid = await elk.layout({
    id: 'root',
    layoutOptions: { ...LAYOUT, 'elk.aspectRatio': String(graphAspect()) },
    children: boxes.map((id) => ({
      id, width: boxWidth(id, id in topics ? BOX_PADDING : ELLIPSE_PADDING), height: BOX_HEIGHT })),
    edges: graph.edges.map((edge, index) => ({ id: `e${index}`, sources: [edge.from], targets: [edge.to] })),
  });
  const canvas = $('graph-svg');
  graphSize = { width: Math.max(laid.width, 200), height: Math.max(laid.height, 100) };
  canvas.setAttribute('viewBox', `0 0 ${graphSize.width} ${graphSize.height}`);
  applyGraphZoom();
  const marker = svg('marker', { id: 'arrow', viewBox: '0 0 10 10', refX: '10', refY: '5',
    markerWidth: '8', markerHeight: '8', orient: 'auto-start-reverse' });
  marker.append(svg('path', { d: 'M 0 0 L 10 5 L 0 10 z', fill: '#333' }));
  const defs = svg('defs');
  defs.append(marker);
  const items = [defs];
  for (const edge of laid.edges) {
    for (const section of edge.sections || []) {
      items.push(svg('path', { class: 'edge', d: edgePath(section),
        'data-from': edge.sources[0], 'data-to': edge.targets[0] }));
    }
  }
  for (const box of laid.children) {
    const kind = box.id in topics ? 'topic' : 'node';
    const group = svg('g', { 'data-id': box.id, 'data-kind': kind });
    if (box.id === window.rqtInspector.topic && inspectorSubscription !== null) group.classList.add('inspected');
    group.append(svg('title', {}, kind === 'topic' ? `${box.id} [${topics[box.id].join(', ')}]` : box.id));
    if (kind === 'node') {
      group.append(svg('ellipse', { class: 'node', cx: box.x + box.width / 2, cy: box.y + box.height / 2,
        rx: box.width / 2, ry: box.height / 2 }));
    } else {
      group.append(svg('rect', { class: 'topic', x: box.x, y: box.y, width: box.width, height: box.height }));
    }
    group.append(svg('text', { x: box.x + box.width / 2, y: box.y + box.height / 2 }, box.id));
    items.push(group);
  }
  canvas.replaceChildren(...items);
  const count = (n, what) => `${n} ${what}${n === 1 ? '' : 's'}`;
  $('graph-status').textContent = `${count(graph.nodes.length, 'node')}, ${count(graph.topics.length, 'topic')}`;
}

// 'readable' (the default: the page's width, but never labels under 8 px, 12 px at 100 %: a graph
// still wider scrolls sideways, as a map would, rather than shrinking to unreadable), 'fit' (the
// whole graph in the page's width, however small: the Fit button) or a zoom factor (1 = the
// layout's pixels).
let graphSize = { width: 200, height: 100 };
let graphZoom = 'readable';
const ZOOM_STEP = 1.25;
const MIN_READABLE = 2 / 3;

function applyGraphZoom() {
  const canvas = $('graph-svg');
  const box = canvas.parentElement;
  const fitting = typeof graphZoom === 'string';
  if (fitting && box.clientWidth < 10) return;  // hidden: fitted when shown (ResizeObserver)
  const fitted = Math.min(1, (box.clientWidth - 2) / graphSize.width);
  const zoom = graphZoom === 'fit' ? fitted : graphZoom === 'readable' ? Math.max(fitted, MIN_READABLE) : graphZoom;
  canvas.setAttribute('width', String(Math.round(graphSize.width * zoom)));
  canvas.setAttribute('height', String(Math.round(graphSize.height * zoom)));
  const percent = `${Math.round(zoom * 100)} %`;
  $('graph-zoom-level').textContent = !fitting ? percent : graphZoom === 'fit' ? `fit (${percent})`
    : fitted < MIN_READABLE ? `${percent}: wider than the page, it scrolls (Fit: all of it)` : `fit (${percent})`;
}

function zoomGraph(to) {
  const current = typeof graphZoom === 'string' ? Number($('graph-svg').getAttribute('width')) / graphSize.width
    : graphZoom;
  graphZoom = to === 'fit' ? 'fit' : Math.min(4, Math.max(0.1, to === 'in' ? current * ZOOM_STEP
    : to === 'out' ? current / ZOOM_STEP : 1));
  applyGraphZoom();
}
$('graph-fit').addEventListener('click', () => zoomGraph('fit'));
$('graph-zoom-in').addEventListener('click', () => zoomGraph('in'));
$('graph-zoom-out').addEventListener('click', () => zoomGraph('out'));
$('graph-actual').addEventListener('click', () => zoomGraph('actual'));
$('graph-svg').parentElement.addEventListener('wheel', (event) => {
  if (!event.ctrlKey) return;  // the wheel alone scrolls, as everywhere
  event.preventDefault();
  zoomGraph(event.deltaY < 0 ? 'in' : 'out');
}, { passive: false });
new ResizeObserver(() => { if (typeof graphZoom === 'string') applyGraphZoom(); })
  .observe($('graph-svg').parentElement);

function watchGraph() {
  if (graphSubscription !== null) socket.unsubscribe(graphSubscription);
  const options = { hide_debug: $('graph-hide-debug').checked, hide_leaf_topics: $('graph-hide-leaf').checked };
  graphSubscription = socket.subscribe('graph', options, (graph) => {
    // One layout at a time, in the order the updates came.
    graphDrawing = graphDrawing.then(() => drawGraph(graph)).then(() => showError('graph-error'),
      (error) => showError('graph-error', error));
  }, (error) => showError('graph-error', error));
}

function stopWatchingGraph() {
  if (graphSubscription !== null) socket.unsubscribe(graphSubscription);
  graphSubscription = null;
}

$('graph-hide-debug').addEventListener('change', watchGraph);
$('graph-hide-leaf').addEventListener('change', watchGraph);
tabs['node-graph'] = { enter: watchGraph, leave: () => { stopWatchingGraph(); stopInspecting(); } };

// ---- Topic inspector: a topic's last message, rate, publishers and subscribers with their QoS ----
let inspectorSubscription = null;
window.rqtInspector = { topic: null, state: null, updates: 0 };  // what a test reads

function endpointRows(table, caption, endpoints) {
  const head = `<caption>${caption} (${endpoints.length})</caption>`
    + '<tr><th>node</th><th>reliability</th><th>durability</th><th>liveliness</th></tr>';
  table.innerHTML = head;
  for (const endpoint of endpoints) {
    const row = table.insertRow();
    for (const key of ['node', 'reliability', 'durability', 'liveliness']) {
      row.insertCell().textContent = String(endpoint[key]);
    }
  }
}

function showInspection(state) {
  window.rqtInspector.state = state;
  window.rqtInspector.updates += 1;
  $('inspected-type').textContent = state.type;
  $('inspected-rate').textContent = state.rate === null
    ? `${state.count} messages, none in the last seconds` : `${state.rate.toFixed(1)} Hz, ${state.count} messages`;
  endpointRows($('inspected-publishers'), 'Publishers', state.publishers);
  endpointRows($('inspected-subscribers'), 'Subscribers', state.subscribers);
  $('inspected-message').textContent = state.message === null ? 'No message yet.'
    : JSON.stringify(state.message, null, 2);
}

function inspect(topic) {
  stopInspecting();
  window.rqtInspector = { topic, state: null, updates: 0 };
  $('topic-inspector').hidden = false;
  $('inspected-topic').textContent = topic;
  for (const id of ['inspected-type', 'inspected-rate', 'inspected-message']) $(id).textContent = '';
  showError('inspector-error');
  for (const group of document.querySelectorAll('#graph-svg g.inspected')) group.classList.remove('inspected');
  document.querySelector(`#graph-svg g[data-id="${CSS.escape(topic)}"]`)?.classList.add('inspected');
  inspectorSubscription = socket.subscribe('topic', { topic }, showInspection,
                                           (error) => showError('inspector-error', error));
}

function stopInspecting() {
  if (inspectorSubscription !== null) socket.unsubscribe(inspectorSubscription);
  inspectorSubscription = null;
}

$('graph-svg').addEventListener('click', (event) => {
  const group = event.target.closest('g[data-kind=topic]');
  if (group) inspect(group.dataset.id);
});
$('inspector-close').addEventListener('click', () => {
  stopInspecting();
  $('topic-inspector').hidden = true;
  for (const group of document.querySelectorAll('#graph-svg g.inspected')) group.classList.remove('inspected');
});

// ---- Message Publisher ----------------------------------------------------------------------

let topicTypes = {};
const templates = {};

async function template(type) {
  if (!templates[type]) templates[type] = await api('GET', `api/interface?type=${encodeURIComponent(type)}`);
  return templates[type];
}

// Topics or services from the graph: names offered in a datalist; returns name -> types, or
// null (the error shown) when the request failed.
async function listGraphNames(path, datalistId, errorId) {
  try {
    const entries = await api('GET', path);
    fillDatalist(datalistId, entries.map((entry) => entry.name));
    showError(errorId);
    return Object.fromEntries(entries.map((entry) => [entry.name, entry.types]));
  } catch (error) {
    showError(errorId, error);
    return null;
  }
}

async function refreshTopics() {
  topicTypes = (await listGraphNames('api/topics', 'pub-topics', 'pub-error')) ?? topicTypes;
}

let messageTypes = [];

// A topic's own type, or for a new topic the choice of every installed message type.
$('pub-topic').addEventListener('change', async () => {
  const types = topicTypes[$('pub-topic').value.trim()];
  if (types) {
    fillDatalist('pub-types', types);
    $('pub-type').value = types.length === 1 ? types[0] : '';
    return;
  }
  try {
    if (!messageTypes.length) messageTypes = await api('GET', 'api/interfaces?kind=msg');
    fillDatalist('pub-types', messageTypes);
  } catch (error) {
    showError('pub-error', error);
  }
});

async function patchPublisher(entry, change, box) {
  try {
    const updated = await api('PATCH', `api/publishers/${entry.id}`, change);
    Object.assign(entry, updated);
    box.querySelector('.count').textContent = `${updated.published} published`;
    showError('pub-error');
  } catch (error) {
    showError('pub-error', `publisher ${entry.id} (${entry.topic}): ${error.message}`);
  }
}

async function renderPublisher(entry) {
  const box = element('div', { class: 'publisher', id: `publisher-${entry.id}` });
  const head = element('div', { class: 'head' });
  const enabled = element('input', { type: 'checkbox', title: 'Publish' });
  enabled.checked = entry.enabled;
  const rate = element('input', { type: 'number', min: '0.01', step: 'any' });
  rate.value = entry.rate;
  const remove = element('button', { title: 'Remove publisher' }, '\u2212');
  head.append(enabled, element('b', {}, entry.topic), element('span', { class: 'type' }, entry.type),
    rate, element('span', {}, 'Hz'), element('span', { class: 'count' }, `${entry.published} published`),
    remove);
  const form = element('div');
  form.append(fieldTable((await template(entry.type)).fields, entry.message));
  box.append(head, form);
  enabled.addEventListener('change', () => patchPublisher(entry, { enabled: enabled.checked }, box));
  rate.addEventListener('change', () => patchPublisher(entry, { rate: Number(rate.value) || rate.value }, box));
  form.addEventListener('change', () => patchPublisher(entry, { fields: formValues(form) }, box));
  remove.addEventListener('click', async () => {
    try {
      await api('DELETE', `api/publishers/${entry.id}`);
      box.remove();
      showError('pub-error');
    } catch (error) {
      showError('pub-error', error);
    }
  });
  $('publishers').append(box);
}

$('pub-add').addEventListener('click', async () => {
  try {
    const body = { topic: $('pub-topic').value.trim(), rate: Number($('pub-rate').value) || $('pub-rate').value };
    if ($('pub-type').value.trim()) body.type = $('pub-type').value.trim();
    const entry = await api('POST', 'api/publishers', body);
    await renderPublisher(entry);
    showError('pub-error');
  } catch (error) {
    showError('pub-error', error);
  }
});

async function loadPublishers() {
  await refreshTopics();
  if ($('publishers').childElementCount) return;
  try {
    for (const entry of await api('GET', 'api/publishers')) await renderPublisher(entry);
  } catch (error) {
    showError('pub-error', error);
  }
}

// The "N published" counters follow the publishers while the plugin is shown (once a second).
let countTimer = null;
async function refreshCounts() {
  let entries;
  try {
    entries = await api('GET', 'api/publishers');
  } catch (error) {
    return;  // the page's status says when the server is away
  }
  for (const entry of entries) {
    const count = document.querySelector(`#publisher-${entry.id} .count`);
    if (count) count.textContent = `${entry.published} published`;
  }
}

$('pub-refresh').addEventListener('click', refreshTopics);
tabs['message-publisher'] = {
  enter: () => {
    loadPublishers();
    clearInterval(countTimer);
    countTimer = setInterval(refreshCounts, 1000);
  },
  leave: () => { clearInterval(countTimer); countTimer = null; },
};

// ---- Service Caller -------------------------------------------------------------------------

let serviceTypes = {};
let requestType = null;

async function refreshServices() {
  serviceTypes = (await listGraphNames('api/services', 'srv-names', 'srv-error')) ?? serviceTypes;
}

async function chooseService() {
  const types = serviceTypes[$('srv-name').value.trim()] || [];
  requestType = types[0] || null;
  $('srv-type').textContent = types.join(', ');
  $('srv-request').replaceChildren();
  $('srv-response').replaceChildren();
  if (!requestType) return;
  try {
    $('srv-request').append(fieldTable((await template(requestType)).request, {}));
    showError('srv-error');
  } catch (error) {
    showError('srv-error', error);
  }
}

$('srv-name').addEventListener('change', chooseService);
$('srv-refresh').addEventListener('click', refreshServices);
$('srv-call').addEventListener('click', async () => {
  $('srv-response').replaceChildren();
  try {
    const body = { service: $('srv-name').value.trim(), request: formValues($('srv-request')),
      timeout: Number($('srv-timeout').value) || $('srv-timeout').value };
    if (requestType) body.type = requestType;
    const answer = await api('POST', 'api/call', body);
    const responseTemplate = (await template(answer.type)).response;
    $('srv-response').append(fieldTable(responseTemplate, answer.response, true));
    showError('srv-error');
  } catch (error) {
    showError('srv-error', error);
  }
});
tabs['service-caller'] = { enter: refreshServices };

// ---- Image View -----------------------------------------------------------------------------

const FPS_WINDOW = 2000;  // ms of frames the shown rate counts
let imageSubscription = null;
let nextFrame = null;  // the newest frame not drawn yet; older ones are skipped, never queued
let drawingFrame = false;
let shownTimes = [];

async function refreshImageTopics() {
  try {
    const topics = await api('GET', 'api/image_topics');
    const select = $('img-topic');
    const chosen = select.value;
    select.replaceChildren(element('option', { value: '' }, '(choose an image topic)'),
      ...topics.map((topic) => element('option', { value: topic.name }, topic.name)));
    select.value = topics.some((topic) => topic.name === chosen) ? chosen : '';
    showError('img-error');
  } catch (error) {
    showError('img-error', error);
  }
}

async function drawFrames() {
  drawingFrame = true;
  const canvas = $('img-canvas');
  while (nextFrame) {
    const [header, payload] = nextFrame;
    nextFrame = null;
    try {
      const bitmap = await createImageBitmap(new Blob([payload], { type: header.content_type }));
      if (canvas.width !== bitmap.width || canvas.height !== bitmap.height) {
        canvas.width = bitmap.width;
        canvas.height = bitmap.height;
        $('img-size').textContent = `${bitmap.width}x${bitmap.height}`;
      }
      canvas.getContext('2d').drawImage(bitmap, 0, 0);
      bitmap.close();
    } catch (error) {
      showError('img-error', `frame ${header.frame} of ${header.topic} cannot be shown: ${error.message}`);
      continue;
    }
    const now = performance.now();
    shownTimes.push(now);
    while (shownTimes[0] < now - FPS_WINDOW) shownTimes.shift();
    canvas.dataset.frame = header.frame;
    canvas.dataset.shown = Number(canvas.dataset.shown || 0) + 1;
    const fps = shownTimes.length > 1 ? (shownTimes.length - 1) / ((now - shownTimes[0]) / 1000) : 0;
    $('img-status').textContent = `frame ${header.frame}, ${fps.toFixed(1)} fps shown`;
    showError('img-error');
  }
  drawingFrame = false;
}

function watchImages() {
  stopWatchingImages();
  const topic = $('img-topic').value;
  if (!topic) return;
  imageSubscription = socket.subscribe('image', { topic }, (header, payload) => {
    nextFrame = [header, payload];
    if (!drawingFrame) drawFrames();
  }, (error) => showError('img-error', error));
}

function stopWatchingImages() {
  if (imageSubscription !== null) socket.unsubscribe(imageSubscription);
  imageSubscription = null;
  nextFrame = null;
  shownTimes = [];
}

$('img-topic').addEventListener('change', () => {
  const canvas = $('img-canvas');
  canvas.getContext('2d').clearRect(0, 0, canvas.width, canvas.height);
  delete canvas.dataset.frame;
  canvas.dataset.shown = 0;
  $('img-status').textContent = '';
  $('img-size').textContent = '';
  showError('img-error');
  watchImages();
});
$('img-refresh').addEventListener('click', refreshImageTopics);
tabs['image-view'] = {
  enter: async () => { await refreshImageTopics(); watchImages(); },
  leave: stopWatchingImages,
};

window.addEventListener('hashchange', () => showPlugins(location.hash.slice(1).split('+')));
showPlugins(location.hash.slice(1).split('+'));
showKitPages();
