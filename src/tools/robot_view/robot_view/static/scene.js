// What stands around the robot in the simulated camera's scene (scene:=ball or scene:=person),
// drawn in the model around the head, and the ball dragged with the mouse ("place_ball" commands
// to the camera, which refuses a place outside the ball's world with one line).
// Directions come as (azimuth, elevation) in rad from the camera at rest: azimuth 0 is where the
// lens looks at zero pan (-x of base_link here), growing to the left (counter-clockwise from above).
import * as THREE from 'three';

const PIVOT = new THREE.Vector3(0, 0, 0.1);  // about the camera's height on the head
const BALL_DISTANCE = 0.15;    // m in the model (the ball is about 1 m away in the scene)
const PERSON_DISTANCE = 0.18;  // m in the model (the person stands 3.5 m away)
const BALL_RADIUS = 0.01;
const PLACE_EVERY = 50;        // ms: at most 20 place_ball commands a second while dragging
const BONES = [['nose', 'left_eye'], ['nose', 'right_eye'], ['left_eye', 'right_eye'],
  ['left_ear', 'left_eye'], ['right_ear', 'right_eye'], ['left_shoulder', 'right_shoulder'],
  ['left_shoulder', 'left_elbow'], ['left_elbow', 'left_wrist'], ['right_shoulder', 'right_elbow'],
  ['right_elbow', 'right_wrist'], ['left_shoulder', 'left_hip'], ['right_shoulder', 'right_hip'],
  ['left_hip', 'right_hip'], ['left_hip', 'left_knee'], ['left_knee', 'left_ankle'],
  ['right_hip', 'right_knee'], ['right_knee', 'right_ankle']];

export function direction(azimuth, elevation) {
  return new THREE.Vector3(-Math.cos(elevation) * Math.cos(azimuth), -Math.cos(elevation) * Math.sin(azimuth),
                           Math.sin(elevation));
}

export function startScene({ scene, camera, renderer, render, socket, view, showError }) {
  const ball = new THREE.Mesh(new THREE.SphereGeometry(BALL_RADIUS, 24, 16),
                              new THREE.MeshStandardMaterial({ color: 0xd7141c, roughness: 0.35 }));
  ball.visible = false;
  scene.add(ball);
  const person = new THREE.Group();
  person.visible = false;
  scene.add(person);
  const bone = new THREE.LineBasicMaterial({ color: 0x1d4ed8 });
  const head = new THREE.Mesh(new THREE.SphereGeometry(0.006, 16, 12),
                              new THREE.MeshStandardMaterial({ color: 0xe1b996 }));
  let drawnPerson = '';

  function showPerson(keypoints) {
    const key = JSON.stringify(keypoints);
    if (key === drawnPerson) return;
    drawnPerson = key;
    person.clear();
    const at = (name) => PIVOT.clone().addScaledVector(direction(...keypoints[name]), PERSON_DISTANCE);
    for (const [a, b] of BONES) {
      if (!(a in keypoints && b in keypoints)) continue;
      person.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints([at(a), at(b)]), bone));
    }
    if ('nose' in keypoints) {
      head.position.copy(at('nose'));
      person.add(head);
    }
  }

  let dragging = false;
  let trailing = null;     // the timer of a place still to be sent
  let placesInFlight = 0;  // places sent and not answered yet
  // The ball stays where the mouse put it until the camera has answered its last place: a state
  // that comes meanwhile may still hold an earlier place.
  const placing = () => dragging || trailing !== null || placesInFlight > 0;
  function showBall() {
    if (ball.visible && !placing()) {
      ball.position.copy(PIVOT).addScaledVector(direction(...view.scene.ball), BALL_DISTANCE);
    }
  }
  view.scene = null;
  // Called with each state of the "kit" channel: true when the scene changed what the model shows.
  function update(shown) {
    const before = JSON.stringify(view.scene);
    view.scene = shown || null;
    if (JSON.stringify(view.scene) === before) return false;
    ball.visible = Boolean(view.scene && view.scene.ball);
    showBall();
    person.visible = Boolean(view.scene && view.scene.keypoints);
    if (person.visible) showPerson(view.scene.keypoints);
    return true;
  }

  // ---- dragging the ball: it follows the pointer on its sphere around the head ----------------
  const raycaster = new THREE.Raycaster();
  const sphere = new THREE.Sphere(PIVOT, BALL_DISTANCE);
  function pointerRay(event) {
    const rect = renderer.domElement.getBoundingClientRect();
    raycaster.setFromCamera(new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
                                              -((event.clientY - rect.top) / rect.height) * 2 + 1), camera);
    return raycaster.ray;
  }
  let lastPlace = -Infinity;
  let place = null;  // where the pointer last put the ball, as the camera takes it
  function sendPlace() {
    const wait = lastPlace + PLACE_EVERY - performance.now();
    if (wait > 0) {
      if (trailing === null) trailing = setTimeout(() => { trailing = null; sendPlace(); }, wait);
      return;
    }
    lastPlace = performance.now();
    const sent = socket.command('place_ball', place, (error) => {
      placesInFlight -= 1;
      view.ballAnswers.push(error);
      if (!error) return;  // the camera's next state shows the ball where it was put
      showError(error);
      showBall();  // back where the camera has it, unless more places are on their way
      render();
    });
    if (sent) {
      placesInFlight += 1;
      view.ballPlacesSent += 1;
    }
  }
  view.ballAnswers = [];
  view.ballPlacesSent = 0;
  renderer.domElement.addEventListener('pointerdown', (event) => {
    if (!ball.visible) return;
    pointerRay(event);
    if (raycaster.intersectObject(ball).length === 0) return;
    dragging = true;
    event.stopImmediatePropagation();  // not the IMU's drag
    renderer.domElement.setPointerCapture(event.pointerId);
  }, { capture: true });
  renderer.domElement.addEventListener('pointermove', (event) => {
    if (!dragging) return;
    const hit = pointerRay(event).intersectSphere(sphere, new THREE.Vector3());
    if (hit === null) return;
    ball.position.copy(hit);
    const d = hit.clone().sub(PIVOT).normalize();
    place = { azimuth: Math.atan2(-d.y, -d.x), elevation: Math.asin(Math.max(-1, Math.min(1, d.z))) };
    render();
    sendPlace();
  });
  function release(event) {
    if (!dragging) return;
    dragging = false;
    if (renderer.domElement.hasPointerCapture(event.pointerId)) renderer.domElement.releasePointerCapture(event.pointerId);
  }
  renderer.domElement.addEventListener('pointerup', release);
  renderer.domElement.addEventListener('pointercancel', release);

  // Where the ball is on the page, and where a direction would be, for a test's mouse.
  const onPage = (point) => {
    const rect = renderer.domElement.getBoundingClientRect();
    const p = point.clone().project(camera);
    return { x: rect.left + (p.x + 1) / 2 * rect.width, y: rect.top + (1 - p.y) / 2 * rect.height };
  };
  view.ballOnPage = () => onPage(ball.position);
  view.personParts = () => (person.visible ? person.children.length : 0);
  view.personOnPage = () => onPage(head.getWorldPosition(new THREE.Vector3()));
  view.ballPlaceOnPage = (azimuth, elevation) =>
    onPage(PIVOT.clone().addScaledVector(direction(azimuth, elevation), BALL_DISTANCE));
  return update;
}
