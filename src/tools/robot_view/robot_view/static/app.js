// The robot view: the Owl Kit as a three.js model that follows the servos' joints and the IMU's
// orientation pushed by the server (channel "kit"), the camera's frames (channel "camera"), and
// the IMU block turned with the mouse ("hold_imu" commands to the simulated IMU); the camera
// scene's ball and person around the head (scene.js); beside it the live plots (plots.js) and the
// servos' controls (controls.js), on the same socket.
// The model works in base_link's frame (metres, z up), from shared/specs/olive_hardware.md §7.
import * as THREE from 'three';
import { OrbitControls } from '../lib/three/examples/jsm/controls/OrbitControls.js';
import { showKitPages } from '../owl/links.js';
import { OwlSocket } from '../owl/socket.js';
import { startControls } from './controls.js';
import { startPlots } from './plots.js';
import { startScene } from './scene.js';
import { visiblyChanged } from './view_changes.js';

const DRAG_RADIANS_PER_PIXEL = 0.01;
const FPS_WINDOW = 2000;  // ms: the shown frame rate is the frames received in the last 2 s, / 2 s
const STALE_AFTER = 2000;  // ms without a camera frame before its picture is greyed out as frozen

const status = document.getElementById('status');
const errors = document.getElementById('errors');
// Connection lost: everything shown is frozen, and greyed out to say so, until the server is back.
const socket = new OwlSocket((connected, detail) => {
  document.body.classList.toggle('stale', !connected);
  status.textContent = connected ? (detail || 'connected')
    : `${detail}. What the page shows is frozen; start robot_view again `
      + '(ros2 launch robot_view robot_view.launch.py) and it comes back by itself.';
});

// What the tests read (page.evaluate) and the page shows.
// lastFrame: robot_view's count of the camera frames it took from DDS, sent with each frame: where
// it grows faster than frames, frames were dropped between robot_view and this page.
// renders: how many times the 3D view was drawn.
const view = { pan: null, tilt: null, imu: null, kit: null, frames: 0, lastFrame: 0, fps: 0, commandsSent: 0,
               errors: [], renders: 0 };
window.robotView = view;

// ---- scene --------------------------------------------------------------------------------------
const container = document.getElementById('model');
// Whether WebGL runs in software (SwiftShader in a headless or GPU-less browser, llvmpipe): there
// antialiasing doubled the main thread's input delay while dragging (bench/robot_view_smoothness.py),
// so it is on only where a GPU draws.
function softwareRendering() {
  const canvas = document.createElement('canvas');
  const gl = canvas.getContext('webgl2') || canvas.getContext('webgl');
  if (!gl) return true;
  const debug = gl.getExtension('WEBGL_debug_renderer_info');  // RENDERER alone says "WebKit WebGL"
  const name = String(gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}
view.softwareRendering = softwareRendering();
const renderer = new THREE.WebGLRenderer({ antialias: !view.softwareRendering, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(container.clientWidth, container.clientHeight, false);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xe5e7eb);
const camera = new THREE.PerspectiveCamera(42, container.clientWidth / container.clientHeight, 0.01, 10);
camera.up.set(0, 0, 1);
camera.position.set(-0.36, -0.40, 0.26);
const LOOK_AT = new THREE.Vector3(-0.03, 0, 0.07);
camera.lookAt(LOOK_AT);
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(-1, -2, 3);
scene.add(sun);
const grid = new THREE.GridHelper(0.6, 12, 0x9ca3af, 0xd1d5db);
grid.rotation.x = Math.PI / 2;  // GridHelper lies in x-z; ours is the x-y floor
scene.add(grid);

function box(sx, sy, sz, color, x = 0, y = 0, z = 0) {
  const mesh = new THREE.Mesh(new THREE.BoxGeometry(sx, sy, sz),
                              new THREE.MeshStandardMaterial({ color, roughness: 0.6 }));
  mesh.position.set(x, y, z);
  return mesh;
}

function cylinder(radius, length, color, axis) {
  // CylinderGeometry's axis is y: turn it onto the wanted axis
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length, 32),
                              new THREE.MeshStandardMaterial({ color, roughness: 0.4 }));
  if (axis === 'x') mesh.rotation.z = Math.PI / 2;
  if (axis === 'z') mesh.rotation.x = Math.PI / 2;
  return mesh;
}

