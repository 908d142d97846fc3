// Unit tests of the error plot's events (src/events.js), node's test runner:
//   cd web && npm test
// The frame log's columns become tick lanes and share curves on the error plot's time axis.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { errorPlotEvents, eventLegend } from '../src/events.js';

// Six logged frames of a realtime run: frames 3 and 4 were skipped, frame 5 was lost and
// frame 6 relocalized; frames 0 and 6 became keyframes.
const kEvents = {
  frame: [0, 1, 2, 5, 6, 7],
  timestamp: [100.0, 100.1, 100.2, 100.5, 100.6, 100.7],
  tracked: [1, 1, 1, 0, 1, 1],
  keyframe: [1, 0, 0, 0, 1, 0],
  movers_share: [0, 0.1, 0.2, 0.5, 0.4, 0.3],
  features: [1000, 1000, 1000, 0, 1200, 1000],
  removed: [0, 100, 300, 0, 600, 250],
};

const close = (actual, expected) =>
  assert.ok(
    actual.length === expected.length && actual.every((v, i) => Math.abs(v - expected[i]) < 1e-9),
    `${JSON.stringify(actual)} != ${JSON.stringify(expected)}`);

test('lost, relocalized, keyframe and skipped frames land at their times', () => {
  const marks = errorPlotEvents(kEvents, [], [], 100.0);
  close(marks.lost, [0.5]);
  close(marks.relocalized, [0.6]);
  close(marks.keyframes, [0.0, 0.6]);
  // Two frames missing between the logged frames 2 (t 0.2) and 5 (t 0.5).
  close(marks.skipped, [0.3, 0.4]);
});

test('shares follow the frames; a frame without features has no removed share', () => {
  const marks = errorPlotEvents(kEvents, [], [], 100.0);
  close(marks.moversShare.map((p) => p[1]), [0, 0.1, 0.2, 0.5, 0.4, 0.3]);
  close(marks.removedShare.map((p) => p[0]), [0.0, 0.1, 0.2, 0.6, 0.7]);
  close(marks.removedShare.map((p) => p[1]), [0, 0.1, 0.3, 0.5, 0.25]);
});

test('loop closures and rejected loop candidates come from the stats', () => {
  const loops = [{ timestamp: 100.65 }];
  const rejections = [{ timestamp: 100.25 }, { timestamp: 100.45 }];
  const marks = errorPlotEvents(kEvents, loops, rejections, 100.0);
  close(marks.loopsClosed, [0.65]);
  close(marks.loopsRejected, [0.25, 0.45]);
});

test('a log from before the event columns still gives lost and skipped frames', () => {
  const old = { frame: kEvents.frame, timestamp: kEvents.timestamp, tracked: kEvents.tracked };
  const marks = errorPlotEvents(old, undefined, undefined, 100.0);
  close(marks.lost, [0.5]);
  close(marks.skipped, [0.3, 0.4]);
  assert.equal(marks.keyframes.length, 0);
  assert.equal(marks.moversShare.length, 0);
});

test('without a frame log there are no marks, and the legend lists only what is drawn', () => {
  const none = errorPlotEvents(null, [], [], 0);
  assert.deepEqual(eventLegend(none), []);
  const labels = eventLegend(errorPlotEvents(kEvents, [], [{ timestamp: 100.3 }], 100.0)).map(
    (e) => e.label);
  assert.deepEqual(labels, ["movers' share", 'features removed', 'keyframe (2)', 'lost (1)',
                            'relocalized (1)', 'skipped (2)', 'loop rejected (1)']);
});
