// drvslam's viewer page. One page for three sources:
//   report:  the run's data inlined as window.DRVSLAM_DATA (drvslam report, openable offline);
//   view:    data/run.json from `drvslam view RUN_DIR`;
//   live:    data/run.json says mode "live"; updates then come over the WebSocket at /ws from
//            `drvslam run --viewer`.
// What it drew is counted in window.drvslamViewer, which the tests read back.
import { decodeCloud, normalizeRun, poseNearest } from './data.js';
import { showFigures, runFigures, showStages, showLoops, showNotes } from './panels.js';
import { errorPlotEvents } from './events.js';
import { plotErrors, plotTrajectory } from './plots.js';
import { groupStages } from './stages.js';
import { createMapView } from './view3d.js';

const viewer = {
  ready: false,
  mode: '',
  poses: 0,
  keyframes: 0,
  groundTruthPoses: 0,
  mapPoints: 0,
  densePoints: 0,
  denseTotal: 0,
  loops: 0,
  errorSamples: 0,
  eventFrames: 0,       // frames of the frame log drawn beside the error (0 without one)
  keyframeTicks: 0,
  updates: 0,
  frameUpdates: 0,
  images: 0,
  lastFrameId: -1,
  trackingState: '',
  localizationQuality: '',  // verified, tentative or lost (live runs)
  finished: false,
  failure: null,
  webgl: null,          // whether the 3-D view has WebGL (null until the page starts)
  webglProblem: null,   // why not, when it has not
};
window.drvslamViewer = viewer;

const $ = (id) => document.getElementById(id);

function loopPositions(loops, trajectory) {
  const positions = [];
  for (const loop of loops) {
    const pose = poseNearest(trajectory, loop.timestamp);
    if (pose) positions.push([pose[1], pose[2], pose[3]]);
  }
  return positions;
}

function denseNote(shown, total) {
  return shown < total ? `dense map: showing ${shown} of ${total} points (decimated for the browser)`
                       : `dense map: ${total} points`;
}

// marks: the events beside the error (errorPlotEvents), or null for none.
function drawPlots(trajectory, groundTruth, errors, ate, marks = null) {
  $('plots').hidden = false;
  plotTrajectory($('plot-trajectory'), trajectory, groundTruth);
  plotErrors($('plot-errors'), errors, ate ? ate.rmse : null, marks);
}

// The finished run's events on the error plot's time axis (null without ground truth).
function runEventMarks(run) {
  if (!run.errors || run.errors.length === 0) return null;
  const loop = run.stats?.loop;
  return errorPlotEvents(run.events, loop?.loops, loop?.rejections, run.errors[0][0]);
}

// A finished run (view or report): everything at once. The text panels and the 2-D plots come
// first, so that they are there whatever happens to the 3-D view.
function drawRun(scene, run) {
  document.title = run.title;
  $('title').textContent = run.title;
  showFigures($('figures'), runFigures(run));
  showStages($('stages'), groupStages(run.stats?.stages, 'median'), 'time per stage');
  showLoops($('loops'), run.loops);
  const notes = [...run.notes];
  if (run.dense.total > 0) notes.push(denseNote(run.dense.count, run.dense.total));
  if (run.grid) {
    notes.push(`occupancy grid (map.yaml): ${run.grid.width} x ${run.grid.height} cells of ` +
               `${run.grid.resolution} m, drawn on the floor under the trajectory`);
  }
  showNotes($('notes'), notes);
  const marks = runEventMarks(run);
  drawPlots(run.trajectory, run.groundTruth, run.errors, run.ate, marks);

  scene.fit(run.trajectory, run.sparse.positions);
  scene.setSparse(run.sparse.positions);
  if (run.dense.count > 0) scene.addDenseChunk(run.dense.positions, run.dense.colors);
  scene.setGrid(run.grid);
  scene.setTrajectory(run.trajectory);
  scene.setKeyframes(run.keyframes);
  if (run.groundTruth) scene.setGroundTruth(run.groundTruth);
  scene.setLoops(loopPositions(run.loops, run.trajectory));

  Object.assign(viewer, {
    poses: run.trajectory.length,
    keyframes: run.keyframes.length,
    groundTruthPoses: run.groundTruth ? run.groundTruth.length : 0,
    mapPoints: run.sparse.count,
    densePoints: run.dense.count,
    denseTotal: run.dense.total,
    gridCells: run.grid ? run.grid.width * run.grid.height : 0,
    gridOccupied: run.grid ? run.grid.cells.filter((cell) => cell === 2).length : 0,
    loops: run.loops.length,
    errorSamples: run.errors ? run.errors.length : 0,
    eventFrames: run.events?.frame ? run.events.frame.length : 0,
    keyframeTicks: marks ? marks.keyframes.length : 0,
    finished: true,
  });
}

// A run in progress: state that the messages of /ws keep up to date.
class LiveRun {
  constructor(scene) {
    this.scene = scene;
    this.trajectory = [];
    this.groundTruth = null;
    this.errors = null;
    this.ate = null;
    this.loops = [];
    this.denseShown = 0;
    this.denseTotal = 0;
    this.figures = {};
    this.plotPending = false;
  }

