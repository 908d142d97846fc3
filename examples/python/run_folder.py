#!/usr/bin/env python3
"""Runs drvslam on a TUM-layout RGB-D folder through the Python module.

The folder is read as `drvslam run --dataset` reads it (associations.txt, else rgb.txt and
depth.txt paired by timestamp; TUM RGB-D, Bonn and `drvslam synth` sequences), and every frame is
handed to System.track_rgbd as numpy arrays: the loop a camera SDK's frame callback drives
(pyrealsense2, pyk4a, an Orbbec or ROS callback give the same two arrays and a timestamp).
The trajectories are written as `drvslam run` writes them, so with --sequential the output is
byte-identical to `drvslam run --sequential` with the same options.

    PYTHONPATH=build/python python3 examples/python/run_folder.py SEQUENCE --out OUT
"""
import argparse
import os
import re
import sys

import drvslam


def read_list(path, fields_per_line):
    """The data lines of a TUM list: '#' comments and blank lines skipped, fields split on
    spaces, tabs and commas; an entry whose timestamp does not increase is dropped, as
    `drvslam run` drops it."""
    entries = []
    with open(path) as lines:
        for number, line in enumerate(lines, 1):
            fields = [f for f in re.split(r"[ \t,\r\n]+", line) if f]
            if not fields or fields[0].startswith("#"):
                continue
            if len(fields) != fields_per_line:
                raise SystemExit(f"{path}:{number}: expected {fields_per_line} fields")
            stamp = float(fields[0])
            if entries and stamp <= entries[-1][0]:
                print(f"{path}:{number}: timestamp does not increase; entry skipped",
                      file=sys.stderr)
                continue
            entries.append((stamp, *fields[1:]))
    return entries


def frames(folder):
    """(timestamp, colour image path, depth image path) of every colour/depth pair."""
    join = lambda name: os.path.join(folder, name)
    if os.path.exists(join("associations.txt")):
        return [(t, join(rgb), join(depth))
                for t, rgb, _, depth in read_list(join("associations.txt"), 4)]
    rgb = read_list(join("rgb.txt"), 2)
    depth = read_list(join("depth.txt"), 2)
    pairs = drvslam.associate([t for t, _ in rgb], [t for t, _ in depth], max_difference=0.02)
    return [(rgb[i][0], join(rgb[i][1]), join(depth[j][1])) for i, j in pairs]


def colour_bgr(image):
    """An 8-bit colour file as the (H, W, 3) BGR array track_rgbd takes."""
    if image.ndim == 2:  # grey: repeated into three channels
        return image[:, :, None].repeat(3, axis=2)
    return image[:, :, :3].copy() if image.shape[2] == 4 else image  # BGRA: alpha dropped


def on_off(text):
    return None if text is None else text == "on"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", help="TUM-layout sequence folder")
    parser.add_argument("--settings", help="settings file (default: FOLDER/settings.yaml)")
    parser.add_argument("--out", default="out", help="output folder")
    parser.add_argument("--sequential", action="store_true",
                        help="every stage on this thread: bit-identical results")
    parser.add_argument("--segmenter", choices=["yolo", "masks", "gt", "none"])
    parser.add_argument("--model", help="YOLO segmentation ONNX file (implies yolo)")
    parser.add_argument("--dynamic", choices=["on", "off"])
    parser.add_argument("--dense", choices=["on", "off"])
    parser.add_argument("--loop", choices=["on", "off"])
    parser.add_argument("--max-frames", type=int, default=0, help="stop after N frames")
    parser.add_argument("--trajectory-format", default="tum", choices=["tum", "kitti", "euroc"])
    args = parser.parse_args()

    system = drvslam.System(args.settings, dataset=args.folder, sequential=args.sequential,
                            segmenter=args.segmenter, model=args.model,
                            dynamic=on_off(args.dynamic), dense=on_off(args.dense),
                            loop=on_off(args.loop))
    print(f"settings: {system.settings_source}; segmenter: {system.segmenter}")
    todo = frames(args.folder)
    if args.max_frames > 0:
        todo = todo[:args.max_frames]
    lost = 0
    for timestamp, rgb_path, depth_path in todo:
        # A camera SDK hands over these two arrays: colour as uint8 BGR, depth as uint16 raw
        # units (DepthMapFactor per metre) or float32 metres.
        try:
            bgr = colour_bgr(drvslam.read_image(rgb_path))
            depth = drvslam.read_image(depth_path)
        except drvslam.Error as error:
            print(f"skipped: {error}", file=sys.stderr)
            continue
        result = system.track_rgbd(bgr, depth, timestamp)
        if result.state == drvslam.TrackingState.LOST:
            lost += 1
    system.shutdown()  # mapping drains its queue: the final poses
    path = system.write_trajectories(args.out, args.trajectory_format)
    stats = system.stats()
    print(f"frames: {stats['frames']}, tracked: {stats['tracked']}, lost: {lost}, "
          f"keyframes: {stats['keyframes']}, map points: {stats['map_points']}")
    print(f"wrote: {path}")


if __name__ == "__main__":
    main()
