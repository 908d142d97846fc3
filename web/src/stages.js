// Which stage of stats.json (or of a live frame's stage times) is timed how often and where.
// No DOM here, so node's test runner checks it as it is (web/test/stages_test.mjs).
//
// The stages come from StageTimings::Record calls in src/drvslam:
//   per frame, on the tracking thread (System::TrackRGBD): "total" and its parts "extraction",
//     "tracking", "dense_handoff", and the dynamic front end's "segmentation_wait", "removal",
//     "motion_consistency" and "late_keyframe_masks" (--realtime, only on frames while a keyframe
//     awaits its masks); "observer" (handing the frame to a live viewer) right after it;
//   per frame, beside the tracking thread: "flow" (a helper thread, overlapping extraction) and
//     "segmentation" (the network's time on the segmentation thread);
//   per keyframe, on the other threads (inline in the tracking thread with --sequential):
//     local mapping "local_mapping" and its steps "local_triangulation", "local_fusion",
//     "local_ba", "local_keyframe_culling"; dense mapping "dense_keyframe"; loop closing
//     "loop_detection", "loop_correction", "global_ba".

// Per-frame stages that run on a thread of their own (so are not part of "total").
const kBesideTracking = {
  flow: 'optical-flow helper thread',
  segmentation: 'segmentation thread',
};

// Per-keyframe stages: the thread each runs on and the stage it is a step of (if any).
const kPerKeyframe = {
  local_mapping: { thread: 'local mapping thread' },
  local_triangulation: { thread: 'local mapping thread', parent: 'local_mapping' },
  local_fusion: { thread: 'local mapping thread', parent: 'local_mapping' },
  local_ba: { thread: 'local mapping thread', parent: 'local_mapping' },
  local_keyframe_culling: { thread: 'local mapping thread', parent: 'local_mapping' },
  dense_keyframe: { thread: 'dense mapping thread' },
  loop_detection: { thread: 'loop closing thread' },
  loop_correction: { thread: 'loop closing thread' },
  global_ba: { thread: 'loop closing thread' },
};

// A stage this page does not know yet: per keyframe when named like the known ones.
function keyframeInfo(name) {
  if (kPerKeyframe[name]) return kPerKeyframe[name];
  if (/^local_/.test(name)) return { thread: 'local mapping thread', parent: 'local_mapping' };
  if (/^(loop_|global_)/.test(name)) return { thread: 'loop closing thread' };
  if (/^dense_keyframe/.test(name)) return { thread: 'dense mapping thread' };
  return null;
}

// Where a stage is timed: {perKeyframe, thread, parent}.
export function stageKind(name) {
  const keyframe = keyframeInfo(name);
  if (keyframe) return { perKeyframe: true, thread: keyframe.thread, parent: keyframe.parent ?? null };
  if (kBesideTracking[name]) return { perKeyframe: false, thread: kBesideTracking[name], parent: null };
  // "observer" is timed on the tracking thread right after "total", so is not a part of it.
  const partOfTotal = name !== 'total' && name !== 'observer';
  return { perKeyframe: false, thread: 'tracking thread', parent: partOfTotal ? 'total' : null };
}

// Rows in drawing order: each parent, then its steps (largest first); parents largest first,
// except that "total" leads.
function orderRows(rows) {
  const byName = new Map(rows.map((r) => [r.name, r]));
  const bySize = (a, b) => b.ms - a.ms || a.name.localeCompare(b.name);
  const tops = rows.filter((r) => !r.parent || !byName.has(r.parent));
  tops.sort((a, b) => (a.name === 'total' ? -1 : b.name === 'total' ? 1 : bySize(a, b)));
  const ordered = [];
  for (const top of tops) {
    ordered.push({ ...top, depth: 0 });
    const steps = rows.filter((r) => r !== top && r.parent === top.name).sort(bySize);
    for (const step of steps) ordered.push({ ...step, depth: 1 });
  }
  return ordered;
}

// stages: {name: ms} or {name: {median_ms, count, ...}} (stats.json). Returns the groups to draw,
// each on its own scale, empty ones left out:
//   [{id: 'frame' | 'keyframe', title, rows: [{name, ms, count, thread, depth}], largest}]
// `when` names what the times are: 'median' (a finished run) or 'latest' (a live run).
export function groupStages(stages, when = 'median') {
  const frame = [];
  const keyframe = [];
  for (const [name, value] of Object.entries(stages ?? {})) {
    const ms = typeof value === 'number' ? value : value?.median_ms;
    if (!Number.isFinite(ms)) continue;
    const count = typeof value === 'object' && Number.isFinite(value.count) ? value.count : null;
    const kind = stageKind(name);
    const row = { name, ms, count, thread: kind.thread, parent: kind.parent };
    (kind.perKeyframe ? keyframe : frame).push(row);
  }
  const titles = when === 'latest'
    ? { frame: 'per frame: this frame', keyframe: 'per keyframe: the latest one' }
    : { frame: 'per frame (median)', keyframe: 'per keyframe (median)' };
  const groups = [];
  for (const [id, rows] of [['frame', frame], ['keyframe', keyframe]]) {
    if (rows.length === 0) continue;
    const ordered = orderRows(rows).map(({ parent, ...row }) => row);
    groups.push({ id, title: titles[id], rows: ordered, largest: Math.max(...rows.map((r) => r.ms)) });
  }
  return groups;
}