  connect() {
    const protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
    const socket = new WebSocket(`${protocol}//${location.host}/ws`);
    socket.onmessage = (event) => this.handle(JSON.parse(event.data));
    socket.onclose = () => {
      $('state').textContent = viewer.finished ? 'run finished' : 'disconnected';
    };
    return socket;
  }

  handle(message) {
    viewer.updates += 1;
    switch (message.type) {
      case 'hello':
        $('title').textContent = message.title;
        document.title = message.title;
        break;
      case 'frame': this.onFrame(message); break;
      case 'image': this.onImage(message); break;
      case 'map': this.onMap(message); break;
      case 'dense': this.onDense(message); break;
      case 'truth': this.onTruth(message); break;
      case 'loops': this.onLoops(message); break;
      case 'end':
        viewer.finished = true;
        $('state').textContent = 'run finished';
        break;
      default: break;
    }
  }

  onFrame(m) {
    viewer.frameUpdates += 1;
    this.trajectory.push(...m.poses);
    viewer.poses = this.trajectory.length;
    viewer.lastFrameId = m.frame_id;
    viewer.trackingState = m.state;
    viewer.localizationQuality = m.quality ?? '';
    this.scene.fit(this.trajectory, null);
    this.scene.setTrajectory(this.trajectory);
    // The quality a robot would act on: a tentative pose was just found again, not confirmed.
    $('state').textContent = m.quality ? `tracking: ${m.state} (${m.quality})` : `tracking: ${m.state}`;
    this.figures = {
      ...this.figures,
      'frame': m.frame_id,
      'tracked': `${m.tracked} / ${m.frames}`,
      'fps': m.fps.toFixed(1),
      'frame time': `${m.frame_ms.toFixed(1)} ms`,
      'features kept / removed': `${m.kept} / ${m.removed}`,
      'inliers': m.inliers,
    };
    showFigures($('figures'), Object.entries(this.figures));
    showStages($('stages'), groupStages(m.stages, 'latest'), 'time per stage');
    this.schedulePlots();
  }

  onImage(m) {
    viewer.images += 1;
    const image = $('frame-image');
    image.hidden = false;
    image.src = `data:image/jpeg;base64,${m.jpeg}`;
  }

  onMap(m) {
    const sparse = decodeCloud(m.sparse);
    this.scene.setSparse(sparse.positions);
    this.scene.setKeyframes(m.keyframes);
    viewer.mapPoints = sparse.count;
    viewer.keyframes = m.keyframes.length;
    this.figures = { ...this.figures, 'keyframes': m.keyframes.length, 'map points': sparse.count };
    showFigures($('figures'), Object.entries(this.figures));
  }

  onDense(m) {
    if (m.reset) {
      this.scene.clearDense();
      this.denseShown = 0;
    }
    const chunk = decodeCloud(m.chunk);
    if (chunk.count > 0) this.scene.addDenseChunk(chunk.positions, chunk.colors);
    this.denseShown += chunk.count;
    this.denseTotal = m.total;
    viewer.densePoints = this.denseShown;
    viewer.denseTotal = m.total;
    showNotes($('notes'), [denseNote(this.denseShown, Math.max(m.total, this.denseShown))]);
  }

  onTruth(m) {
    this.groundTruth = m.ground_truth;
    this.errors = m.errors;
    this.ate = m.ate;
    viewer.groundTruthPoses = m.ground_truth.length;
    viewer.errorSamples = m.errors.length;
    this.scene.setGroundTruth(m.ground_truth);
    this.schedulePlots();
  }

  onLoops(m) {
    this.loops = m.loops;
    viewer.loops = m.loops.length;
    showLoops($('loops'), m.loops);
    this.scene.setLoops(loopPositions(m.loops, this.trajectory));
  }

  // The 2-D plots at most twice a second.
  schedulePlots() {
    if (this.plotPending) return;
    this.plotPending = true;
    setTimeout(() => {
      this.plotPending = false;
      drawPlots(this.trajectory, this.groundTruth, this.errors, this.ate);
    }, 500);
  }
}

async function loadRun() {
  if (window.DRVSLAM_DATA) return window.DRVSLAM_DATA;
  const response = await fetch('data/run.json');
  if (!response.ok) throw new Error(`data/run.json: HTTP ${response.status}`);
  return response.json();
}

async function start() {
  const view = createMapView($('view3d'));
  viewer.webgl = view.webgl;
  viewer.webglProblem = view.problem;
  const scene = view.scene;
  const json = await loadRun();
  viewer.mode = json.mode ?? 'view';
  if (viewer.mode === 'live') {
    $('title').textContent = json.title ?? 'drvslam run (live)';
    $('state').textContent = 'connecting';
    new LiveRun(scene).connect();
  } else {
    drawRun(scene, normalizeRun(json));
    $('state').textContent = viewer.mode === 'report' ? 'report of a finished run' : 'finished run';
  }
  viewer.ready = true;
}

start().catch((error) => {
  viewer.failure = String(error);
  $('state').textContent = `error: ${error.message}`;
  console.error(error);
});
