#!/usr/bin/env python3
"""Writes the seed corpora of the fuzzers (fuzz/corpus/<target>/) from real files.

  fuzz/seed_tools/make_seeds.py --drvslam build/bin/drvslam \
      --bonn /work/data/bonn_crowd_dev --model /work/shared/models/yolo11n-seg-320x256.onnx

What each seed is (the input layouts are the bodies', fuzz/fuzz_bodies/*.cc):
  settings:      configs/*.yaml, the Bonn dataset's settings.yaml, a `drvslam synth` settings.yaml
  map_file:      a map saved by `drvslam run --save-map` on a short synthetic sequence, with and
                 without the dense map, cut down by trim_map.py; flag byte 1 (fix the checksum)
                 and 0 (as saved)
  tum_text:      the head of the Bonn rgb.txt, depth.txt and groundtruth.txt as a dataset, a
                 synthetic dataset with associations.txt, groundtruth.txt alone, and the
                 CameraTrajectory of a 15-frame Bonn run in tum, kitti (with times) and euroc
  vocabulary:    `drvslam vocab train` on the synthetic images, k 4, L 2, text and binary
  onnx_metadata: the model's ONNX header (ir_version, producer, opsets, metadata with the class
                 names, graph inputs and outputs; nodes and weights left out), and its "names"
  ros2_image:    Image messages in every encoding the node reads (padded rows, big-endian
                 depth) and CameraInfo messages (plumb_bob, rational_polynomial, none)
"""
import argparse
import pathlib
import struct
import subprocess
import sys
import tempfile

FUZZ = pathlib.Path(__file__).resolve().parent.parent
ROOT = FUZZ.parent
SEPARATOR = b"\n--8<--\n"  # tum_text_body.cc's kFileSeparator


def write(target, name, data):
    folder = FUZZ / "corpus" / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data)


def head(path, lines):
    with open(path, "rb") as f:
        return b"".join(f.readline() for _ in range(lines))


def run(*args):
    subprocess.run([str(a) for a in args], check=True, stdout=subprocess.DEVNULL)


def settings_seeds(bonn, work):
    for config in sorted((ROOT / "configs").glob("*.yaml")):
        write("settings", config.name, config.read_bytes())
    write("settings", "bonn_settings.yaml", (bonn / "settings.yaml").read_bytes())
    write("settings", "synth_settings.yaml", (work / "synth" / "settings.yaml").read_bytes())


def map_seeds(drvslam, work):
    settings = work / "map_settings.yaml"
    settings.write_bytes((work / "synth" / "settings.yaml").read_bytes() +
                         b'Relocalization.vocabulary: "%s"\n' % str(work / "vocab.bin").encode())
    trim = FUZZ / "seed_tools" / "trim_map.py"
    for dense in ("off", "on"):
        saved, trimmed = work / f"map_{dense}.bin", work / f"trim_{dense}.bin"
        run(drvslam, "run", "--dataset", work / "synth", "--config", settings, "--segmenter",
            "none", "--dense", dense, "--max-frames", 12, "--sequential", "--out",
            work / f"run_{dense}", "--save-map", saved)
        run(sys.executable, trim, saved, trimmed)
        name = "sparse" if dense == "off" else "dense"
        write("map_file", f"{name}_fixed_checksum.bin", b"\x01" + trimmed.read_bytes())
        write("map_file", f"{name}_as_saved.bin", b"\x00" + trimmed.read_bytes())


def tum_seeds(drvslam, bonn, work):
    lists = [head(bonn / name, 12) for name in ("rgb.txt", "depth.txt", "groundtruth.txt")]
    write("tum_text", "bonn_dataset.txt", b"\x00" + SEPARATOR.join(lists))
    synth = work / "synth"
    files = [head(synth / name, 6)
             for name in ("rgb.txt", "depth.txt", "groundtruth.txt", "associations.txt")]
    write("tum_text", "synth_dataset_associations.txt", b"\x00" + SEPARATOR.join(files))
    write("tum_text", "bonn_groundtruth.txt", b"\x01" + head(bonn / "groundtruth.txt", 20))
    for fmt, mode in (("tum", 3), ("kitti", 4), ("euroc", 5)):
        out = work / f"bonn_{fmt}"
        run(drvslam, "run", "--dataset", bonn, "--segmenter", "none", "--dense", "off",
            "--max-frames", 15, "--sequential", "--trajectory-format", fmt, "--out", out)
        poses = next(out.glob("CameraTrajectory.*")).read_bytes()
        times = out / "CameraTrajectory_times.txt"
        data = poses + (SEPARATOR + times.read_bytes() if times.exists() else b"")
        write("tum_text", f"{fmt}_detected.txt", b"\x02" + data)
        write("tum_text", f"{fmt}_given.txt", bytes([mode]) + data)


def vocabulary_seeds(drvslam, work):
    for fmt, suffix in (("binary", "bin"), ("text", "txt")):
        out = work / f"vocab.{suffix}"
        run(drvslam, "vocab", "train", "--images", work / "synth" / "rgb", "--out", out, "--k", 4,
            "--levels", 2, "--features", 200, "--format", fmt)
        write("vocabulary", f"k4_l2.{suffix}", out.read_bytes())


def varint(value):
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        out.append(byte | (0x80 if value else 0))
        if not value:
            return bytes(out)


