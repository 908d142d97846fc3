#!/usr/bin/env python3
"""Cuts a map file saved by `drvslam run --save-map` down to a fuzz seed of a few kilobytes.

Keeps the first --keypoints keypoints of the first keyframe, adds a second keyframe (a copy,
id+1, child of the first, covisible with it) so the graph and spanning-tree code is reached,
keeps the map points seen at the kept keypoints (observed by both keyframes), and the first
--voxels dense voxels of each level anchored to the first keyframe. The layout is map_file.h's;
the file length and CRC-32 are rewritten.

  trim_map.py IN.bin OUT.bin [--keypoints 24] [--voxels 4]
"""
import argparse
import struct
import zlib

KEYPOINT_BYTES = 7 * 4 + 32
VOXEL_BYTES = 4 + 12 + 3 + 2 + 4 + 4 + 2 + 2 + 1


class Reader:
    def __init__(self, data):
        self.data, self.pos = data, 0

    def take(self, fmt):
        values = struct.unpack_from("<" + fmt, self.data, self.pos)
        self.pos += struct.calcsize("<" + fmt)
        return values if len(values) > 1 else values[0]

    def raw(self, n):
        out = self.data[self.pos:self.pos + n]
        self.pos += n
        return out


def pairs(blob):
    return struct.pack("<Q", len(blob)) + b"".join(struct.pack("<qi", a, b) for a, b in blob)


def read_pairs(r):
    return [r.take("qi") for _ in range(r.take("Q"))]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--keypoints", type=int, default=24)
    parser.add_argument("--voxels", type=int, default=4)
    args = parser.parse_args()
    data = open(args.input, "rb").read()
    r = Reader(data)
    magic = r.raw(8)
    version, count, _ = r.take("IIQ")
    sections = []
    for _ in range(count):
        tag, length = r.take("IQ")
        sections.append((tag, r.raw(length)))

    out_sections = []
    kept = args.keypoints
    for tag, payload in sections:
        name = struct.pack("<I", tag)
        r = Reader(payload)
        if name == b"META":
            head = r.raw(len(payload) - 16)
            next_kf, next_mp = r.take("qq")
            out_sections.append((tag, head + struct.pack("<qq", max(next_kf, 2), next_mp)))
        elif name == b"KFRM":
            r.take("Q")
            kf_id, frame_id, stamp = r.take("qqd")
            pose = r.raw(56)
            n = r.take("Q")
            keypoints = r.raw(n * KEYPOINT_BYTES)[:kept * KEYPOINT_BYTES]
            read_pairs(r)
            r.take("q")
            first = (struct.pack("<qqd", kf_id, frame_id, stamp) + pose +
                     struct.pack("<Q", kept) + keypoints + pairs([(kf_id + 1, kept)]) +
                     struct.pack("<q", -1))
            second = (struct.pack("<qqd", kf_id + 1, frame_id + 1, stamp + 0.033) + pose +
                      struct.pack("<Q", kept) + keypoints + pairs([(kf_id, kept)]) +
                      struct.pack("<q", kf_id))
            out_sections.append((tag, struct.pack("<Q", 2) + first + second))
        elif name == b"MPNT":
            points = []
            for _ in range(r.take("Q")):
                pid = r.take("q")
                position = r.raw(24)
                ref, visible, found = r.take("qii")
                observations = read_pairs(r)
                seen = [(k, i) for k, i in observations if i < kept]
                if seen:
                    k, i = seen[0]
                    points.append(struct.pack("<q", pid) + position +
                                  struct.pack("<qii", ref, visible, found) +
                                  pairs([(k, i), (k + 1, i)]))
            out_sections.append((tag, struct.pack("<Q", len(points)) + b"".join(points)))
        elif name == b"DENS":
            anchors = r.take("Q")
            anchor_bytes = r.raw(anchors * 72)[:72]
            levels = []
            for _ in range(2):
                n = r.take("Q")
                voxels = [r.raw(VOXEL_BYTES) for _ in range(n)]
                chosen = [v for v in voxels if struct.unpack_from("<i", v)[0] == 0][:args.voxels]
                levels.append(struct.pack("<Q", len(chosen)) + b"".join(chosen))
            out_sections.append((tag, struct.pack("<Q", 1) + anchor_bytes + b"".join(levels)))
        else:
            out_sections.append((tag, payload))

    body = b"".join(struct.pack("<IQ", tag, len(p)) + p for tag, p in out_sections)
    length = 8 + 16 + len(body) + 4
    file = magic + struct.pack("<IIQ", version, len(out_sections), length) + body
    open(args.output, "wb").write(file + struct.pack("<I", zlib.crc32(file) & 0xffffffff))


if __name__ == "__main__":
    main()