// base plate and the pan servo's body (its bottom face on base_link, 46 mm tall)
scene.add(box(0.12, 0.12, 0.006, 0x4b5563, 0, 0, -0.003));
scene.add(box(0.04, 0.04, 0.046, 0x2563eb, 0, 0, 0.023));
// pan: everything above the pan horn turns about +z at z = 46 mm
const panJoint = new THREE.Group();
panJoint.position.set(0, 0, 0.046);
scene.add(panJoint);
const panHorn = cylinder(0.012, 0.004, 0xf59e0b, 'z');
panHorn.position.z = 0.002;
panJoint.add(panHorn);
panJoint.add(box(0.012, 0.012, 0.04, 0x9ca3af, 0, 0, 0.02));            // X-Bolt and bracket
panJoint.add(box(0.04, 0.046, 0.04, 0x2563eb, 0, 0.012, 0.04));         // tilt servo body, on its side
// tilt: turns about -y of base_link (at zero pan) through (0, 0, 86 mm); positive looks down
const tiltJoint = new THREE.Group();
tiltJoint.position.set(0, -0.011, 0.04);
panJoint.add(tiltJoint);
const tiltHorn = cylinder(0.012, 0.004, 0xf59e0b, 'y');
tiltJoint.add(tiltHorn);
tiltJoint.add(box(0.03, 0.004, 0.075, 0x9ca3af, -0.005, -0.004, 0.037));  // L-bracket up to the eye
// the camera eye, its lens along -x of base_link at zero angles
const eye = new THREE.Group();
eye.position.set(-0.02, 0.011, 0.075);
tiltJoint.add(eye);
eye.add(box(0.03, 0.04, 0.04, 0x10b981));
const lens = cylinder(0.009, 0.012, 0x111827, 'x');
lens.position.x = -0.02;
eye.add(lens);

// the IMU: a block of its own beside the kit, turned by its measured orientation
const imuBlock = new THREE.Group();
imuBlock.position.set(0.12, -0.07, 0.04);
scene.add(imuBlock);
const imuBody = box(0.06, 0.04, 0.016, 0xdc2626);
imuBlock.add(imuBody);
imuBlock.add(new THREE.AxesHelper(0.055));  // x red, y green, z blue: the IMU's own axes

// At most one render per animation frame: updates come faster than a screen shows them (two
// joints and the IMU), and rendering each would starve the camera and the mouse.
let renderQueued = false;
function render() {
  if (renderQueued) return;
  renderQueued = true;
  requestAnimationFrame(() => {
    renderQueued = false;
    view.renders += 1;
    renderer.render(scene, camera);
  });
}

let dragging = null;  // {x, y} of the last pointer position while the IMU is held

// ---- the kit's state, pushed ---------------------------------------------------------------------
const degrees = (radians) => (radians === null ? '–' : `${(radians * 180 / Math.PI).toFixed(1)}°`);

function eulerOf(q) {
  // roll, pitch, yaw (ZYX) of an (x, y, z, w) quaternion, for the readout
  const [x, y, z, w] = q;
  const roll = Math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
  const pitch = Math.asin(Math.max(-1, Math.min(1, 2 * (w * y - z * x))));
  const yaw = Math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
  return [roll, pitch, yaw];
}

// Only a change a student could see, measured from what the last render drew, is rendered
// (view_changes.js says why).
let drawn = { pan: null, tilt: null, imu: null };

let updateScene = () => false;  // set once the scene's objects exist (below)
// ---- what runs of the kit, and what steers it (the server looks at the ROS graph every second) ----
const kitState = document.getElementById('kit-state');
const imuHint = document.getElementById('imu-hint');
const levelButton = document.getElementById('level');
const cameraMissing = document.getElementById('camera-missing');
const KIT_LAUNCH = '<code>ros2 launch robot_view robot_view.launch.py</code>';

