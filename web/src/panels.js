// The text panels: run figures, the strip of per-stage times, loop closures and notes.

function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);
}

function row(label, value) {
  return `<tr><th>${escapeHtml(label)}</th><td>${escapeHtml(value)}</td></tr>`;
}

// figures: [[label, value], ...]
export function showFigures(element, figures) {
  element.innerHTML = `<table>${figures.map(([l, v]) => row(l, v)).join('')}</table>`;
}

// The figures of a finished run's stats.json (and its ATE, when there is ground truth).
export function runFigures(run) {
  const s = run.stats ?? {};
  const figures = [];
  if (s.frames != null) figures.push(['frames tracked', `${s.tracked} / ${s.frames}`]);
  if (s.keyframes != null) figures.push(['keyframes', s.keyframes]);
  if (s.map_points != null) figures.push(['map points', s.map_points]);
  if (s.fps != null) figures.push(['fps (wall clock)', s.fps.toFixed(1)]);
  if (s.tracking_fps != null) figures.push(['fps (tracking calls)', s.tracking_fps.toFixed(1)]);
  if (s.segmenter?.label) {
    const oracle = s.segmenter.oracle && !s.segmenter.label.includes('ORACLE');
    figures.push(['segmenter', oracle ? `${s.segmenter.label} (ORACLE masks)` : s.segmenter.label]);
  }
  const features = s.dynamic?.features;
  if (features) figures.push(['features removed', `${features.removed} of ${features.extracted}`]);
  if (s.frames_lost != null) figures.push(['frames lost', s.frames_lost]);
  if (run.ate) figures.push(['ATE RMSE', `${(100 * run.ate.rmse).toFixed(2)} cm over ${run.ate.matched} poses`]);
  return figures;
}

const kStageColors = ['#1f6fd1', '#e67e22', '#27ae60', '#8e44ad', '#c0392b', '#16a085', '#7f8c8d',
                      '#d35400', '#2c3e50', '#f1c40f'];

// stages: {name: ms}. A horizontal bar per stage, scaled to the largest; "total" is drawn first.
export function showStages(element, stages, caption) {
  const entries = Object.entries(stages ?? {}).filter(([, ms]) => Number.isFinite(ms));
  entries.sort((a, b) => (a[0] === 'total' ? -1 : b[0] === 'total' ? 1 : b[1] - a[1]));
  const largest = Math.max(1e-6, ...entries.map(([, ms]) => ms));
  const bars = entries.map(([name, ms], i) => {
    const width = Math.max(1, Math.round((100 * ms) / largest));
    const color = kStageColors[i % kStageColors.length];
    return `<div class="stage"><span class="name">${escapeHtml(name)}</span>` +
           `<span class="bar" style="width:${width}%;background:${color}"></span>` +
           `<span class="ms">${ms.toFixed(2)} ms</span></div>`;
  });
  element.innerHTML = `<div class="caption">${escapeHtml(caption)}</div>${bars.join('')}`;
}

// loops: [{keyframe, loop_keyframe, timestamp, correction_m, ...}]
export function showLoops(element, loops) {
  if (!loops.length) {
    element.innerHTML = '<div class="caption">loop closures: none</div>';
    return;
  }
  const items = loops.map((l) => `<li>t=${Number(l.timestamp).toFixed(2)} s: keyframe ${l.keyframe} ` +
                                 `to ${l.loop_keyframe}, moved ${(100 * (l.correction_m ?? 0)).toFixed(1)} cm</li>`);
  element.innerHTML = `<div class="caption">loop closures: ${loops.length}</div><ul>${items.join('')}</ul>`;
}

export function showNotes(element, notes) {
  element.innerHTML = notes.map((n) => `<div class="note">${escapeHtml(n)}</div>`).join('');
}
