// The page's plot data functions (static/plot_data.js), run by node's own test runner through
// test_page_functions_js.py.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import {
  MIN_STEP, alignedRanges, columnsCsv, emptyColumns, mergeBatch, plotData, recordedOverlay, recordingOf,
  stepMeasurements,
} from '../robot_view/static/plot_data.js';

const rows = (from, to, step = 1) => {
  const t = [];
  for (let time = from; time <= to + 1e-9; time += step) t.push(time);
  return { t, position: t.map((time) => time * 10) };
};

test('a first batch is taken as it is', () => {
  const merged = mergeBatch(emptyColumns(['position']), rows(0, 3));
  assert.deepEqual(merged, rows(0, 3));
});

test('an overlapping batch replaces the rows from its first time on', () => {
  const columns = mergeBatch(emptyColumns(['position']), rows(0, 5));
  const batch = { t: [4, 5, 6], position: [41, 51, 61] };  // 4 and 5 again, complete now
  assert.deepEqual(mergeBatch(columns, batch), { t: [0, 1, 2, 3, 4, 5, 6], position: [0, 10, 20, 30, 41, 51, 61] });
});

test('only the last window is kept', () => {
  const merged = mergeBatch(emptyColumns(['position']), rows(0, 30), 10);
  assert.equal(merged.t[0], 20);
  assert.equal(merged.t.at(-1), 30);
  const later = mergeBatch(merged, { t: [35], position: [350] }, 10);
  assert.deepEqual(later.t, [25, 26, 27, 28, 29, 30, 35]);
});

test('a series a batch lacks is null, an empty batch changes nothing', () => {
  const columns = emptyColumns(['position', 'goal']);
  const merged = mergeBatch(columns, { t: [1, 2], position: [1, 2] });
  assert.deepEqual(merged.goal, [null, null]);
  assert.equal(mergeBatch(merged, { t: [], position: [] }), merged);
});

test("uPlot's data: x in seconds before the newest row, then the series", () => {
  assert.deepEqual(plotData({ t: [100.5, 101, 102.25], position: [1, 2, 3] }, ['position']),
                   [[-1.75, -1.25, 0], [1, 2, 3]]);
  assert.deepEqual(plotData(emptyColumns(['position']), ['position']), [[], []]);
});

test('a window of the kept rows: only the last seconds are plotted', () => {
  const columns = rows(0, 60, 1);
  const [x, position] = plotData(columns, ['position'], 5);
  assert.deepEqual(x, [-5, -4, -3, -2, -1, 0]);
  assert.deepEqual(position, [550, 560, 570, 580, 590, 600]);
  assert.equal(plotData(columns, ['position'])[0].length, 61);  // 60 s kept, all drawn
});

test('the zeros of the rad and N*m scales are at the same height', () => {
  // a servo at 1.57 rad (all positive) and an effort swinging both ways
  const ranges = alignedRanges({ rad: [0, 1.57], Nm: [-0.3, 0.1] });
  const zero = ([low, high]) => -low / (high - low);
  assert.ok(Math.abs(zero(ranges.rad) - zero(ranges.Nm)) < 1e-9, JSON.stringify(ranges));
  for (const [scale, [low, high]] of Object.entries(ranges)) {
    assert.ok(low < 0 && high > 0, scale);
  }
  assert.ok(ranges.rad[1] >= 1.57 && ranges.Nm[0] <= -0.3 && ranges.Nm[1] >= 0.1);
  // flat data (a servo at rest, no effort) still gets a range that shows the line
  const flat = alignedRanges({ rad: [0, 0], Nm: [null, null] });
  assert.ok(flat.rad[1] - flat.rad[0] >= 0.5);
});

