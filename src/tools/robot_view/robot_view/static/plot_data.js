// The live plots' data as plain functions (no DOM, no uPlot): what the page does with the batches
// the server pushes (robot_view/plot_window.py makes them). node's test runner checks them
// (src/tools/robot_view/test/plot_data.test.mjs).
//
// A batch is columns {t: [s], <series>: [value or null]}, oldest first. It repeats the end of the
// previous batch (so an update the server replaced before sending loses nothing), so the page
// replaces its rows from the batch's first time on and keeps only the last `seconds`.

export const KEPT_SECONDS = 60;  // what the page keeps (the server keeps as much): the widest window
export const WINDOWS = [5, 10, 20, 30, 60];  // s a student can choose to see
export const WINDOW_SECONDS = 10;  // the window shown at first

export function emptyColumns(series) {
  return Object.fromEntries(['t', ...series].map((name) => [name, []]));
}

// The page's columns with a batch merged in and rows older than `seconds` before the newest dropped.
export function mergeBatch(columns, batch, seconds = KEPT_SECONDS) {
  const count = batch.t.length;
  if (count === 0) return columns;
  let end = columns.t.length;  // rows before `end` are older than the batch
  while (end > 0 && columns.t[end - 1] >= batch.t[0]) end -= 1;
  const times = columns.t.slice(0, end).concat(batch.t);
  const oldest = batch.t[count - 1] - seconds;
  let start = 0;
  while (times[start] < oldest) start += 1;
  const merged = {};
  for (const name of Object.keys(columns)) {
    const fresh = name in batch ? batch[name] : new Array(count).fill(null);
    merged[name] = columns[name].slice(0, end).concat(fresh).slice(start);
  }
  return merged;
}

// uPlot's data for some series: x in seconds before the newest row (-seconds..0), then each series;
// only the rows of the last `seconds`.
export function plotData(columns, series, seconds = KEPT_SECONDS) {
  const times = columns.t;
  const newest = times.length ? times[times.length - 1] : 0;
  let start = 0;
  while (start < times.length && times[start] < newest - seconds - 1e-9) start += 1;
  return [times.slice(start).map((time) => Math.round((time - newest) * 1000) / 1000),
          ...series.map((name) => columns[name].slice(start))];
}

// Y ranges of several scales (e.g. rad and N*m) with their zeros at the same height, so an effort of
// 0 is drawn on the 0 rad line. extents: {scale: [min, max]} of the data (nulls when it has none).
// Each range holds its data and 0, is at least minSpan tall, padded by 8 %, and keeps 0 at least 5 %
// from its edges; then the scales whose 0 sits lower than the highest 0 grow downwards to match it.
export function alignedRanges(extents, minSpan = 0.5) {
  const ranges = {};
  for (const [scale, [min, max]] of Object.entries(extents)) {
    let low = Math.min(min ?? 0, 0);
    let high = Math.max(max ?? 0, 0);
    const grow = Math.max(minSpan - (high - low), 0);
    low -= grow / 2;
    high += grow / 2;
    const pad = (high - low) * 0.04;
    low -= pad;
    high += pad;
    const margin = (high - low) * 0.05;  // 0 never on an edge, so every scale can match any other
    ranges[scale] = [Math.min(low, -margin), Math.max(high, margin)];
  }
  const zeroAt = (range) => -range[0] / (range[1] - range[0]);  // height of 0 from the bottom, 0..1
  const highest = Math.max(...Object.values(ranges).map(zeroAt));
  for (const range of Object.values(ranges)) {
    if (zeroAt(range) < highest) range[0] = -highest * range[1] / (1 - highest);
  }
  return ranges;
}

// A goal change smaller than this is no step to measure: imu_control_robot moves its goals by
// hundredths of a radian 100 times a second, and a 0.02 rad "step" measured an overshoot of 363 %
// that was the encoder's resolution. A nudge of the pad's arrows (0.1 rad) is one.
export const MIN_STEP = 0.1;  // rad

