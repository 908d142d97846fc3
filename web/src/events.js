// The events drawn beside the error over time, from the frame log (frames.tsv, read by the
// server into columns) and the loop-closing stats: what the frames went through where the error
// grows. Times are seconds since t0, the first error sample's timestamp.

// Each lane is drawn as ticks along the time axis; `label` names it in the legend.
export const kTickLanes = [
  { id: 'keyframes', label: 'keyframe', color: '#2aa84a' },
  { id: 'lost', label: 'lost', color: '#c0392b' },
  { id: 'relocalized', label: 'relocalized', color: '#e67e22' },
  { id: 'skipped', label: 'skipped', color: '#7f8c8d' },
  { id: 'loopsRejected', label: 'loop rejected', color: '#8e44ad' },
  { id: 'loopsClosed', label: 'loop closed', color: '#1f6fd1' },
];

function column(events, name) {
  return events && Array.isArray(events[name]) ? events[name] : null;
}

// Frames the log lacks between two logged ones were skipped (realtime); their times are spread
// evenly between their neighbours'.
function skippedTimes(frames, times, t0) {
  const out = [];
  for (let i = 1; i < frames.length; ++i) {
    const gap = frames[i] - frames[i - 1];
    for (let k = 1; k < gap; ++k) {
      out.push(times[i - 1] + ((times[i] - times[i - 1]) * k) / gap - t0);
    }
  }
  return out;
}

// events: {frame, timestamp, tracked, keyframe?, movers_share?, features?, removed?} (arrays of
// equal length); loops and rejections: stats.json's loop.loops and loop.rejections. Returns the
// tick lanes (times) and the shares drawn as curves ([time, share in 0..1]).
export function errorPlotEvents(events, loops, rejections, t0) {
  const out = { moversShare: [], removedShare: [] };
  for (const lane of kTickLanes) out[lane.id] = [];
  const times = column(events, 'timestamp');
  if (times) {
    const tracked = column(events, 'tracked');
    const keyframe = column(events, 'keyframe');
    const movers = column(events, 'movers_share');
    const features = column(events, 'features');
    const removed = column(events, 'removed');
    const frames = column(events, 'frame');
    for (let i = 0; i < times.length; ++i) {
      const t = times[i] - t0;
      if (tracked && !tracked[i]) out.lost.push(t);
      if (tracked && tracked[i] && i > 0 && !tracked[i - 1]) out.relocalized.push(t);
      if (keyframe && keyframe[i]) out.keyframes.push(t);
      if (movers) out.moversShare.push([t, movers[i]]);
      if (features && removed && features[i] > 0) out.removedShare.push([t, removed[i] / features[i]]);
    }
    if (frames) out.skipped = skippedTimes(frames, times, t0);
  }
  for (const loop of loops ?? []) out.loopsClosed.push(loop.timestamp - t0);
  for (const rejection of rejections ?? []) out.loopsRejected.push(rejection.timestamp - t0);
  return out;
}

// The legend's entries: every lane with at least one tick, with its count, then the curves.
export function eventLegend(marks) {
  const entries = [];
  if (marks.moversShare.length > 0) entries.push({ label: "movers' share", color: '#9cc3e6' });
  if (marks.removedShare.length > 0) entries.push({ label: 'features removed', color: '#555' });
  for (const lane of kTickLanes) {
    const n = marks[lane.id].length;
    if (n > 0) entries.push({ label: `${lane.label} (${n})`, color: lane.color });
  }
  return entries;
}
