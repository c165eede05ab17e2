'use strict';
// The page of rqt_web: four plugins over the JSON API of the rqt node (see the package README).

const $ = (id) => document.getElementById(id);
const SVG = 'http://www.w3.org/2000/svg';

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

const tabs = {};

function selectTab(name) {
  if (!document.getElementById(name)) name = 'node-graph';
  for (const button of document.querySelectorAll('#tabs button')) {
    button.classList.toggle('active', button.dataset.tab === name);
  }
  for (const section of document.querySelectorAll('.plugin')) {
    section.classList.toggle('active', section.id === name);
  }
  if (location.hash !== '#' + name) history.replaceState(null, '', '#' + name);
  if (tabs[name]) tabs[name]();
}

for (const button of document.querySelectorAll('#tabs button')) {
  button.addEventListener('click', () => selectTab(button.dataset.tab));
}

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
    element('th', {}, readOnly ? 'value' : 'expression'));
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

function svg(tag, attributes = {}, text) {
  const node = document.createElementNS(SVG, tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

function drawGraph(graph) {
  const canvas = $('graph-svg');
  canvas.setAttribute('width', Math.max(graph.width, 200));
  canvas.setAttribute('height', Math.max(graph.height, 100));
  const marker = svg('marker', { id: 'arrow', viewBox: '0 0 10 10', refX: '10', refY: '5',
    markerWidth: '8', markerHeight: '8', orient: 'auto-start-reverse' });
  marker.append(svg('path', { d: 'M 0 0 L 10 5 L 0 10 z', fill: '#333' }));
  const defs = svg('defs');
  defs.append(marker);
  const items = [defs];
  const boxes = Object.fromEntries(graph.boxes.map((box) => [box.id, box]));
  for (const edge of graph.edges) {
    const a = boxes[edge.from];
    const b = boxes[edge.to];
    const x1 = a.x + a.width;
    const y1 = a.y + a.height / 2;
    const x2 = b.x;
    const y2 = b.y + b.height / 2;
    const bend = Math.max(40, Math.abs(x2 - x1) / 2);
    items.push(svg('path', { class: 'edge',
      d: `M ${x1} ${y1} C ${x1 + bend} ${y1}, ${x2 - bend} ${y2}, ${x2} ${y2}` }));
  }
  for (const box of graph.boxes) {
    const group = svg('g');
    const title = box.kind === 'topic' ? `${box.id} [${box.types.join(', ')}]` : box.id;
    group.append(svg('title', {}, title));
    if (box.kind === 'node') {
      group.append(svg('ellipse', { class: 'node', cx: box.x + box.width / 2, cy: box.y + box.height / 2,
        rx: box.width / 2, ry: box.height / 2 }));
    } else {
      group.append(svg('rect', { class: 'topic', x: box.x, y: box.y, width: box.width, height: box.height }));
    }
    group.append(svg('text', { x: box.x + box.width / 2, y: box.y + box.height / 2 }, box.id));
    items.push(group);
  }
  canvas.replaceChildren(...items);
}

async function refreshGraph() {
  try {
    const hideDebug = $('graph-hide-debug').checked ? 1 : 0;
    const hideLeaf = $('graph-hide-leaf').checked ? 1 : 0;
    drawGraph(await api('GET', `/api/graph?hide_debug=${hideDebug}&hide_leaf_topics=${hideLeaf}`));
    showError('graph-error');
  } catch (error) {
    showError('graph-error', error);
  }
}

$('graph-refresh').addEventListener('click', refreshGraph);
$('graph-hide-debug').addEventListener('change', refreshGraph);
$('graph-hide-leaf').addEventListener('change', refreshGraph);
setInterval(() => {
  if ($('graph-auto').checked && $('node-graph').classList.contains('active')) refreshGraph();
}, 2000);
tabs['node-graph'] = refreshGraph;

// ---- Message Publisher ----------------------------------------------------------------------

let topicTypes = {};
const templates = {};

async function template(type) {
  if (!templates[type]) templates[type] = await api('GET', `/api/interface?type=${encodeURIComponent(type)}`);
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
  topicTypes = (await listGraphNames('/api/topics', 'pub-topics', 'pub-error')) ?? topicTypes;
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
    if (!messageTypes.length) messageTypes = await api('GET', '/api/interfaces?kind=msg');
    fillDatalist('pub-types', messageTypes);
  } catch (error) {
    showError('pub-error', error);
  }
});

async function patchPublisher(entry, change, box) {
  try {
    const updated = await api('PATCH', `/api/publishers/${entry.id}`, change);
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
      await api('DELETE', `/api/publishers/${entry.id}`);
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
    const entry = await api('POST', '/api/publishers', body);
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
    for (const entry of await api('GET', '/api/publishers')) await renderPublisher(entry);
  } catch (error) {
    showError('pub-error', error);
  }
}

$('pub-refresh').addEventListener('click', refreshTopics);
tabs['message-publisher'] = loadPublishers;

// ---- Service Caller -------------------------------------------------------------------------

let serviceTypes = {};
let requestType = null;

async function refreshServices() {
  serviceTypes = (await listGraphNames('/api/services', 'srv-names', 'srv-error')) ?? serviceTypes;
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
    const answer = await api('POST', '/api/call', body);
    const responseTemplate = (await template(answer.type)).response;
    $('srv-response').append(fieldTable(responseTemplate, answer.response, true));
    showError('srv-error');
  } catch (error) {
    showError('srv-error', error);
  }
});
tabs['service-caller'] = refreshServices;

// ---- Image View -----------------------------------------------------------------------------

let imageLoop = 0;  // a new number stops the previous loop

async function refreshImageTopics() {
  try {
    const topics = await api('GET', '/api/image_topics');
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

async function showImages(topic, loop) {
  let frame = 0;
  let shown = 0;
  const started = performance.now();
  while (loop === imageLoop && topic) {
    if (!$('image-view').classList.contains('active')) {
      await new Promise((resolve) => setTimeout(resolve, 300));
      continue;
    }
    try {
      const response = await fetch(`/api/image?topic=${encodeURIComponent(topic)}&after=${frame}`);
      if (!response.ok) {
        const data = await response.json().catch(() => ({}));
        throw new Error(data.error || `HTTP ${response.status}`);
      }
      frame = Number(response.headers.get('X-Frame')) || frame;
      const url = URL.createObjectURL(await response.blob());
      const image = $('img-frame');
      const previous = image.src;
      image.src = url;
      if (previous.startsWith('blob:')) URL.revokeObjectURL(previous);
      shown += 1;
      const fps = shown / ((performance.now() - started) / 1000);
      $('img-status').textContent = `frame ${frame}  ${fps.toFixed(1)} fps shown`;
      showError('img-error');
    } catch (error) {
      if (loop !== imageLoop) return;
      showError('img-error', error);
      await new Promise((resolve) => setTimeout(resolve, 1000));
    }
  }
}

$('img-topic').addEventListener('change', () => {
  imageLoop += 1;
  $('img-frame').removeAttribute('src');
  $('img-status').textContent = '';
  $('img-size').textContent = '';
  showImages($('img-topic').value, imageLoop);
});
$('img-frame').addEventListener('load', () => {
  const image = $('img-frame');
  $('img-size').textContent = `${image.naturalWidth}x${image.naturalHeight}`;
});
$('img-refresh').addEventListener('click', refreshImageTopics);
tabs['image-view'] = refreshImageTopics;

selectTab(location.hash.slice(1));
