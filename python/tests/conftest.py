"""Shared fixtures: the built CLI and one short synthetic sequence it generates.

CTest (python/CMakeLists.txt) sets PYTHONPATH to the built module and DRVSLAM_CLI /
DRVSLAM_SOURCE_DIR; run by hand:
    DRVSLAM_CLI=build/bin/drvslam DRVSLAM_SOURCE_DIR=. PYTHONPATH=build/python \
        /usr/bin/python3 -m pytest python/tests
"""
import os
import subprocess

import numpy as np
import pytest

FRAMES = 60


def _required(name):
    value = os.environ.get(name)
    if not value or not os.path.exists(value):
        message = f"{name} is not set to an existing path (got {value!r})"
        if os.environ.get("DRVSLAM_REQUIRE_TEST_DATA", "") not in ("", "0"):
            pytest.fail(message + " and DRVSLAM_REQUIRE_TEST_DATA is set")
        pytest.skip(message)
    return value


@pytest.fixture(scope="session")
def cli():
    return _required("DRVSLAM_CLI")


@pytest.fixture(scope="session")
def source_dir():
    return _required("DRVSLAM_SOURCE_DIR")


@pytest.fixture(scope="session")
def sequence(cli, tmp_path_factory):
    """walking_xyz, 60 frames, seed 1: people walk through a room (masks and ground truth)."""
    folder = tmp_path_factory.mktemp("sequence") / "walking_xyz"
    subprocess.run([cli, "synth", "--scenario", "walking_xyz", "--frames", str(FRAMES), "--seed",
                    "1", "--out", str(folder)], check=True, capture_output=True)
    return folder


def read_tum(path):
    """(timestamps (N,), T_wc (N, 4, 4)) of a TUM trajectory file."""
    rows = np.loadtxt(path, comments="#", ndmin=2)
    poses = np.tile(np.eye(4), (len(rows), 1, 1))
    for pose, (_, tx, ty, tz, qx, qy, qz, qw) in zip(poses, rows):
        pose[:3, :3] = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw),
                         2 * (qx * qz + qy * qw)],
                        [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz),
                         2 * (qy * qz - qx * qw)],
                        [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw),
                         1 - 2 * (qx * qx + qy * qy)]]
        pose[:3, 3] = [tx, ty, tz]
    return rows[:, 0], poses


def sequence_frames(folder):
    """(timestamp, rgb path, depth path) from a synthetic sequence's associations.txt."""
    frames = []
    with open(folder / "associations.txt") as lines:
        for line in lines:
            fields = line.split()
            if fields and not fields[0].startswith("#"):
                frames.append((float(fields[0]), folder / fields[1], folder / fields[3]))
    return frames
