// Unit tests of the page's parts that need no browser (node's test runner):
//   cd web && npm test      (node --test test/stages_test.mjs)
// The stage chart's split into per-frame and per-keyframe groups (src/stages.js, drawn by
// src/panels.js), and the 3-D panel's fallback when the browser gives no WebGL (src/view3d.js).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { showStages } from '../src/panels.js';
import { groupStages, stageKind } from '../src/stages.js';
import { createMapView, NoScene, webglProblem } from '../src/view3d.js';

// The stages of a stats.json as the issue saw them: ~13 ms of tracking per frame beside
// 78 ms of local mapping and 74 ms of dense mapping per keyframe.
const kStats = {
  total: { median_ms: 13.1, count: 300 },
  extraction: { median_ms: 6.2, count: 300 },
  tracking: { median_ms: 5.0, count: 300 },
  dense_handoff: { median_ms: 0.6, count: 300 },
  segmentation_wait: { median_ms: 0.01, count: 300 },
  removal: { median_ms: 0.4, count: 300 },
  motion_consistency: { median_ms: 1.1, count: 300 },
  observer: { median_ms: 0.2, count: 300 },
  flow: { median_ms: 3.5, count: 300 },
  segmentation: { median_ms: 9.0, count: 300 },
  local_mapping: { median_ms: 78.0, count: 40 },
  local_triangulation: { median_ms: 8.0, count: 40 },
  local_fusion: { median_ms: 6.0, count: 40 },
  local_ba: { median_ms: 55.0, count: 38 },
  local_keyframe_culling: { median_ms: 0.3, count: 40 },
  dense_keyframe: { median_ms: 74.0, count: 40 },
  loop_detection: { median_ms: 0.5, count: 40 },
  loop_correction: { median_ms: 20.0, count: 1 },
  global_ba: { median_ms: 300.0, count: 1 },
};

const names = (group) => group.rows.map((r) => r.name);

test('per-frame stages and per-keyframe work are split into two groups', () => {
  const groups = groupStages(kStats, 'median');
  assert.deepEqual(groups.map((g) => g.id), ['frame', 'keyframe']);
  const [frame, keyframe] = groups;
  assert.deepEqual(new Set(names(frame)),
                   new Set(['total', 'extraction', 'tracking', 'dense_handoff', 'segmentation_wait',
                            'removal', 'motion_consistency', 'observer', 'flow', 'segmentation']));
  assert.deepEqual(new Set(names(keyframe)),
                   new Set(['local_mapping', 'local_triangulation', 'local_fusion', 'local_ba',
                            'local_keyframe_culling', 'dense_keyframe', 'loop_detection',
                            'loop_correction', 'global_ba']));
  assert.match(frame.title, /per frame/);
  assert.match(keyframe.title, /per keyframe/);
});

test('each group has its own scale: the frame group is not dwarfed by keyframe work', () => {
  const [frame, keyframe] = groupStages(kStats);
  assert.equal(frame.largest, 13.1);
  assert.equal(keyframe.largest, 300.0);
});

test('"total" leads the per-frame group, its parts follow it indented, largest first', () => {
  const [frame] = groupStages(kStats);
  assert.equal(frame.rows[0].name, 'total');
  assert.equal(frame.rows[0].depth, 0);
  const parts = frame.rows.filter((r) => r.depth === 1).map((r) => r.name);
  assert.deepEqual(parts, ['extraction', 'tracking', 'motion_consistency', 'dense_handoff', 'removal',
                           'segmentation_wait']);
  assert.deepEqual(frame.rows.slice(0, 7).map((r) => r.name), ['total', ...parts]);
  // Work on other threads, and the observer (timed after total), are not parts of total.
  for (const name of ['flow', 'segmentation', 'observer']) {
    const row = frame.rows.find((r) => r.name === name);
    assert.equal(row.depth, 0, name);
  }
  assert.equal(frame.rows.find((r) => r.name === 'flow').thread, 'optical-flow helper thread');
  assert.equal(frame.rows.find((r) => r.name === 'observer').thread, 'tracking thread');
});

test("local mapping's steps follow it; counts are kept", () => {
  const [, keyframe] = groupStages(kStats);
  const at = names(keyframe).indexOf('local_mapping');
  assert.deepEqual(names(keyframe).slice(at, at + 5),
                   ['local_mapping', 'local_ba', 'local_triangulation', 'local_fusion',
                    'local_keyframe_culling']);
  assert.deepEqual(keyframe.rows.slice(at + 1, at + 5).map((r) => r.depth), [1, 1, 1, 1]);
  assert.equal(keyframe.rows.find((r) => r.name === 'local_ba').count, 38);
});