test("the last goal step's rise, overshoot, settling and error", () => {
  // goal 0 -> 1 at t = 1; the position rises linearly from t = 1 to t = 2, overshoots to 1.1 at 2.2,
  // and is back within 2 % from t = 2.52 on (1.1 falling 0.25/s to 1.0 at 2.6)
  const times = [];
  const goals = [];
  const positions = [];
  for (let i = 0; i <= 400; i += 1) {
    const t = i * 0.01;
    times.push(t);
    goals.push(t < 1 ? 0 : 1);
    let p = 0;
    if (t >= 1 && t < 2) p = t - 1;
    else if (t >= 2 && t < 2.2) p = 1 + (t - 2) / 2;
    else if (t >= 2.2 && t < 2.6) p = 1.1 - (t - 2.2) / 4;
    else if (t >= 2.6) p = 1.005;
    positions.push(p);
  }
  const step = stepMeasurements(times, goals, positions);
  assert.equal(step.time, 1);
  assert.equal(step.from, 0);
  assert.equal(step.to, 1);
  assert.ok(Math.abs(step.rise - 0.8) < 0.02, step.rise);
  assert.ok(Math.abs(step.overshoot - 10) < 0.6, step.overshoot);
  assert.ok(Math.abs(step.settling - 1.52) < 0.02, step.settling);
  assert.ok(Math.abs(step.error - -0.005) < 1e-9, step.error);
  assert.equal(stepMeasurements([0, 1], [0.5, 0.5], [0, 0]), null);  // never stepped
});

test('goal changes under MIN_STEP (the small moves of a steering node) are not measured as steps', () => {
  assert.equal(MIN_STEP, 0.1);
  const times = [0, 0.1, 0.2, 0.3, 0.4, 0.5];
  assert.equal(stepMeasurements(times, [0, 0, 0.02, 0.02, 0.04, 0.04], [0, 0, 0, 0.03, 0.03, 0.04]), null);
  // the last step of 0.1 rad or more is measured, and the small changes after it end its samples
  const step = stepMeasurements(times, [0, 0.5, 0.5, 0.5, 0.52, 0.52], [0, 0, 0.3, 0.5, 0.5, 0.52]);
  assert.equal(step.from, 0);
  assert.equal(step.to, 0.5);
  assert.equal(step.time, 0.1);
});

test('CSV: a header and a row per bucket, t from the first row, an empty cell for no sample', () => {
  assert.equal(columnsCsv({ t: [1764705600.5, 1764705600.52], pan_goal: [1.57, 1.57], pan_position: [0.2, null] }),
               't,unix_time,pan_goal,pan_position\n0,1764705600.5,1.57,0.2\n0.02,1764705600.52,1.57,\n');
  assert.equal(columnsCsv({ t: [], pan_goal: [] }), 't,unix_time,pan_goal\n');
});

test('a recording lies under the live plot with both last goal steps lined up', () => {
  // recorded: a step at -2 s of its own end, the position reaching 1 a second later
  const recorded = { x: [-3, -2.5, -2, -1.5, -1, -0.5, 0], goal: [0, 0, 1, 1, 1, 1, 1],
                     position: [0, 0, 0, 0.5, 1, 1, 1] };
  // live: the same step at -4 s
  const liveX = [-5, -4.5, -4, -3.5, -3, -2.5];
  const overlay = recordedOverlay(liveX, [0, 0, 1, 1, 1, 1], [0, 0, 0, 0.2, 0.4, 0.6], recorded);
  assert.deepEqual(overlay, [0, 0, 0, 0.5, 1, 1]);
  // no step in the live plot: end on end; nothing recorded there: null
  assert.deepEqual(recordedOverlay([-1, 0, 5], [0, 0, 0], [0, 0, 0], recorded), [1, 1, null]);
  assert.deepEqual(recordedOverlay([0], [0], [0], null), [null]);
});

test('a recording is the rows between two times, x before its end', () => {
  const columns = { t: [10, 10.5, 11, 11.5], pan_goal: [0, 1, 1, 1], pan_position: [0, 0.2, 0.9, 1] };
  assert.deepEqual(recordingOf(columns, 'pan', 10.5, 11.2), { x: [-0.5, 0], goal: [1, 1], position: [0.2, 0.9] });
});