def fields(message):
    """(number, wire type, raw field bytes, payload) of each field of a protobuf message."""
    pos = 0
    while pos < len(message):
        start = pos
        tag, shift = 0, 0
        while True:
            byte = message[pos]
            pos += 1
            tag |= (byte & 0x7F) << shift
            shift += 7
            if not byte & 0x80:
                break
        number, wire = tag >> 3, tag & 7
        payload = b""
        if wire == 0:
            while message[pos] & 0x80:
                pos += 1
            pos += 1
        elif wire == 1:
            pos += 8
        elif wire == 5:
            pos += 4
        elif wire == 2:
            length, shift = 0, 0
            while True:
                byte = message[pos]
                pos += 1
                length |= (byte & 0x7F) << shift
                shift += 7
                if not byte & 0x80:
                    break
            payload = message[pos:pos + length]
            pos += length
        else:
            raise ValueError(f"wire type {wire}")
        yield number, wire, message[start:pos], payload


def onnx_seeds(model):
    data = model.read_bytes()
    header = bytearray()
    names = None
    for number, _, raw, payload in fields(data):
        if number == 7:  # graph: its name, inputs and outputs only
            graph = b"".join(raw_g for n, _, raw_g, _ in fields(payload) if n in (2, 11, 12))
            header += varint(7 << 3 | 2) + varint(len(graph)) + graph
        else:
            header += raw
        if number == 14:  # metadata_props: key 1, value 2
            entry = {n: p for n, _, _, p in fields(payload)}
            if entry.get(1) == b"names":
                names = entry.get(2)
    write("onnx_metadata", f"{model.stem}_header.onnx", b"\x00" + bytes(header))
    if names:
        write("onnx_metadata", "names_python_dict.txt", b"\x01" + names)
    write("onnx_metadata", "names_json.txt", b'\x01{"0": "person", "1": "bicycle", "2": "car"}')


def image_message(encoding, width, height, step, data, big_endian=0):
    text = encoding.encode()
    return (b"\x00" + struct.pack("<IIBI", height, width, big_endian, step) +
            bytes([len(text)]) + text + data)


def info_message(model, d, width=640, height=480):
    text = model.encode()
    k = [525.0, 0, 319.5, 0, 525.0, 239.5, 0, 0, 1]
    r = [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0]
    p = [525.0, 0, 319.5, 0, 0, 525.0, 239.5, 0, 0, 0, 1.0, 0]
    return (b"\x01" + struct.pack("<II", height, width) + bytes([len(text)]) + text +
            bytes([len(d)]) + struct.pack(f"<{len(d)}d", *d) + struct.pack("<9d", *k) +
            struct.pack("<9d", *r) + struct.pack("<12d", *p) + struct.pack("<II", 0, 0))


def ros2_seeds():
    pixels = bytes(range(48))
    write("ros2_image", "rgb8_padded.bin", image_message("rgb8", 2, 2, 8, pixels[:16]))
    write("ros2_image", "bgr8.bin", image_message("bgr8", 4, 2, 12, pixels[:24]))
    write("ros2_image", "rgba8.bin", image_message("rgba8", 2, 2, 8, pixels[:16]))
    write("ros2_image", "bgra8.bin", image_message("bgra8", 2, 2, 8, pixels[:16]))
    write("ros2_image", "mono8.bin", image_message("mono8", 4, 4, 4, pixels[:16]))
    depth16 = struct.pack("<4H", 1234, 0, 5000, 65535)
    write("ros2_image", "16uc1.bin", image_message("16UC1", 2, 2, 4, depth16))
    write("ros2_image", "16uc1_big_endian.bin",
          image_message("16UC1", 2, 2, 4, struct.pack(">4H", 1234, 0, 5000, 65535), 1))
    write("ros2_image", "mono16.bin", image_message("mono16", 2, 2, 4, depth16))
    depth32 = struct.pack("<4f", 2.5, float("nan"), -1.0, float("inf"))
    write("ros2_image", "32fc1.bin", image_message("32FC1", 2, 2, 8, depth32))
    write("ros2_image", "32fc1_big_endian.bin",
          image_message("32FC1", 2, 2, 8, struct.pack(">4f", 2.5, 0.0, 1.0, 3.0), 1))
    write("ros2_image", "info_plumb_bob.bin",
          info_message("plumb_bob", [0.1, -0.2, 0.001, 0.002, 0.03]))
    write("ros2_image", "info_rational.bin",
          info_message("rational_polynomial", [0.1, -0.2, 0.001, 0.002, 0.03, 0, 0, 0]))
    write("ros2_image", "info_no_distortion.bin", info_message("", []))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--drvslam", required=True, type=pathlib.Path)
    parser.add_argument("--bonn", required=True, type=pathlib.Path)
    parser.add_argument("--model", required=True, type=pathlib.Path)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        work = pathlib.Path(folder)
        run(args.drvslam, "synth", "--scenario", "static_xyz", "--frames", 12, "--seed", 2,
            "--clean", "--out", work / "synth")
        vocabulary_seeds(args.drvslam, work)
        settings_seeds(args.bonn, work)
        map_seeds(args.drvslam, work)
        tum_seeds(args.drvslam, args.bonn, work)
    onnx_seeds(args.model)
    ros2_seeds()


if __name__ == "__main__":
    main()