function showKit(kit) {
  view.kit = kit;
  if (kit === null) return;  // not looked yet: nothing said (a line that then goes would move the page)
  const modules = kit.modules;
  levelButton.disabled = !kit.imu_steerable;
  showLiveness();
  if (!modules.imu) {
    imuHint.textContent = 'No IMU runs: the block has nothing to hold.';
  } else if (!kit.imu_steerable) {
    imuHint.innerHTML = 'The IMU follows its own motion (the simulated hand of owl_kit.launch.py, or a '
      + 'real module), so dragging the block does nothing. To hold it with the mouse, start the kit with '
      + `${KIT_LAUNCH} (its IMU takes the page's orientation).`;
  } else {
    const steered = kit.steered.pan.length || kit.steered.tilt.length;
    imuHint.innerHTML = 'Drag the IMU block: left/right turns it (yaw), up/down tips it (pitch).'
      + (steered ? '' : ' Nothing steers the servos from the IMU yet: run '
        + '<code>ros2 run olive_servo imu_control_robot</code> and the head follows it.');
  }
  levelButton.title = kit.imu_steerable ? 'hold the IMU flat, facing ahead'
    : 'only a simulated IMU started with motion:=command takes an orientation from this page';
  showCamera();
}

// ---- modules that send nothing or do not run: greyed where the page shows them --------------------
const MODULE_NAMES = { imu: 'the IMU', pan: 'the pan servo', tilt: 'the tilt servo', camera: 'the camera' };
view.silent = {};

// What the page shows of a module is live only while its data comes (the server says which modules
// have sent nothing for a second, and for how long) and the graph has it.
function showLiveness() {
  const silent = view.silent;
  const gone = (module) => module in silent || (view.kit !== null && !view.kit.modules[module]);
  for (const element of document.querySelectorAll('[data-module]')) {
    element.classList.toggle('silent', gone(element.dataset.module));
  }
  for (const line of document.querySelectorAll('#silences [data-silence]')) {
    const seconds = silent[line.dataset.silence];
    line.textContent = seconds === undefined ? ''
      : `No data from ${MODULE_NAMES[line.dataset.silence]} for ${seconds} s.`;
  }
  imuBody.material.color.set(gone('imu') ? 0x9ca3af : 0xdc2626);
  render();
  showKitLine();
  if (view.showServoAvailability) view.showServoAvailability();
}

// The line above the view: what of the kit does not run, or runs and sends nothing (a module that
// was killed stays in the graph for its DDS lease, about 10 s, but sends nothing at once).
function showKitLine() {
  if (view.kit === null) return;  // not looked yet: nothing said (a line that then goes would move the page)
  const modules = view.kit.modules;
  const missing = Object.keys(modules).filter((name) => !modules[name]);
  const silent = Object.keys(view.silent).filter((name) => modules[name]);
  if (missing.length === Object.keys(modules).length) {
    kitState.innerHTML = 'No Owl Kit module runs in this ROS domain. Start the simulated kit with this page: '
      + `${KIT_LAUNCH}, or the kit alone: <code>ros2 launch olive_sim owl_kit.launch.py</code>. `
      + 'Real modules: <code>owl network</code> checks the way to them.';
  } else if (missing.length || silent.length) {
    kitState.innerHTML = (missing.length ? `Not running: ${missing.join(', ')}. ` : '')
      + (silent.length ? `Running but sending nothing: ${silent.join(', ')}. ` : '')
      + 'The whole simulated kit: <code>ros2 launch olive_sim owl_kit.launch.py</code>.';
  } else {
    kitState.textContent = '';
  }
}

// Setting an element's text replaces its text node even when the text is the same, and the page is
// laid out and painted again: at 100 kit states a second, for five readouts that mostly stay put.
function showReadout(id, text) {
  const readout = document.getElementById(id);
  if (readout.textContent !== text) readout.textContent = text;
}

