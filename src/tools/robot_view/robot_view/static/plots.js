// The robot view's live plots (channel "plots"): each servo's goal, position and effort and the
// IMU's roll, pitch and yaw over the last 10 s, drawn with uPlot; Pause freezes what is drawn
// while the batches keep coming, so Resume shows the live window at once.
import uPlot from 'uplot';
import { WINDOW_SECONDS, emptyColumns, mergeBatch, plotData } from '/static/plot_data.js';

const SERVO_SERIES = (servo) => [
  { name: `${servo}_goal`, label: 'goal', stroke: '#6b7280', dash: [6, 4], scale: 'rad' },
  { name: `${servo}_position`, label: 'position', stroke: '#2563eb', scale: 'rad' },
  { name: `${servo}_effort`, label: 'effort', stroke: '#f59e0b', scale: 'Nm' },
];
const PLOTS = {
  pan: { title: 'pan servo', series: SERVO_SERIES('pan'), axes: ['rad', 'N·m'] },
  tilt: { title: 'tilt servo', series: SERVO_SERIES('tilt'), axes: ['rad', 'N·m'] },
  imu: {
    title: 'IMU',
    series: [
      { name: 'roll', label: 'roll', stroke: '#dc2626', scale: 'rad' },
      { name: 'pitch', label: 'pitch', stroke: '#16a34a', scale: 'rad' },
      { name: 'yaw', label: 'yaw', stroke: '#2563eb', scale: 'rad' },
    ],
    axes: ['rad'],
  },
};
const HEIGHT = 190;

// A y range at least `span` tall around the data, padded by 8 %: uPlot's own range for a flat line
// (a servo at rest, effort 0) is 0..100, which hides the line on the axis.
function rangeAtLeast(span) {
  return (plot, min, max) => {
    if (min === null || max === null) return [-span / 2, span / 2];
    const centre = (min + max) / 2;
    const half = Math.max(max - min, span) / 2 * 1.08;
    return [centre - half, centre + half];
  };
}

function makePlot(key, spec) {
  const target = document.getElementById(`plot-${key}`);
  const width = target.clientWidth || 400;
  const axes = [{ label: 's', size: 36 }, { scale: 'rad', label: spec.axes[0], size: 48 }];
  if (spec.axes[1]) axes.push({ scale: 'Nm', label: spec.axes[1], side: 1, size: 52, grid: { show: false } });
  const options = {
    title: spec.title,
    width,
    height: HEIGHT,
    // x: seconds before the newest sample, always the whole window
    scales: { x: { time: false, range: [-WINDOW_SECONDS, 0] }, rad: { range: rangeAtLeast(0.5) },
              Nm: { range: rangeAtLeast(0.5) } },
    series: [{ label: 't (s)' },
             ...spec.series.map((s) => ({ label: s.label, stroke: s.stroke, dash: s.dash, scale: s.scale,
                                          width: 1.5, spanGaps: true, points: { show: false } }))],
    axes,
    cursor: { drag: { x: false, y: false } },
    legend: { live: false },
  };
  const plot = new uPlot(options, [[], ...spec.series.map(() => [])], target);
  // as wide as its place in the page, whatever the window's width
  new ResizeObserver(() => {
    if (target.clientWidth && target.clientWidth !== plot.width) plot.setSize({ width: target.clientWidth, height: HEIGHT });
  }).observe(target);
  return plot;
}

export function startPlots(socket, view, showError) {
  const names = Object.values(PLOTS).flatMap((spec) => spec.series.map((s) => s.name));
  let columns = emptyColumns(names);
  const plots = Object.fromEntries(Object.entries(PLOTS).map(([key, spec]) => [key, makePlot(key, spec)]));
  const pauseButton = document.getElementById('pause');
  view.plots = { paused: false, batches: 0 };

  function draw() {
    for (const [key, spec] of Object.entries(PLOTS)) {
      plots[key].setData(plotData(columns, spec.series.map((s) => s.name)));
    }
  }

  socket.subscribe('plots', {}, (batch) => {
    columns = mergeBatch(columns, batch);
    view.plots.batches += 1;
    if (!view.plots.paused) draw();
  }, showError);

  pauseButton.addEventListener('click', () => {
    view.plots.paused = !view.plots.paused;
    pauseButton.textContent = view.plots.paused ? 'Resume' : 'Pause';
    pauseButton.setAttribute('aria-pressed', String(view.plots.paused));
    if (!view.plots.paused) draw();
  });

  // What a plot draws now, for a test: {x: [...], <label>: [...]} (x in s before the newest sample).
  view.plotted = (key) => {
    const data = plots[key].data;
    return Object.fromEntries([['x', Array.from(data[0] || [])],
                               ...PLOTS[key].series.map((s, i) => [s.label, Array.from(data[i + 1] || [])])]);
  };
}
