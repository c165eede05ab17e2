// When the page's 3D view is drawn again (static/view_changes.js), under node's own test runner
// through test_page_functions_js.py.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { VISIBLE, VISIBLE_IMU, turnBetween, visiblyChanged } from '../robot_view/static/view_changes.js';

// [x, y, z, w] of a turn by `angle` rad about the unit axis [ax, ay, az]
const turn = (angle, [ax, ay, az]) => {
  const s = Math.sin(angle / 2);
  return [ax * s, ay * s, az * s, Math.cos(angle / 2)];
};
const LEVEL = [0, 0, 0, 1];
const state = (imu, pan = 0, tilt = 0) => ({ pan, tilt, imu });

// The IMU's orientation jitter: a turn about a random axis whose components each have a spread of
// 0.002 rad (imu_sim's orientation_noise), from a seeded generator so that the test repeats.
function jitters(count, sigma = 0.002) {
  let seed = 12345;
  const uniform = () => {
    seed = (seed * 1103515245 + 12345) % 2147483648;
    return (seed + 0.5) / 2147483648;
  };
  const normal = () => Math.sqrt(-2 * Math.log(uniform())) * Math.cos(2 * Math.PI * uniform());
  return Array.from({ length: count }, () => {
    const v = [normal() * sigma, normal() * sigma, normal() * sigma];
    const angle = Math.hypot(...v);
    return turn(angle, v.map((c) => c / angle));
  });
}

test('the turn between two orientations is one angle whichever sign a quaternion has', () => {
  assert.ok(Math.abs(turnBetween(LEVEL, turn(0.3, [0, 0, 1])) - 0.3) < 1e-9);
  assert.ok(Math.abs(turnBetween(turn(0.1, [1, 0, 0]), turn(0.4, [1, 0, 0])) - 0.3) < 1e-9);
  assert.ok(turnBetween(LEVEL, LEVEL.map((c) => -c)) < 1e-6);  // -q is the same orientation
  assert.equal(turnBetween(LEVEL, [0, 0, 0, 1.0000001]), 0);  // rounding past 1 is no turn
});

test('a kit at rest whose IMU jitters is not drawn again', () => {
  const drawn = state(jitters(1)[0]);
  const redrawn = jitters(1000).filter((imu) => visiblyChanged(state(imu), drawn));
  assert.equal(redrawn.length, 0);
});

test('the same jitter compared component by component with a quarter of a pixel was drawn often', () => {
  // what the page did before: the reason for one angle (view_changes.js)
  const drawn = jitters(1)[0];
  const often = jitters(1000).filter((imu) => imu.some((c, i) => Math.abs(c - drawn[i]) > VISIBLE / 2));
  assert.ok(often.length > 50, `${often.length}`);
});

test('a turn of the IMU a student can see is drawn, about any axis', () => {
  for (const axis of [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0.6, 0, 0.8]]) {
    assert.equal(visiblyChanged(state(turn(VISIBLE_IMU * 1.1, axis)), state(LEVEL)), true, `${axis}`);
    assert.equal(visiblyChanged(state(turn(VISIBLE_IMU * 0.9, axis)), state(LEVEL)), false, `${axis}`);
  }
});

test("a servo's turn is drawn past half a pixel", () => {
  assert.equal(visiblyChanged(state(LEVEL, VISIBLE * 1.1), state(LEVEL)), true);
  assert.equal(visiblyChanged(state(LEVEL, 0, -VISIBLE * 1.1), state(LEVEL)), true);
  assert.equal(visiblyChanged(state(LEVEL, VISIBLE * 0.9, VISIBLE * 0.9), state(LEVEL)), false);
});

test('a module that comes or goes is drawn', () => {
  assert.equal(visiblyChanged(state(null), state(LEVEL)), true);
  assert.equal(visiblyChanged(state(LEVEL), state(null)), true);
  assert.equal(visiblyChanged(state(LEVEL, null), state(LEVEL)), true);
  assert.equal(visiblyChanged(state(LEVEL, 0, null), state(LEVEL, 0, null)), false);
  assert.equal(visiblyChanged(state(null, null, null), state(null, null, null)), false);
});