socket.subscribe('kit', {}, (state) => {
  const sceneChanged = updateScene(state.scene);
  if (JSON.stringify(state.silent) !== JSON.stringify(view.silent)) {
    view.silent = state.silent;
    showLiveness();
  }
  document.getElementById('ball-hint').hidden = !(state.scene && state.scene.ball);
  if (JSON.stringify(state.kit) !== JSON.stringify(view.kit)) showKit(state.kit);
  view.pan = state.pan;
  view.tilt = state.tilt;
  view.imu = state.imu;
  if (view.followGoal) view.followGoal();
  if (state.pan !== null) panJoint.rotation.z = state.pan;
  if (state.tilt !== null) tiltJoint.rotation.y = -state.tilt;  // about -y: a positive tilt looks down
  if (state.imu !== null && !holding()) imuBlock.quaternion.set(...state.imu);
  showReadout('pan', degrees(state.pan));
  showReadout('tilt', degrees(state.tilt));
  const [roll, pitch, yaw] = state.imu ? eulerOf(state.imu) : [null, null, null];
  showReadout('roll', degrees(roll));
  showReadout('pitch', degrees(pitch));
  showReadout('yaw', degrees(yaw));
  if (visiblyChanged(state, drawn) || sceneChanged) {
    drawn = { pan: state.pan, tilt: state.tilt, imu: state.imu };
    render();
  }
}, showError);

function showError(line) {
  view.errors.push(line);
  errors.textContent = line;
}

// ---- the camera, pushed ------------------------------------------------------------------------
const image = document.getElementById('camera');
const fpsLabel = document.getElementById('fps');
const frameTimes = [];
let cameraSince = null;  // when the first frame of this page came

// The picture, or in its place a line saying why there is none; greyed out when frames stopped.
function showCamera() {
  const now = performance.now();
  const last = frameTimes.length ? frameTimes[frameTimes.length - 1] : null;
  const running = view.kit === null || view.kit.modules.camera;
  image.hidden = view.frames === 0;
  cameraMissing.hidden = view.frames > 0;
  if (view.frames === 0) {
    cameraMissing.innerHTML = running ? 'No camera frames yet.'
      : 'No camera runs. Start the kit: <code>ros2 launch olive_sim owl_kit.launch.py</code>.';
  }
  const frozen = last !== null && now - last > STALE_AFTER;
  image.classList.toggle('stale', frozen);
  if (frozen) fpsLabel.textContent = `no frames for ${((now - last) / 1000).toFixed(0)} s`;
}
setInterval(showCamera, 500);

socket.subscribe('camera', {}, (header, payload) => {
  const url = URL.createObjectURL(new Blob([payload], { type: header.content_type }));
  const previous = image.src;
  image.src = url;
  if (previous.startsWith('blob:')) URL.revokeObjectURL(previous);
  const now = performance.now();
  if (cameraSince === null) cameraSince = now;
  frameTimes.push(now);
  while (frameTimes[0] <= now - FPS_WINDOW) frameTimes.shift();
  view.frames += 1;
  view.lastFrame = header.frame;
  // frames received over a fixed window (shorter only in the first 2 s), so the label holds still
  const span = Math.max(Math.min(FPS_WINDOW, now - cameraSince), 250);
  view.fps = frameTimes.length * 1000 / span;
  fpsLabel.textContent = `${view.fps.toFixed(1)} fps`;
  if (image.hidden || image.classList.contains('stale')) showCamera();
}, showError);

// ---- holding the IMU -----------------------------------------------------------------------------
const raycaster = new THREE.Raycaster();

function hitsImu(event) {
  const rect = renderer.domElement.getBoundingClientRect();
  const pointer = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
                                    -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  return raycaster.intersectObject(imuBody).length > 0;
}

const WORLD_Z = new THREE.Vector3(0, 0, 1);
const WORLD_Y = new THREE.Vector3(0, 1, 0);
const HOLD_EVERY = 20;  // ms: at most 50 commands a second; the newest orientation is what matters
let lastHold = -Infinity;
let trailingHold = null;
// The orientation the mouse gave. A hold still to be sent sends it, not the block's: a state of the
// kit's that comes after the mouse let go holds the IMU where it was before the last moves (seen in
// a suite: the head stopped short of the drag).
const held = new THREE.Quaternion();
const holding = () => dragging !== null || trailingHold !== null;