// The last step of a goal (MIN_STEP or more) and the response to it, measured from plotted rows:
// times (s), the held goal and the position (nulls where a bucket had none). null when the goal
// never stepped. Rise: 10 % to 90 % of the step; overshoot: beyond the goal, in % of the step;
// settling: from the step until the position stays within band (2 %) of the step around the goal,
// null if it has not yet; error: goal minus the last position.
export function stepMeasurements(times, goals, positions, band = 0.02) {
  let step = -1;
  for (let i = goals.length - 1; i > 0; i -= 1) {
    if (goals[i] !== null && goals[i - 1] !== null && Math.abs(goals[i] - goals[i - 1]) >= MIN_STEP - 1e-9) {
      step = i;
      break;
    }
  }
  if (step < 0) return null;
  const from = goals[step - 1];
  const to = goals[step];
  const size = to - from;
  const progress = (position) => (position - from) / size;  // 0 at the start, 1 at the goal
  const samples = [];
  for (let i = step; i < times.length && goals[i] === to; i += 1) {
    if (positions[i] !== null) samples.push([times[i], positions[i]]);
  }
  if (!samples.length) return null;
  const at = (fraction) => samples.find(([, position]) => progress(position) >= fraction)?.[0] ?? null;
  const t10 = at(0.1);
  const t90 = at(0.9);
  const peak = Math.max(...samples.map(([, position]) => progress(position)));
  let settled = null;
  for (let i = samples.length - 1; i >= 0; i -= 1) {
    if (Math.abs(progress(samples[i][1]) - 1) > band) break;
    settled = samples[i][0];
  }
  const last = samples[samples.length - 1];
  // Settled only if the band has held for a while (a tenth of what was measured, at least 3 samples).
  const held = settled !== null && samples.length - samples.findIndex(([time]) => time === settled) >= 3;
  return {
    time: times[step], from, to,
    rise: t10 !== null && t90 !== null ? t90 - t10 : null,
    overshoot: Math.max(peak - 1, 0) * 100,
    settling: held ? settled - times[step] : null,
    error: to - last[1],
  };
}

// The last recording's position under a live plot: each live x (s before the newest row) gets the
// recorded position at the same time after its last goal step as the live plot's last goal step, so
// two tunings' responses to a step lie on each other; with no step in either, at the same time
// before the end. recorded: {x, goal, position}, x in s before the recording's end. null where the
// recording has no sample within tolerance (s) of that time.
export function recordedOverlay(liveX, liveGoals, livePositions, recorded, tolerance = 0.05) {
  if (!recorded || !recorded.x.length) return liveX.map(() => null);
  const live = stepMeasurements(liveX, liveGoals, livePositions);
  const past = stepMeasurements(recorded.x, recorded.goal, recorded.position);
  const offset = live && past ? past.time - live.time : 0;
  const times = recorded.x;
  return liveX.map((x) => {
    const wanted = x + offset;
    let low = 0;
    let high = times.length - 1;
    while (low < high) {  // the first sample at or after wanted
      const middle = (low + high) >> 1;
      if (times[middle] < wanted) low = middle + 1; else high = middle;
    }
    const nearest = low > 0 && Math.abs(times[low - 1] - wanted) < Math.abs(times[low] - wanted) ? low - 1 : low;
    return Math.abs(times[nearest] - wanted) <= tolerance ? recorded.position[nearest] : null;
  });
}

// A recording's rows of one servo from the page's columns between two times (s since the epoch, as
// columns.t): {x, goal, position}, x in s before its end.
export function recordingOf(columns, servo, from, to) {
  const rows = columns.t.map((time, i) => i).filter((i) => columns.t[i] >= from && columns.t[i] <= to);
  const end = rows.length ? columns.t[rows[rows.length - 1]] : to;
  return { x: rows.map((i) => Math.round((columns.t[i] - end) * 1000) / 1000),
           goal: rows.map((i) => columns[`${servo}_goal`][i]),
           position: rows.map((i) => columns[`${servo}_position`][i]) };
}

// The kept columns as CSV: a header row, then one row per bucket; t in seconds from the first row
// (what a spreadsheet plots against), unix_time the clock's seconds since the epoch; an empty cell
// where a series had no sample.
export function columnsCsv(columns) {
  const names = Object.keys(columns).filter((name) => name !== 't');
  const lines = [['t', 'unix_time', ...names].join(',')];
  const start = columns.t.length ? columns.t[0] : 0;
  for (let row = 0; row < columns.t.length; row += 1) {
    const since = Math.round((columns.t[row] - start) * 1000) / 1000;
    const cells = names.map((name) => (columns[name][row] === null ? '' : String(columns[name][row])));
    lines.push([String(since), String(columns.t[row]), ...cells].join(','));
  }
  return `${lines.join('\n')}\n`;
}
