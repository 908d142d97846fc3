// 2-D plots on a canvas, no library: the trajectory seen from above with ground truth, and the
// position error over time with the frames' events beside it (src/events.js).
import { eventLegend, kTickLanes } from './events.js';

const kMargin = { left: 48, right: 12, top: 22, bottom: 30 };

function prepare(canvas, title) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth || 360;
  const height = canvas.clientHeight || 240;
  canvas.width = width * ratio;
  canvas.height = height * ratio;
  const g = canvas.getContext('2d');
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, width, height);
  g.fillStyle = '#222';
  g.font = '12px sans-serif';
  g.fillText(title, kMargin.left, 14);
  return { g, width, height };
}

// A linear map from [lo, hi] onto [a, b].
function scale(lo, hi, a, b) {
  const span = hi - lo || 1;
  return (v) => a + ((v - lo) / span) * (b - a);
}

function axes(g, width, height, xLabel, yLabel, xRange, yRange) {
  g.strokeStyle = '#999';
  g.lineWidth = 1;
  g.strokeRect(kMargin.left, kMargin.top, width - kMargin.left - kMargin.right,
               height - kMargin.top - kMargin.bottom);
  g.fillStyle = '#444';
  g.font = '11px sans-serif';
  g.fillText(xLabel, width / 2 - 20, height - 6);
  g.fillText(xRange[0].toFixed(2), kMargin.left, height - kMargin.bottom + 12);
  const right = xRange[1].toFixed(2);
  g.fillText(right, width - kMargin.right - g.measureText(right).width, height - kMargin.bottom + 12);
  g.save();
  g.translate(12, height / 2 + 20);
  g.rotate(-Math.PI / 2);
  g.fillText(yLabel, 0, 0);
  g.restore();
  g.fillText(yRange[1].toFixed(2), 2, kMargin.top + 8);
  g.fillText(yRange[0].toFixed(2), 2, height - kMargin.bottom);
}

function polyline(g, points, color, dashed) {
  if (points.length < 2) return;
  g.strokeStyle = color;
  g.lineWidth = 1.5;
  g.setLineDash(dashed ? [5, 3] : []);
  g.beginPath();
  g.moveTo(points[0][0], points[0][1]);
  for (const [x, y] of points.slice(1)) g.lineTo(x, y);
  g.stroke();
  g.setLineDash([]);
}

function range(values) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of values) {
    lo = Math.min(lo, v);
    hi = Math.max(hi, v);
  }
  return lo <= hi ? [lo, hi] : [0, 1];
}

// Top view: x against z (the camera frame's ground plane when the first camera looks ahead).
export function plotTrajectory(canvas, trajectory, groundTruth) {
  const { g, width, height } = prepare(canvas, 'trajectory, top view (x-z, m): estimate blue, ground truth green dashed');
  const all = trajectory.concat(groundTruth ?? []);
  if (all.length === 0) return;
  let xRange = range(all.map((p) => p[1]));
  let zRange = range(all.map((p) => p[3]));
  // Same scale on both axes, so the path's shape is true.
  const plotW = width - kMargin.left - kMargin.right;
  const plotH = height - kMargin.top - kMargin.bottom;
  const perPixel = Math.max((xRange[1] - xRange[0]) / plotW, (zRange[1] - zRange[0]) / plotH, 1e-6);
  const padX = (perPixel * plotW - (xRange[1] - xRange[0])) / 2;
  const padZ = (perPixel * plotH - (zRange[1] - zRange[0])) / 2;
  xRange = [xRange[0] - padX, xRange[1] + padX];
  zRange = [zRange[0] - padZ, zRange[1] + padZ];
  const sx = scale(xRange[0], xRange[1], kMargin.left, width - kMargin.right);
  const sz = scale(zRange[0], zRange[1], height - kMargin.bottom, kMargin.top);
  axes(g, width, height, 'x (m)', 'z (m)', xRange, zRange);
  if (groundTruth) polyline(g, groundTruth.map((p) => [sx(p[1]), sz(p[3])]), '#2aa84a', true);
  polyline(g, trajectory.map((p) => [sx(p[1]), sz(p[3])]), '#1f6fd1', false);
}

