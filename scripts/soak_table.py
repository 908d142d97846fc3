#!/usr/bin/env python3
"""The soak table of a `drvslam run --frame-log FRAMES.tsv` run (scripts/soak.sh).

Prints, as Markdown, a row every 1,000 frames (frames, keyframes, map points, RSS, frames
tracked and loop corrections so far) and how memory grows after the warm-up: the RSS, keyframe
and map-point change from the warm-up frame to the last, and the frame coefficient of the
least-squares fit RSS = a + b * keyframes + c * frame over those frames (KiB a frame costs
beyond what the map's growth explains; soak_integration_test asserts the same fit).
RUN.log (an `--log-level info` log) gives the loop corrections ("loop closed: ... (t STAMP)")
and global bundle adjustments.

usage: soak_table.py FRAMES.tsv RUN.log [--warm-up FRAMES] [--every N]
"""
import argparse
import re

LOOP = re.compile(r"\] loop closed: keyframe \d+ \(t ([0-9.]+)\)")
GLOBAL_BA = re.compile(r"\] global bundle adjustment: \d+ keyframes")


def read_frames(path):
    rows = []
    with open(path) as frames:
        header = next(frames).rstrip("\n").split("\t")
        for line in frames:
            fields = dict(zip(header, line.rstrip("\n").split("\t")))
            if len(fields) != len(header):
                continue  # a line cut off by a crash
            rows.append({"frame": int(fields["frame"]), "stamp": float(fields["timestamp"]),
                         "tracked": int(fields["tracked"]),
                         "keyframes": int(fields["keyframes"]),
                         "map_points": int(fields["map_points"]),
                         "rss_kib": int(fields["rss_kib"])})
    return rows


def read_log(path):
    loop_stamps, global_bas = [], 0
    with open(path, errors="replace") as log:
        for line in log:
            match = LOOP.search(line)
            if match:
                loop_stamps.append(float(match.group(1)))
            elif GLOBAL_BA.search(line):
                global_bas += 1
    return sorted(loop_stamps), global_bas


def solve3(a, b):
    """Solves the 3x3 system a x = b by Gaussian elimination with partial pivoting."""
    m = [row[:] + [rhs] for row, rhs in zip(a, b)]
    for col in range(3):
        pivot = max(range(col, 3), key=lambda r: abs(m[r][col]))
        m[col], m[pivot] = m[pivot], m[col]
        if m[col][col] == 0:
            return None
        for r in range(3):
            if r != col:
                factor = m[r][col] / m[col][col]
                m[r] = [x - factor * y for x, y in zip(m[r], m[col])]
    return [m[i][3] / m[i][i] for i in range(3)]


def kib_per_frame_beyond_map(rows):
    """Frame coefficient c of rss = a + b * keyframes + c * frame; while the map holds still
    (one keyframe count throughout) the slope of rss = a + c * frame."""
    if len({row["keyframes"] for row in rows}) == 1:
        n = len(rows)
        mean_frame = sum(row["frame"] for row in rows) / n
        mean_rss = sum(row["rss_kib"] for row in rows) / n
        spread = sum((row["frame"] - mean_frame) ** 2 for row in rows)
        return "RSS = a + c*frame (the map held still)", sum(
            (row["frame"] - mean_frame) * (row["rss_kib"] - mean_rss) for row in rows) / spread
    normal = [[0.0] * 3 for _ in range(3)]
    right = [0.0] * 3
    for row in rows:
        x = (1.0, float(row["keyframes"]), float(row["frame"]))
        for i in range(3):
            right[i] += x[i] * row["rss_kib"]
            for j in range(3):
                normal[i][j] += x[i] * x[j]
    solution = solve3(normal, right)
    return "RSS = a + b*keyframes + c*frame", None if solution is None else solution[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("frames")
    parser.add_argument("log")
    parser.add_argument("--warm-up", type=int, default=2000)
    parser.add_argument("--every", type=int, default=1000)
    args = parser.parse_args()
    rows = read_frames(args.frames)
    if not rows:
        raise SystemExit(args.frames + ": no frames logged")
    loop_stamps, global_bas = read_log(args.log)

    print("| frames | keyframes | map points | RSS MiB | tracked | loop corrections |")
    print("|---:|---:|---:|---:|---:|---:|")
    tracked = 0
    for row in rows:
        tracked += row["tracked"]
        count = row["frame"] + 1
        if count % args.every == 0 or row is rows[-1]:
            loops = sum(1 for stamp in loop_stamps if stamp <= row["stamp"])
            print(f"| {count} | {row['keyframes']} | {row['map_points']} | "
                  f"{row['rss_kib'] / 1024:.1f} | {tracked} | {loops} |")
    print()
    print(f"frames logged: {len(rows)}, tracked: {tracked}; loop corrections: {len(loop_stamps)}, "
          f"global BAs: {global_bas}")
    after = [row for row in rows if row["frame"] >= args.warm_up]
    if len(after) < 2:
        print(f"fewer than 2 frames after the warm-up ({args.warm_up}): no growth figures")
        return
    first, last = after[0], after[-1]
    span = last["frame"] - first["frame"]
    formula, coefficient = kib_per_frame_beyond_map(after)
    print(f"after warm-up (frame {first['frame']} -> {last['frame']}, {span} frames): "
          f"keyframes {first['keyframes']} -> {last['keyframes']}, map points "
          f"{first['map_points']} -> {last['map_points']}, RSS {first['rss_kib'] / 1024:.1f} -> "
          f"{last['rss_kib'] / 1024:.1f} MiB ({(last['rss_kib'] - first['rss_kib']) / span:.3f} "
          f"KiB/frame overall); fit {formula}: c = "
          + ("n/a" if coefficient is None else f"{coefficient:.3f}")
          + " KiB per frame beyond the map's growth")


if __name__ == "__main__":
    main()
