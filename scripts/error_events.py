#!/usr/bin/env python3
"""Error over time beside a run's events: where a run's trajectory error comes from.

Usage: error_events.py RUN_DIR [GROUND_TRUTH] [--window 15] [--worst 3] [--tsv FILE]

RUN_DIR is a `drvslam run --frame-log RUN_DIR/frames.tsv` output folder or a benchmark run
(`run_k/`, which has frames.tsv and eval.json). The ground truth defaults to the dataset's
groundtruth.txt named in stats.json. The estimate is put in the ground truth's frame with the
alignment eval.json holds (`drvslam eval --json`), so the per-frame errors are the ones the ATE
summarises. Prints the worst stretches of --window frames (by mean error, not overlapping) with
the events in them (masks, movers' share, features removed, keyframes, lost frames, unlabelled
regions, carried masks), and with --tsv writes one line per frame: error and events.

It splits the error by how fast it changes. Per-frame noise is read from the second
difference of consecutive positions (white noise of sigma gives sqrt(6) sigma; a smooth camera
path gives almost none, the ground truth shows how little). The ATE of the estimate averaged over
--smooth frames (a centred window, same alignment) is the slow part: drift and bias that
no per-frame filter can remove.

When the run saved its poses as tracked beside the smoothed trajectory
(TrackedCameraTrajectory.txt), their ATE and per-frame noise are printed too, with the same
alignment.

And it says whether the error comes from the movers at all: the RMS error (same alignment) over
the frames with no potentially-moving object in view, against the frames with one or more. When
both are alike, the people are not what limits the run; the camera's own tracking is.

Only the standard library: it runs wherever python3 does.
"""
import argparse
import bisect
import json
import math
import os
import sys


def read_tum(path):
    poses = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#") or len(fields) < 8:
                continue
            poses.append((float(fields[0]), [float(v) for v in fields[1:4]]))
    poses.sort()
    return poses


def read_frame_log(path):
    rows = {}
    with open(path) as f:
        header = f.readline().rstrip("\n").split("\t")
        for line in f:
            values = line.rstrip("\n").split("\t")
            if len(values) != len(header):
                continue
            row = dict(zip(header, values))
            rows[round(float(row["timestamp"]), 4)] = row
    return header, rows


def nearest(stamps, t, max_diff):
    i = bisect.bisect_left(stamps, t)
    best = None
    for j in (i - 1, i):
        if 0 <= j < len(stamps) and abs(stamps[j] - t) <= max_diff:
            if best is None or abs(stamps[j] - t) < abs(stamps[best] - t):
                best = j
    return best


def per_frame_errors(estimate, truth, alignment, max_diff=0.02):
    rot, trans, scale = alignment["rotation"], alignment["translation"], alignment["scale"]
    stamps = [t for t, _ in truth]
    errors = []
    for t, p in estimate:
        j = nearest(stamps, t, max_diff)
        if j is None:
            continue
        q = [scale * sum(rot[r][c] * p[c] for c in range(3)) + trans[r] for r in range(3)]
        g = truth[j][1]
        errors.append((t, math.sqrt(sum((q[k] - g[k]) ** 2 for k in range(3))), q, g))
    return errors