function sendHold() {
  // at once when the last command is old enough (no wait for a frame), else once, a little later
  const wait = lastHold + HOLD_EVERY - performance.now();
  if (wait > 0) {
    if (trailingHold === null) trailingHold = setTimeout(() => { trailingHold = null; sendHold(); }, wait);
    return;
  }
  lastHold = performance.now();
  if (socket.command('hold_imu', { orientation: { x: held.x, y: held.y, z: held.z, w: held.w } })) {
    view.commandsSent += 1;
  }
}

renderer.domElement.addEventListener('pointerdown', (event) => {
  if (!hitsImu(event)) return;
  event.stopImmediatePropagation();  // the block is held: the view does not orbit
  dragging = { x: event.clientX, y: event.clientY };
  renderer.domElement.setPointerCapture(event.pointerId);
  container.style.cursor = 'grabbing';
});
// Chromium holds pointermove events back to the next animation frame; pointerrawupdate (Chromium,
// secure pages such as 127.0.0.1) comes as the mouse moves, so a held IMU's command leaves up to a
// frame sooner. pointermove still serves the rest (touch, other browsers): a move the raw update
// already took comes again with no distance, and does nothing.
function dragImu(event) {
  if (!dragging) return;
  const dx = event.clientX - dragging.x;
  const dy = event.clientY - dragging.y;
  if (dx === 0 && dy === 0) return;
  dragging = { x: event.clientX, y: event.clientY };
  // left/right turns about the world's vertical (yaw), up/down about the world's y (pitch)
  const turn = new THREE.Quaternion().setFromAxisAngle(WORLD_Z, dx * DRAG_RADIANS_PER_PIXEL)
    .multiply(new THREE.Quaternion().setFromAxisAngle(WORLD_Y, dy * DRAG_RADIANS_PER_PIXEL));
  imuBlock.quaternion.premultiply(turn).normalize();
  held.copy(imuBlock.quaternion);
  render();
  sendHold();
}
renderer.domElement.addEventListener('pointerrawupdate', dragImu);
renderer.domElement.addEventListener('pointermove', dragImu);
function release(event) {
  if (!dragging) return;
  dragging = null;
  container.style.cursor = '';
  if (renderer.domElement.hasPointerCapture(event.pointerId)) renderer.domElement.releasePointerCapture(event.pointerId);
}
renderer.domElement.addEventListener('pointerup', release);
renderer.domElement.addEventListener('pointercancel', release);

document.getElementById('level').addEventListener('click', () => {
  if (socket.command('level')) view.commandsSent += 1;
});

// Where the IMU block is on the page, for a test's mouse.
view.imuOnPage = () => {
  const rect = renderer.domElement.getBoundingClientRect();
  const centre = new THREE.Vector3();
  imuBody.getWorldPosition(centre);
  centre.project(camera);
  return { x: rect.left + (centre.x + 1) / 2 * rect.width, y: rect.top + (1 - centre.y) / 2 * rect.height };
};
updateScene = startScene({ scene, camera, renderer, render, socket, view, showError });
view.panOfModel = () => panJoint.rotation.z;
view.tiltOfModel = () => -tiltJoint.rotation.y;

// Orbit (drag the background), zoom (wheel, pinch) and pan (right button, two fingers) the view.
// Made last, so the IMU's and the ball's drags, which stop their pointerdown, come first.
const orbit = new OrbitControls(camera, renderer.domElement);
orbit.target.copy(LOOK_AT);
orbit.minDistance = 0.15;
orbit.maxDistance = 1.5;
orbit.update();
orbit.addEventListener('change', render);
view.cameraDistance = () => camera.position.distanceTo(orbit.target);
view.cameraPosition = () => camera.position.toArray();

// The view fills its panel at any width (3:2, as the panel's CSS says).
function fitToPanel() {
  const width = container.clientWidth;
  const height = container.clientHeight;
  if (!width || !height) return;
  renderer.setSize(width, height, false);  // the drawing buffer; the CSS sizes the canvas
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
  render();
}
new ResizeObserver(fitToPanel).observe(container);
render();

startPlots(socket, view, showError);
startControls(socket, view);
showKitPages();
