// The run data the page draws, in one shape whatever its source: a run.json from `drvslam view`,
// the JSON inlined in a report, or the live messages of `drvslam run --viewer`.
//
// Poses are [timestamp, x, y, z, qx, qy, qz, qw] (camera-to-world, the map's frame); ground truth
// comes already aligned into the map's frame, as positions [timestamp, x, y, z].

// Decodes base64 into the bytes of a typed array of `Type` (little-endian, as the server wrote).
export function decodeBase64Array(text, Type) {
  if (!text) return new Type(0);
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return new Type(bytes.buffer, 0, bytes.byteLength / Type.BYTES_PER_ELEMENT);
}

// A cloud as the server sends it: {count, total, positions (base64 float32 xyz), colors (base64
// uint8 rgb, optional)}.
export function decodeCloud(cloud) {
  if (!cloud) return { count: 0, total: 0, positions: new Float32Array(0), colors: null };
  const positions = decodeBase64Array(cloud.positions, Float32Array);
  const colors = cloud.colors ? decodeBase64Array(cloud.colors, Uint8Array) : null;
  return {
    count: positions.length / 3,
    total: cloud.total ?? positions.length / 3,
    positions,
    colors,
  };
}

// The occupancy grid as the server sends it (viewer_json.h: GridJson), its cells decoded; null
// when the run has none.
export function decodeGrid(grid) {
  if (!grid) return null;
  return { ...grid, cells: decodeBase64Array(grid.cells, Uint8Array) };
}

// Normalizes a run.json (or an inlined report's data) into what the page draws.
export function normalizeRun(json) {
  return {
    mode: json.mode ?? 'view',
    title: json.title ?? 'drvslam run',
    trajectory: json.trajectory ?? [],
    keyframes: json.keyframes ?? [],
    groundTruth: json.ground_truth ?? null,
    errors: json.errors ?? null,
    ate: json.ate ?? null,
    stats: json.stats ?? null,
    sparse: decodeCloud(json.sparse),
    dense: decodeCloud(json.dense),
    grid: decodeGrid(json.grid),
    loops: json.loops ?? [],
    events: json.events ?? null,
    notes: json.notes ?? [],
  };
}

// The pose of `trajectory` nearest in time to `timestamp` (null for an empty trajectory).
export function poseNearest(trajectory, timestamp) {
  let best = null;
  let bestGap = Infinity;
  for (const pose of trajectory) {
    const gap = Math.abs(pose[0] - timestamp);
    if (gap < bestGap) {
      bestGap = gap;
      best = pose;
    }
  }
  return best;
}