def consecutive_triples(stamps):
    """Indices i of frames i-1, i, i+1 that are evenly spaced: no skipped frame between them."""
    gaps = sorted(b - a for a, b in zip(stamps, stamps[1:]))
    if not gaps:
        return []
    period = gaps[len(gaps) // 2]
    even = lambda a, b: abs((b - a) - period) <= 0.25 * period
    return [i for i in range(1, len(stamps) - 1)
            if even(stamps[i - 1], stamps[i]) and even(stamps[i], stamps[i + 1])]


def second_difference_rms(positions, triples):
    """RMS norm of p[i-1] - 2 p[i] + p[i+1] over the given i."""
    if not triples:
        return float("nan")
    total = 0.0
    for i in triples:
        total += sum((positions[i - 1][k] - 2 * positions[i][k] + positions[i + 1][k]) ** 2
                     for k in range(3))
    return math.sqrt(total / len(triples))


def noise_and_slow_error(matched, window):
    """(estimate's second-difference RMS, ground truth's, per-frame noise as a 3-D RMS like the
    ATE's, ATE of the estimate averaged over `window` frames), all in metres. `matched` holds (t, aligned estimate,
    ground truth) per frame, in time order."""
    stamps = [t for t, _, _ in matched]
    estimate = [p for _, p, _ in matched]
    truth = [g for _, _, g in matched]
    triples = consecutive_triples(stamps)
    jitter = second_difference_rms(estimate, triples)
    truth_jitter = second_difference_rms(truth, triples)
    noise = math.sqrt(max(jitter ** 2 - truth_jitter ** 2, 0.0) / 6.0)
    half = window // 2
    squared = 0.0
    for i, g in enumerate(truth):
        part = estimate[max(0, i - half):i + half + 1]
        mean = [sum(p[k] for p in part) / len(part) for k in range(3)]
        squared += sum((mean[k] - g[k]) ** 2 for k in range(3))
    return jitter, truth_jitter, noise, math.sqrt(squared / len(truth))


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else math.nan


def error_by_objects_in_view(errors, log):
    """(count, RMS error) over the frames whose log row shows no potentially-moving object, and
    over those with one or more; None when the frame log has no `objects` column."""
    groups = {False: [], True: []}
    for t, e in errors:
        row = log.get(round(t, 4))
        if row is None or row.get("objects", "") == "":
            continue
        groups[int(row["objects"]) > 0].append(e)
    if not groups[False] and not groups[True]:
        return None
    return (len(groups[False]), rms(groups[False])), (len(groups[True]), rms(groups[True]))


def events_of(rows):
    """Summary of the events in a stretch of frame-log rows."""
    def total(key):
        return sum(float(r.get(key, 0) or 0) for r in rows)

    n = max(len(rows), 1)
    parts = [
        "lost %d" % sum(1 for r in rows if r.get("tracked") == "0"),
        "keyframes %d" % total("keyframe"),
        "objects %.1f/frame" % (total("objects") / n),
        "moving %.1f/frame" % (total("moving") / n),
        "movers' share %.2f" % (total("movers_share") / n),
        "removed %.0f of %.0f features/frame" % (total("removed") / n, total("features") / n),
        "unlabelled regions %d" % total("unlabelled"),
        "carried masks %d frames" % sum(1 for r in rows if r.get("own_masks") == "0"),
        "inliers %.0f/frame" % (total("inliers") / n),
    ]
    return ", ".join(parts)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("ground_truth", nargs="?")
    parser.add_argument("--window", type=int, default=15)
    parser.add_argument("--worst", type=int, default=3)
    parser.add_argument("--smooth", type=int, default=9)
    parser.add_argument("--tsv")
    args = parser.parse_args()

    def need(path, what):
        if not os.path.isfile(path):
            sys.exit("error: %s: %s not found" % (path, what))
        return path

    run = args.run_dir
    truth_path = args.ground_truth
    if truth_path is None:
        stats = json.load(open(need(os.path.join(run, "stats.json"), "the run's stats")))
        truth_path = os.path.join(stats.get("dataset", ""), "groundtruth.txt")
    truth = read_tum(need(truth_path, "ground truth"))
    estimate = read_tum(need(os.path.join(run, "CameraTrajectory.txt"), "the trajectory"))
    alignment = json.load(open(need(os.path.join(run, "eval.json"), "eval --json output")))[
        "alignment"]
    header, log = read_frame_log(need(os.path.join(run, "frames.tsv"), "the frame log"))
    errors = per_frame_errors(estimate, truth, alignment)
    if not errors:
        sys.exit("error: %s: no pose matches the ground truth in time" % run)
    matched = [(t, q, g) for t, _, q, g in errors]
    errors = [(t, e) for t, e, _, _ in errors]
    rmse = rms([e for _, e in errors])
    print("%d poses matched, ATE RMSE %.2f cm" % (len(errors), 100 * rmse))
    jitter, truth_jitter, noise, slow = noise_and_slow_error(matched, args.smooth)
    print("per-frame noise %.2f cm (second difference RMS %.2f cm, ground truth's %.2f cm); "
          "averaged over %d frames: ATE %.2f cm" % (100 * noise, 100 * jitter, 100 * truth_jitter,
                                                   args.smooth, 100 * slow))
    # The saved trajectory is smoothed (Tracking.smoothTrajectory); the tracker's own per-frame
    # noise is in the poses as tracked, saved beside it.
    tracked_path = os.path.join(run, "TrackedCameraTrajectory.txt")
    if os.path.exists(tracked_path):
        tracked = per_frame_errors(read_tum(tracked_path), truth, alignment)
        if tracked:
            jitter, truth_jitter, noise, _ = noise_and_slow_error(
                [(t, q, g) for t, _, q, g in tracked], args.smooth)
            print("as tracked (TrackedCameraTrajectory.txt): ATE %.2f cm, per-frame noise %.2f cm "
                  "(second difference RMS %.2f cm)" % (100 * rms([e for _, e, _, _ in tracked]),
                                                       100 * noise, 100 * jitter))

    by_objects = error_by_objects_in_view(errors, log)
    if by_objects:
        (free, free_rms), (busy, busy_rms) = by_objects
        print("frames without potentially-moving objects in view: %d, RMS error %.2f cm; "
              "with them: %d, RMS error %.2f cm" % (free, 100 * free_rms, busy, 100 * busy_rms))

    taken = []
    order = sorted(range(len(errors) - args.window + 1),
                   key=lambda i: -sum(e for _, e in errors[i:i + args.window]))
    for start in order:
        if len(taken) == args.worst:
            break
        if any(abs(start - s) < args.window for s in taken):
            continue
        taken.append(start)
    for rank, start in enumerate(taken, 1):
        stretch = errors[start:start + args.window]
        rows = [log[k] for k in (round(t, 4) for t, _ in stretch) if k in log]
        frames = [int(r["frame"]) for r in rows]
        mean = sum(e for _, e in stretch) / len(stretch)
        span = "frames %d-%d" % (min(frames), max(frames)) if frames else "no frame-log rows"
        print("worst %d: %s, t %.2f-%.2f s, mean error %.2f cm: %s" % (
            rank, span, stretch[0][0] - errors[0][0], stretch[-1][0] - errors[0][0], 100 * mean,
            events_of(rows)))
    if args.tsv:
        with open(args.tsv, "w") as out:
            extra = [h for h in header if h not in ("timestamp", "wall_s")]
            out.write("timestamp\terror_cm\t" + "\t".join(extra) + "\n")
            for t, e in errors:
                row = log.get(round(t, 4), {})
                out.write("%.6f\t%.3f\t%s\n" % (t, 100 * e, "\t".join(row.get(h, "") for h in extra)))


if __name__ == "__main__":
    main()
