// The robot view's live plots (channel "plots"): each servo's goal, position and effort and the
// IMU's roll, pitch and yaw over the last 5 to 60 s (the page keeps 60), drawn with uPlot. Pause
// freezes what is drawn while the batches keep coming, so Resume shows the live window at once.
// For the PID exercise: values on hover, zoom by dragging across a plot (it pauses; double-click
// zooms out and goes live again, unless Pause had paused it first), each servo's last goal step measured from the plotted rows (rise, overshoot,
// settling, error), CSV export of what the page keeps, and the rad and N*m axes sharing their 0.
import uPlot from 'uplot';
import {
  MIN_STEP, WINDOWS, WINDOW_SECONDS, alignedRanges, columnsCsv, emptyColumns, mergeBatch, plotData, recordedOverlay,
  recordingOf, stepMeasurements,
} from './plot_data.js';

const SERVO_SERIES = (servo) => [
  { name: `${servo}_goal`, label: 'goal', stroke: '#6b7280', dash: [6, 4], scale: 'rad' },
  { name: `${servo}_position`, label: 'position', stroke: '#2563eb', scale: 'rad' },
  { name: `${servo}_effort`, label: 'effort', stroke: '#f59e0b', scale: 'Nm' },
  // the last recording's position, faint, its last goal step under the live one (not a column kept)
  { name: `${servo}_recorded`, label: 'recorded', stroke: '#93c5fd', dash: [2, 3], scale: 'rad', computed: true },
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

// The y ranges of a plot's scales from what it draws, zeros aligned (plot_data.js, alignedRanges):
// uPlot's own range for a flat line (a servo at rest, effort 0) is 0..100, which hides the line.
function yRanges(plot, spec) {
  const extents = {};
  spec.series.forEach((series, index) => {
    const values = (plot.data[index + 1] || []).filter((value) => value !== null);
    const [low, high] = extents[series.scale] || [null, null];
    if (!values.length) { extents[series.scale] = [low, high]; return; }
    extents[series.scale] = [Math.min(low ?? Infinity, ...values), Math.max(high ?? -Infinity, ...values)];
  });
  return alignedRanges(extents);
}

function makePlot(key, spec, xRange, onZoom) {
  const target = document.getElementById(`plot-${key}`);
  const width = target.clientWidth || 400;
  const axes = [{ label: 's', size: 36 }, { scale: 'rad', label: spec.axes[0], size: 48 }];
  if (spec.axes[1]) axes.push({ scale: 'Nm', label: spec.axes[1], side: 1, size: 52, grid: { show: false } });
  const options = {
    title: spec.title,
    width,
    height: HEIGHT,
    // x: seconds before the newest sample: the chosen window, or the zoomed part of it
    scales: { x: { time: false, range: () => xRange() },
              ...Object.fromEntries([...new Set(spec.series.map((series) => series.scale))].map(
                (scale) => [scale, { range: (plot) => yRanges(plot, spec)[scale] }])) },
    series: [{ label: 't (s)' },
             ...spec.series.map((s) => ({ label: s.label, stroke: s.stroke, dash: s.dash, scale: s.scale,
                                          width: 1.5, spanGaps: true, points: { show: false } }))],
    axes,
    cursor: { drag: { x: true, y: false, setScale: false } },
    legend: { live: true },  // the values under the cursor
    hooks: {
      setSelect: [(plot) => {
        if (plot.select.width < 3) return;
        const from = plot.posToVal(plot.select.left, 'x');
        const to = plot.posToVal(plot.select.left + plot.select.width, 'x');
        plot.setSelect({ left: 0, top: 0, width: 0, height: 0 }, false);
        onZoom([from, to]);
      }],
    },
  };
  const plot = new uPlot(options, [[], ...spec.series.map(() => [])], target);
  plot.over.addEventListener('dblclick', () => onZoom(null));
  // as wide as its place in the page, whatever the window's width
  new ResizeObserver(() => {
    if (target.clientWidth && target.clientWidth !== plot.width) plot.setSize({ width: target.clientWidth, height: HEIGHT });
  }).observe(target);
  return plot;
}

export function startPlots(socket, view, showError) {
  const kept = (spec) => spec.series.filter((s) => !s.computed).map((s) => s.name);
  const names = Object.values(PLOTS).flatMap(kept);
  let columns = emptyColumns(names);
  let drawn = columns;  // what the plots draw: the live columns, or those of the moment of Pause
  const pauseButton = document.getElementById('pause');
  const windowSelect = document.getElementById('plot-window');
  view.plots = { paused: false, batches: 0, window: WINDOW_SECONDS, zoom: null, steps: {} };
  const xRange = () => view.plots.zoom || [-view.plots.window, 0];
  const plots = Object.fromEntries(Object.entries(PLOTS).map(([key, spec]) => [key, makePlot(key, spec, xRange, zoom)]));

  function draw() {
    for (const [key, spec] of Object.entries(PLOTS)) {
      const data = plotData(drawn, kept(spec), view.plots.window);
      if (spec.series.some((s) => s.computed)) {
        data.push(recordedOverlay(data[0], data[1], data[2], view.plots.lastRecording?.[key]));
      }
      plots[key].setData(data);
    }
    for (const servo of ['pan', 'tilt']) showStep(servo);
  }

  // The last goal step of a servo in what its plot draws (its zoomed part too), measured.
  function showStep(servo) {
    const [x, goal, position] = plots[servo].data;
    const [from, to] = xRange();
    const shown = x.map((time, i) => i).filter((i) => x[i] >= from && x[i] <= to);
    const pick = (column) => shown.map((i) => column[i]);
    const step = stepMeasurements(pick(x), pick(goal), pick(position));
    view.plots.steps[servo] = step;
    const line = document.getElementById(`step-${servo}`);
    if (step === null) {
      line.textContent = `No goal step of ${MIN_STEP} rad or more in this window: press 0 or π/2 (torque on), `
        + 'or run pid_testing.';
      return;
    }
    const seconds = (value) => (value === null ? '–' : `${value.toFixed(2)} s`);
    line.textContent = `last step ${step.from.toFixed(2)} → ${step.to.toFixed(2)} rad at ${step.time.toFixed(1)} s: `
      + `rise (10-90 %) ${seconds(step.rise)}, overshoot ${step.overshoot.toFixed(1)} %, `
      + `settling (2 %) ${step.settling === null ? 'not yet' : seconds(step.settling)}, `
      + `error ${step.error.toFixed(3)} rad`;
  }

  // While paused the hint says so: the data keeps coming, the plots hold still until Resume.
  const hint = document.getElementById('plots-hint');
  const liveHint = hint.textContent;
  let pausedByZoom = false;  // a zoom paused the plots, so zooming out takes them live again
  function setPaused(paused, byZoom = false) {
    view.plots.paused = paused;
    pausedByZoom = paused && byZoom;
    pauseButton.textContent = paused ? 'Resume' : 'Pause';
    pauseButton.setAttribute('aria-pressed', String(paused));
    hint.textContent = paused ? 'Paused: the plots hold still while the data keeps coming; Resume goes live.'
      : liveHint;
    hint.classList.toggle('paused', paused);
    if (!paused) {
      view.plots.zoom = null;  // live again: the whole window
      drawn = columns;
    }
    draw();
  }

  function zoom(range) {
    if (range === null && view.plots.zoom === null) return;
    if (range !== null && !view.plots.paused) setPaused(true, true);  // a moving plot cannot be measured
    if (range === null && pausedByZoom) {
      setPaused(false);  // zoomed out: live again, as before the zoom
      return;
    }
    view.plots.zoom = range;
    draw();
  }

  socket.subscribe('plots', {}, (batch) => {
    columns = mergeBatch(columns, batch);
    view.plots.batches += 1;
    if (!view.plots.paused) {
      drawn = columns;
      draw();
    }
  }, showError);

  pauseButton.addEventListener('click', () => setPaused(!view.plots.paused));

  // Record: `ros2 bag record` of the servos and the IMU (the server runs it); at Stop the page keeps
  // what it plotted meanwhile as the last recording, drawn faintly under the live servo plots.
  const recordButton = document.getElementById('record');
  const recordingLine = document.getElementById('recording');
  view.plots.recording = null;  // {folder, since: columns' time} while recording
  view.plots.lastRecording = null;  // {pan: {x, goal, position}, tilt: ...}
  view.plots.recordAnswers = [];
  const newest = () => (columns.t.length ? columns.t[columns.t.length - 1] : 0);
  recordButton.addEventListener('click', () => {
    const on = view.plots.recording === null;
    recordButton.disabled = true;
    recordingLine.textContent = on ? 'starting ros2 bag record…' : 'finishing the bag…';
    const sent = socket.command('record', { on }, (error, result) => {
      view.plots.recordAnswers.push({ error, result });
      recordButton.disabled = false;
      if (error) {
        recordingLine.textContent = `refused: ${error}`;
        recordingLine.classList.add('refused');
        return;
      }
      recordingLine.classList.remove('refused');
      if (on) {
        view.plots.recording = { folder: result.folder, since: newest() };
        recordingLine.textContent = `recording the servos and the IMU into ${result.folder}`;
      } else {
        const { since } = view.plots.recording;
        view.plots.lastRecording = Object.fromEntries(['pan', 'tilt'].map(
          (servo) => [servo, recordingOf(columns, servo, since, newest())]));
        view.plots.recording = null;
        recordingLine.textContent = `recorded ${result.messages} messages in ${result.seconds.toFixed(1)} s to `
          + `${result.folder} (ros2 bag info, ros2 bag play); drawn faintly under the live plots`;
        draw();
      }
      recordButton.textContent = view.plots.recording ? 'Stop recording' : 'Record';
      recordButton.setAttribute('aria-pressed', String(view.plots.recording !== null));
    });
    if (!sent) {
      recordButton.disabled = false;
      recordingLine.textContent = 'not connected: nothing was recorded';
    }
  });

  for (const seconds of WINDOWS) windowSelect.add(new Option(`${seconds} s`, String(seconds), false,
                                                             seconds === WINDOW_SECONDS));
  windowSelect.addEventListener('change', () => {
    view.plots.window = Number(windowSelect.value);
    view.plots.zoom = null;
    draw();
  });

  document.getElementById('export-csv').addEventListener('click', () => {
    const url = URL.createObjectURL(new Blob([columnsCsv(drawn)], { type: 'text/csv' }));
    const link = document.createElement('a');
    link.href = url;
    link.download = `robot_view_plots_${new Date().toISOString().replace(/[:.]/g, '-')}.csv`;
    link.click();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  });

  // A plot's y scales as drawn ({rad: [min, max], Nm: [...]}), for a test.
  view.plots.scaleRanges = (key) => Object.fromEntries(['rad', 'Nm'].filter((name) => name in plots[key].scales)
    .map((name) => [name, [plots[key].scales[name].min, plots[key].scales[name].max]]));

  // What a plot draws now, for a test: {x: [...], <label>: [...]} (x in s before the newest sample).
  view.plotted = (key) => {
    const data = plots[key].data;
    return Object.fromEntries([['x', Array.from(data[0] || [])],
                               ...PLOTS[key].series.map((s, i) => [s.label, Array.from(data[i + 1] || [])])]);
  };
}
