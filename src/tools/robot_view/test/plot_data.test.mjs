// The page's plot data functions (static/plot_data.js), run by node's own test runner through
// test_plot_data_js.py.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { emptyColumns, mergeBatch, plotData } from '../robot_view/static/plot_data.js';

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