// Shares (0..1, on the plot's full height) behind the error: the image share people cover as a
// filled area, the share of features removed as a thin line.
function drawShares(g, marks, st, width, height) {
  const bottom = height - kMargin.bottom;
  const ss = scale(0, 1, bottom, kMargin.top);
  if (marks.moversShare.length > 1) {
    g.fillStyle = 'rgba(156, 195, 230, 0.55)';
    g.beginPath();
    g.moveTo(st(marks.moversShare[0][0]), bottom);
    for (const [t, share] of marks.moversShare) g.lineTo(st(t), ss(share));
    g.lineTo(st(marks.moversShare[marks.moversShare.length - 1][0]), bottom);
    g.closePath();
    g.fill();
  }
  g.save();
  g.lineWidth = 0.8;
  polyline(g, marks.removedShare.map(([t, share]) => [st(t), ss(share)]), '#555', false);
  g.restore();
  if (marks.moversShare.length > 0 || marks.removedShare.length > 0) {
    g.fillStyle = '#444';
    g.font = '11px sans-serif';
    const label = 'share 0-1';
    g.fillText(label, width - kMargin.right - g.measureText(label).width, kMargin.top - 4);
  }
}

// One lane of ticks per kind of event, stacked up from the time axis.
function drawTicks(g, marks, st, height) {
  const bottom = height - kMargin.bottom;
  let lane = 0;
  for (const { id, color } of kTickLanes) {
    if (marks[id].length === 0) continue;
    const y = bottom - 2 - 6 * lane;
    g.strokeStyle = color;
    g.lineWidth = 1;
    g.beginPath();
    for (const t of marks[id]) {
      g.moveTo(st(t), y);
      g.lineTo(st(t), y - 5);
    }
    g.stroke();
    ++lane;
  }
}

function drawLegend(g, marks, width) {
  let x = kMargin.left + 4;
  let y = kMargin.top + 11;
  g.font = '10px sans-serif';
  for (const { label, color } of eventLegend(marks)) {
    const w = g.measureText(label).width + 16;
    if (x + w > width - kMargin.right) {
      x = kMargin.left + 4;
      y += 12;
    }
    g.fillStyle = color;
    g.fillRect(x, y - 7, 8, 8);
    g.fillStyle = '#333';
    g.fillText(label, x + 10, y);
    x += w + 6;
  }
}

// errors: [[timestamp, metres], ...] over the associated poses; marks (optional): what
// errorPlotEvents made of the run's frame log, in seconds since the first error sample.
export function plotErrors(canvas, errors, rmse, marks) {
  const title = rmse == null ? 'position error over time (cm)'
                             : `position error over time (cm); ATE RMSE ${(100 * rmse).toFixed(2)} cm`;
  const { g, width, height } = prepare(canvas, title);
  if (!errors || errors.length === 0) {
    g.fillText('no ground truth for this run', kMargin.left, height / 2);
    return;
  }
  const t0 = errors[0][0];
  const tRange = [0, Math.max(errors[errors.length - 1][0] - t0, 1e-3)];
  const eRange = [0, Math.max(...errors.map((e) => 100 * e[1]), 1e-3)];
  const st = scale(tRange[0], tRange[1], kMargin.left, width - kMargin.right);
  const se = scale(eRange[0], eRange[1], height - kMargin.bottom, kMargin.top);
  axes(g, width, height, 'time (s)', 'error (cm)', tRange, eRange);
  if (marks) {
    drawShares(g, marks, st, width, height);
    drawTicks(g, marks, st, height);
  }
  polyline(g, errors.map((e) => [st(e[0] - t0), se(100 * e[1])]), '#c0392b', false);
  if (marks) drawLegend(g, marks, width);
}
