// The 3-D panel, with or without WebGL. Without it (no GPU and no software renderer, WebGL turned
// off, a remote desktop...) the panel says why, and the page goes on with a scene that draws
// nothing, so the figures, stage times, plots and loop closures still appear.
import { MapScene } from './scene.js';

// Why WebGL 2 (what three.js needs) cannot be had here, or null when it can. Tried on a canvas
// of its own, released at once, so the page's canvas keeps the attributes three.js asks for.
export function webglProblem(doc = document) {
  const canvas = doc.createElement('canvas');
  let reason = '';
  canvas.addEventListener('webglcontextcreationerror', (event) => {
    reason = event.statusMessage || reason;
  });
  let gl = null;
  try {
    gl = canvas.getContext('webgl2');
  } catch (error) {
    reason = String(error?.message ?? error);
  }
  if (gl) {
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return null;
  }
  if (!reason) {
    const has1 = !!canvas.getContext?.('webgl');
    reason = has1 ? 'only WebGL 1 is available; the 3-D view needs WebGL 2'
                  : 'the browser gave no WebGL context';
  }
  return reason;
}

// Stands in for MapScene when there is no WebGL: takes the same calls, draws nothing.
export class NoScene {
  fit() {}
  setSparse() {}
  addDenseChunk() {}
  clearDense() {}
  setTrajectory() {}
  setGroundTruth() {}
  setKeyframes() {}
  setCurrent() {}
  setLoops() {}
  setGrid() {}
}

// Replaces the 3-D canvas with a note of why there is no 3-D view (`reason` from the browser).
export function showNoWebgl(canvas, reason) {
  const note = canvas.ownerDocument.createElement('div');
  note.id = 'view3d-message';
  note.setAttribute('role', 'status');
  const head = note.ownerDocument.createElement('b');
  head.textContent = '3-D view unavailable: this browser could not start WebGL.';
  const body = note.ownerDocument.createElement('div');
  body.textContent = 'The map, trajectory and keyframes are not drawn in 3-D. The figures, stage ' +
                     'times, loop closures and the 2-D plots below work without it. To see the ' +
                     '3-D view, open the page in a browser with WebGL 2 (hardware acceleration ' +
                     'turned on, or a software renderer).';
  const why = note.ownerDocument.createElement('div');
  why.className = 'reason';
  why.textContent = `reason: ${reason}`;
  note.append(head, body, why);
  canvas.replaceWith(note);
  return note;
}

// The scene for `canvas`: {scene, webgl, problem}. `makeScene` is for tests.
export function createMapView(canvas, makeScene = (c) => new MapScene(c)) {
  let problem = webglProblem(canvas.ownerDocument);
  if (!problem) {
    try {
      return { scene: makeScene(canvas), webgl: true, problem: null };
    } catch (error) {
      problem = String(error?.message ?? error);
    }
  }
  showNoWebgl(canvas, problem);
  return { scene: new NoScene(), webgl: false, problem };
}
