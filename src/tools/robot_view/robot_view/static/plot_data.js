// The live plots' data as plain functions (no DOM, no uPlot): what the page does with the batches
// the server pushes (robot_view/plot_window.py makes them). node's test runner checks them
// (src/tools/robot_view/test/plot_data.test.mjs).
//
// A batch is columns {t: [s], <series>: [value or null]}, oldest first. It repeats the end of the
// previous batch (so an update the server replaced before sending loses nothing), so the page
// replaces its rows from the batch's first time on and keeps only the last `seconds`.

export const WINDOW_SECONDS = 10;

export function emptyColumns(series) {
  return Object.fromEntries(['t', ...series].map((name) => [name, []]));
}

// The page's columns with a batch merged in and rows older than `seconds` before the newest dropped.
export function mergeBatch(columns, batch, seconds = WINDOW_SECONDS) {
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

// uPlot's data for some series: x in seconds before the newest row (-10..0), then each series.
export function plotData(columns, series) {
  const times = columns.t;
  const newest = times.length ? times[times.length - 1] : 0;
  return [times.map((time) => Math.round((time - newest) * 1000) / 1000), ...series.map((name) => columns[name])];
}
