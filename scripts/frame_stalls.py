#!/usr/bin/env python3
"""Tracking-thread time per frame during map corrections.

Reads a `drvslam run --frame-log FRAMES.tsv` file and the run's log (`--log-level info`, whose
"loop closed ... N ms" and "global bundle adjustment: ... N ms" lines end when the correction
ends) and prints the TrackRGBD time (max, p95, median) of all frames and of the frames whose call
overlapped a loop correction or a global bundle adjustment (from its gather to its merge).
The log's clock is the local time of the machine; the frame log's is Unix time: run in UTC.
With --stopped FILE (lines starting with the Unix time at which the process was seen stopped,
e.g. sampled every 0.1 s from /proc/PID/stat on a shared machine whose other users SIGSTOP it),
frames whose call overlapped a stop are left out of both summaries and counted.

usage: frame_stalls.py FRAMES.tsv RUN.log [--stopped FILE] [--json]
"""
import datetime
import json
import re
import sys

LINE = re.compile(r"^\[(\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3})\] \[info\] (loop closed|global bundle "
                  r"adjustment):.*?([0-9.]+) ms")


def windows(log_path):
    result = []
    with open(log_path) as log:
        for line in log:
            match = LINE.match(line)
            if not match:
                continue
            end = datetime.datetime.strptime(match.group(1), "%Y-%m-%d %H:%M:%S.%f").replace(
                tzinfo=datetime.timezone.utc).timestamp()
            # The last "N ms" of the line is the step's duration.
            duration = float(re.findall(r"([0-9.]+) ms", line)[-1]) / 1000.0
            result.append((match.group(2), end - duration, end))
    return result


def stopped_spans(path, gap_s=0.5, pad_s=0.2):
    """Sample times merged into intervals (samples closer than gap_s), widened by pad_s."""
    with open(path) as samples:
        times = sorted(float(line.split()[0]) for line in samples if line.strip())
    spans = []
    for t in times:
        if spans and t - spans[-1][1] <= gap_s:
            spans[-1][1] = t
        else:
            spans.append([t, t])
    return [(start - pad_s, end + pad_s) for start, end in spans]


def summary(values):
    if not values:
        return {"frames": 0}
    ordered = sorted(values)
    p95 = ordered[min(len(ordered) - 1, int(round(0.95 * (len(ordered) - 1))))]
    return {"frames": len(values), "max_ms": round(ordered[-1], 1), "p95_ms": round(p95, 1),
            "median_ms": round(ordered[len(ordered) // 2], 1)}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    spans = windows(sys.argv[2])
    stops = []
    if "--stopped" in sys.argv:
        stops = stopped_spans(sys.argv[sys.argv.index("--stopped") + 1])
    all_ms, during_ms = [], []
    left_out = 0
    with open(sys.argv[1]) as frames:
        next(frames)
        for line in frames:
            fields = line.split("\t")
            end, ms = float(fields[2]), float(fields[3])
            start = end - ms / 1000.0
            if any(start <= s_end and end >= s_start for s_start, s_end in stops):
                left_out += 1
                continue
            all_ms.append(ms)
            if any(start <= w_end and end >= w_start for _, w_start, w_end in spans):
                during_ms.append(ms)
    report = {"corrections": sum(1 for kind, _, _ in spans if kind == "loop closed"),
              "global_bas": sum(1 for kind, _, _ in spans if kind != "loop closed"),
              "correction_window_s": round(sum(e - s for _, s, e in spans), 2),
              "all_frames": summary(all_ms), "during_corrections": summary(during_ms)}
    if "--stopped" in sys.argv:
        report["frames_left_out_stopped"] = left_out
    print(json.dumps(report, indent=1 if "--json" in sys.argv else None))


if __name__ == "__main__":
    main()
