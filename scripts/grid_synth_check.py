#!/usr/bin/env python3
"""Scores a run's occupancy grid (map.yaml + map.pgm) against a `drvslam synth` walking room.

The synthetic room's layout (drvslam synth: room_layout.h, scene_builder.cc, actors.cc): floor
z = 0, table 1.6 m x 0.9 m centred on the origin, stools at (+-0.45, 0.85), walkers on lanes at
y = -1.15 (and -1.35 near x = 0), y = 1.35 and x = +-1.25. The grid is brought into the room's
frame through drvslam_T_world_grid and the first frame's true pose (the run's world frame is its
first camera's). Pure Python: no numpy on the build machines.
"""
import argparse
import math
import os
import sys


def read_yaml(path):
    values = {}
    with open(path) as f:
        for line in f:
            if ":" not in line or line.startswith("#"):
                continue
            key, value = line.split(":", 1)
            value = value.strip()
            if value.startswith("["):
                values[key] = [float(v) for v in value.strip("[]").split(",") if v.strip()]
            else:
                values[key] = value
    return values


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    if fields[0] != b"P5":
        sys.exit(f"{path}: not a binary PGM")
    width, height = int(fields[1]), int(fields[2])
    return width, height, data[pos + 1:pos + 1 + width * height]


def pose_matrix(tx, ty, tz, qx, qy, qz, qw):
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw), tx],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw), ty],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy), tz],
            [0, 0, 0, 1]]


def first_pose(path):
    with open(path) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                return pose_matrix(*[float(v) for v in line.split()[1:8]])
    sys.exit(f"{path}: no pose")


def inverse(T):
    R = [[T[j][i] for j in range(3)] for i in range(3)]
    t = [-sum(R[i][k] * T[k][3] for k in range(3)) for i in range(3)]
    return [R[0] + [t[0]], R[1] + [t[1]], R[2] + [t[2]], [0, 0, 0, 1]]


def multiply(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def distance_to_segment(p, a, b):
    ax, ay = a
    dx, dy = b[0] - ax, b[1] - ay
    s = max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / (dx * dx + dy * dy)))
    return math.hypot(p[0] - ax - s * dx, p[1] - ay - s * dy)


# The walkers' lanes (actors.cc BuildRoutes with the default room) as segments.
LANES = [((-2.55, -1.15), (2.55, -1.15)), ((-0.45, -1.15), (0.0, -1.35)),
         ((0.0, -1.35), (0.45, -1.15)), ((-2.55, 1.35), (2.55, 1.35)),
         ((-1.25, -1.15), (-1.25, 1.35)), ((1.25, -1.15), (1.25, 1.35))]


def in_rect(p, x0, x1, y0, y1):
    return x0 <= p[0] <= x1 and y0 <= p[1] <= y1


def near_furniture(p, margin):
    if in_rect(p, -0.8 - margin, 0.8 + margin, -0.45 - margin, 0.45 + margin):  # table
        return True
    for sx in (-0.45, 0.45):  # stools, 0.38 m seats
        if in_rect(p, sx - 0.19 - margin, sx + 0.19 + margin, 0.66 - margin, 1.04 + margin):
            return True
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--run", required=True, help="the run's output folder (map.yaml)")
    parser.add_argument("--sequence", required=True, help="the synth folder (groundtruth.txt)")
    parser.add_argument("--lane-radius", type=float, default=0.15)
    args = parser.parse_args()
    yaml = read_yaml(os.path.join(args.run, "map.yaml"))
    width, height, pixels = read_pgm(os.path.join(args.run, yaml["image"]))
    resolution = float(yaml["resolution"])
    ox, oy = yaml["origin"][0], yaml["origin"][1]
    g = yaml["drvslam_T_world_grid"]
    T_world_grid = [g[0:4], g[4:8], g[8:12], g[12:16]]
    # The run's world frame is its first camera frame; the truth's first pose places it.
    T_room_world = first_pose(os.path.join(args.sequence, "groundtruth.txt"))
    T_room_grid = multiply(T_room_world, T_world_grid)

    counts = {k: {0: 0, 254: 0, 205: 0} for k in ("table", "table_inner", "lanes", "open")}
    floor_height = []
    for row in range(height):
        for column in range(width):
            x = ox + (column + 0.5) * resolution
            y = oy + (height - row - 0.5) * resolution
            p = [sum(T_room_grid[i][k] * v for k, v in enumerate((x, y, 0.0, 1.0))) for i in range(3)]
            value = pixels[row * width + column]
            if row == 0 and column == 0:
                floor_height.append(p[2])
            if in_rect(p, -0.8, 0.8, -0.45, 0.45):
                counts["table"][value] += 1
            if in_rect(p, -0.75, 0.75, -0.4, 0.4):
                counts["table_inner"][value] += 1
            on_lane = min(distance_to_segment(p, a, b) for a, b in LANES) <= args.lane_radius
            if on_lane and not near_furniture(p, 0.3):
                counts["lanes"][value] += 1
            if in_rect(p, -2.3, 2.3, -2.6, 1.45) and not near_furniture(p, 0.3):
                counts["open"][value] += 1
    print(f"grid: {width} x {height} cells at {resolution} m = {width * resolution:.2f} m x "
          f"{height * resolution:.2f} m; cells: {pixels.count(0)} occupied, {pixels.count(254)} "
          f"free, {pixels.count(205)} unknown")
    grid_up = [T_room_grid[i][2] for i in range(3)]
    print(f"grid floor in the room: up = ({grid_up[0]:.3f}, {grid_up[1]:.3f}, {grid_up[2]:.3f}), "
          f"height of the grid origin {T_room_grid[2][3]:+.3f} m (truth: floor z = 0)")
    for name, what in (("table", "table footprint (1.6 x 0.9 m)"),
                       ("table_inner", "table footprint inset 5 cm"),
                       ("lanes", f"people's lanes (within {args.lane_radius} m, 0.3 m off furniture)"),
                       ("open", "open floor (|x| <= 2.3, -2.6 <= y <= 1.45, 0.3 m off furniture)")):
        c = counts[name]
        total = sum(c.values())
        share = c[0] / total if total else float("nan")
        print(f"{what}: {total} cells, {c[0]} occupied ({100 * share:.1f} %), {c[254]} free, "
              f"{c[205]} unknown")


if __name__ == "__main__":
    main()
