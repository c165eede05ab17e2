// Whether the kit's state changed the 3D view visibly since it was last drawn: plain functions (no
// DOM, no three.js), checked by node's test runner (src/tools/robot_view/test/view_changes.test.mjs).
//
// A render costs a whole WebGL frame (in software where there is no GPU, as in a headless browser:
// 6-7 ms of the page's main thread, which the next kit state and the mouse then wait for), and the
// IMU's jitter (0.002 rad about each axis) changes its orientation with every message. Compared
// component by component against a quarter of a pixel, that jitter redrew a kit at rest 18 times a
// second; as one angle against most of a pixel, about never.

export const VISIBLE = 0.005;  // rad: a servo's turn of half a pixel at the head (0.1 m from the pan axis)
export const VISIBLE_IMU = 0.015;  // rad: most of a pixel at the tips of the IMU's axes (55 mm out)

// The angle (rad) of the turn from one unit quaternion [x, y, z, w] to another.
export function turnBetween(a, b) {
  const dot = Math.abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]);
  return 2 * Math.acos(Math.min(1, dot));
}

// state and drawn: {pan, tilt (rad), imu ([x, y, z, w])}, each null while unknown.
export function visiblyChanged(state, drawn) {
  const moved = (now, before) => (now === null) !== (before === null)
    || (now !== null && Math.abs(now - before) > VISIBLE);
  if (moved(state.pan, drawn.pan) || moved(state.tilt, drawn.tilt)) return true;
  if ((state.imu === null) !== (drawn.imu === null)) return true;
  return state.imu !== null && turnBetween(state.imu, drawn.imu) > VISIBLE_IMU;
}