test("a live frame's latest times (plain numbers) split the same way", () => {
  const groups = groupStages({ total: 12.5, tracking: 7, local_mapping: 80, dense_keyframe: 70 }, 'latest');
  assert.deepEqual(groups.map((g) => [g.id, names(g)]),
                   [['frame', ['total', 'tracking']], ['keyframe', ['local_mapping', 'dense_keyframe']]]);
  assert.match(groups[0].title, /this frame/);
  assert.ok(groups.every((g) => g.rows.every((r) => r.count === null)));
});

test('no stages, or no keyframe work yet: only what there is', () => {
  assert.deepEqual(groupStages(undefined), []);
  assert.deepEqual(groupStages({}), []);
  assert.deepEqual(groupStages({ total: 5, bogus: NaN }).map((g) => g.id), ['frame']);
});

test('stages this page does not know: by name, else per frame on the tracking thread', () => {
  assert.deepEqual(stageKind('local_new_step'),
                   { perKeyframe: true, thread: 'local mapping thread', parent: 'local_mapping' });
  assert.equal(stageKind('loop_something').perKeyframe, true);
  assert.deepEqual(stageKind('new_frame_stage'),
                   { perKeyframe: false, thread: 'tracking thread', parent: 'total' });
});

test('the chart shows every name in full, in two captioned groups', () => {
  const element = { innerHTML: '' };
  showStages(element, groupStages(kStats), 'time per stage');
  assert.equal((element.innerHTML.match(/class="stage-group"/g) ?? []).length, 2);
  assert.match(element.innerHTML, /data-group="frame"/);
  assert.match(element.innerHTML, /data-group="keyframe"/);
  for (const name of Object.keys(kStats)) assert.ok(element.innerHTML.includes(`>${name}</span>`), name);
  assert.match(element.innerHTML, /&times;40/);  // how many keyframes a median is over
});

// A minimal DOM: enough of document and elements for view3d.js.
function fakeDocument({ webgl2, webgl1 = false, reason = '' }) {
  const doc = {
    createElement(tag) {
      const element = {
        tag,
        ownerDocument: doc,
        children: [],
        listeners: {},
        textContent: '',
        attributes: {},
        setAttribute(name, value) { this.attributes[name] = value; },
        addEventListener(type, listener) { this.listeners[type] = listener; },
        append(...children) { this.children.push(...children); },
        replaceWith(other) { this.replacedBy = other; },
        getContext(kind) {
          if (kind === 'webgl2' && webgl2) return { getExtension: () => ({ loseContext() {} }) };
          if (kind === 'webgl' && webgl1) return {};
          this.listeners.webglcontextcreationerror?.({ statusMessage: reason });
          return null;
        },
      };
      return element;
    },
  };
  return doc;
}

test('webglProblem: null with WebGL 2, else the reason the browser gives', () => {
  assert.equal(webglProblem(fakeDocument({ webgl2: true })), null);
  assert.equal(webglProblem(fakeDocument({ webgl2: false, reason: 'disabled by switch' })), 'disabled by switch');
  assert.match(webglProblem(fakeDocument({ webgl2: false, webgl1: true })), /WebGL 2/);
  assert.match(webglProblem(fakeDocument({ webgl2: false })), /no WebGL context/);
});

test('without WebGL the 3-D panel says why and the page gets a scene that draws nothing', () => {
  const doc = fakeDocument({ webgl2: false, reason: 'disabled by switch' });
  const canvas = doc.createElement('canvas');
  let made = 0;
  const view = createMapView(canvas, () => { made += 1; });
  assert.equal(made, 0);
  assert.equal(view.webgl, false);
  assert.equal(view.problem, 'disabled by switch');
  assert.ok(view.scene instanceof NoScene);
  // Every call the page makes on a scene is there, and does nothing.
  for (const method of ['fit', 'setSparse', 'addDenseChunk', 'clearDense', 'setTrajectory',
                        'setGroundTruth', 'setKeyframes', 'setCurrent', 'setLoops', 'setGrid']) {
    assert.equal(view.scene[method]([], []), undefined, method);
  }
  const note = canvas.replacedBy;
  assert.equal(note.id, 'view3d-message');
  const text = note.children.map((c) => c.textContent).join(' ');
  assert.match(text, /3-D view unavailable/);
  assert.match(text, /plots/);
  assert.match(text, /reason: disabled by switch/);
});

test('with WebGL the real scene is made; if it still fails, the panel falls back', () => {
  const ok = createMapView(fakeDocument({ webgl2: true }).createElement('canvas'), () => 'scene');
  assert.deepEqual(ok, { scene: 'scene', webgl: true, problem: null });
  const canvas = fakeDocument({ webgl2: true }).createElement('canvas');
  const failed = createMapView(canvas, () => { throw new Error('Error creating WebGL context.'); });
  assert.equal(failed.webgl, false);
  assert.equal(failed.problem, 'Error creating WebGL context.');
  assert.equal(canvas.replacedBy.id, 'view3d-message');
});
