// The text panels: run figures, the per-stage times (per frame and per keyframe), loop closures
// and notes.

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
  const reloc = s.relocalization;
  if (reloc?.attempts > 0) {
    // Why poses found again were not trusted (docs/maps-and-localization.md).
    const r = reloc.rejected ?? {};
    figures.push(['relocalizations', `${reloc.relocalizations} of ${reloc.attempts} attempts, ` +
                  `${reloc.verified ?? 0} verified`]);
    figures.push(['relocalizations refused', `${r.ambiguous ?? 0} ambiguous, ` +
                  `${r.depth_disagrees ?? 0} depth disagrees, ${r.not_confirmed ?? 0} not confirmed`]);
  }
  if (run.ate) figures.push(['ATE RMSE', `${(100 * run.ate.rmse).toFixed(2)} cm over ${run.ate.matched} poses`]);
  return figures;
}

const kStageColors = ['#1f6fd1', '#e67e22', '#27ae60', '#8e44ad', '#c0392b', '#16a085', '#7f8c8d',
                      '#d35400', '#2c3e50', '#f1c40f'];

const kGroupNotes = {
  frame: 'tracking thread (italic: alongside it, on a thread of its own)',
  keyframe: 'local mapping, dense mapping and loop closing threads (inline when --sequential)',
};

function stageRow(row, largest, color, perKeyframe) {
  const width = Math.max(1, Math.round((100 * row.ms) / largest));
  const beside = !perKeyframe && row.thread !== 'tracking thread';
  const times = row.count != null ? `, ${row.count} times` : '';
  const classes = `name${row.depth ? ' step' : ''}${beside ? ' beside' : ''}`;
  const title = escapeHtml(`${row.thread}${times}`);
  return `<span class="${classes}" title="${title}">${escapeHtml(row.name)}</span>` +
         `<span class="track"><span class="bar" style="width:${width}%;background:${color}"></span></span>` +
         `<span class="ms">${row.ms.toFixed(2)} ms</span>` +
         `<span class="count">${row.count != null && perKeyframe ? `&times;${row.count}` : ''}</span>`;
}

// groups: what groupStages (stages.js) returns. Each group is a captioned block of horizontal bars
// on its own scale (its largest stage fills the width), names in full.
export function showStages(element, groups, caption) {
  const blocks = groups.map((group) => {
    const perKeyframe = group.id === 'keyframe';
    const rows = group.rows.map((row, i) =>
      stageRow(row, Math.max(group.largest, 1e-6), kStageColors[i % kStageColors.length], perKeyframe));
    const note = `${kGroupNotes[group.id] ?? ''}; bars to this group's own scale`;
    return `<div class="stage-group" data-group="${group.id}">` +
           `<div class="group-title">${escapeHtml(group.title)}</div>` +
           `<div class="group-note">${escapeHtml(note)}</div>` +
           `<div class="stages">${rows.join('')}</div></div>`;
  });
  element.innerHTML = `<div class="caption">${escapeHtml(caption)}</div>${blocks.join('')}`;
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
