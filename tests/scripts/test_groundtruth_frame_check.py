"""scripts/groundtruth_frame_check.py on trajectories whose body frames differ by a known transform.

A smooth camera path is written as the estimate; the ground truth is the pose of a body fixed to
the camera (rotated by a known angle, offset by a known lever arm), as motion-capture markers are.
The script must find that rotation, place the camera where the lever arm says, and find nothing
when the two are the same frame.
"""
import os
import re
import subprocess
import sys

import numpy as np

SCRIPT = os.path.join(os.environ.get("DRVSLAM_SOURCE_DIR", "."), "scripts",
                      "groundtruth_frame_check.py")


def axis_angle(axis, degrees):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = np.radians(degrees)
    return np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K


def quaternion(R):
    """(x, y, z, w) of a rotation matrix, by the largest of the four squared components."""
    w2, x2, y2, z2 = (1 + np.trace(R)) / 4, (1 + R[0, 0] - R[1, 1] - R[2, 2]) / 4, \
        (1 - R[0, 0] + R[1, 1] - R[2, 2]) / 4, (1 - R[0, 0] - R[1, 1] + R[2, 2]) / 4
    largest = np.argmax([w2, x2, y2, z2])
    if largest == 0:
        w = np.sqrt(w2)
        return [(R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w),
                (R[1, 0] - R[0, 1]) / (4 * w), w]
    if largest == 1:
        x = np.sqrt(x2)
        return [x, (R[0, 1] + R[1, 0]) / (4 * x), (R[0, 2] + R[2, 0]) / (4 * x),
                (R[2, 1] - R[1, 2]) / (4 * x)]
    if largest == 2:
        y = np.sqrt(y2)
        return [(R[0, 1] + R[1, 0]) / (4 * y), y, (R[1, 2] + R[2, 1]) / (4 * y),
                (R[0, 2] - R[2, 0]) / (4 * y)]
    z = np.sqrt(z2)
    return [(R[0, 2] + R[2, 0]) / (4 * z), (R[1, 2] + R[2, 1]) / (4 * z), z,
            (R[1, 0] - R[0, 1]) / (4 * z)]


def camera_path(frames=300):
    """A handheld-like path: a slow sweep with wobble about all three axes."""
    poses = []
    for i in range(frames):
        t = i / 30.0
        R = axis_angle([0, 1, 0], 20 * np.sin(0.7 * t)) @ axis_angle([1, 0, 0], 8 * np.sin(1.3 * t)) \
            @ axis_angle([0, 0, 1], 5 * np.sin(2.1 * t))
        p = np.array([0.4 * np.sin(0.5 * t), 0.05 * np.sin(1.7 * t), 0.2 * t])
        poses.append((1000.0 + t, R, p))
    return poses


def write_tum(path, poses):
    with open(path, "w") as f:
        for stamp, R, p in poses:
            f.write(f"{stamp:.6f} {p[0]:.9f} {p[1]:.9f} {p[2]:.9f} "
                    + " ".join(f"{v:.12f}" for v in quaternion(R)) + "\n")


def run_check(tmp_path, body_rotation, lever, lever_argument=None):
    camera = camera_path()
    # The body's pose: the camera's composed with the fixed camera-to-body transform.
    body = [(s, R @ body_rotation, p + R @ lever) for s, R, p in camera]
    write_tum(tmp_path / "estimate.txt", camera)
    write_tum(tmp_path / "truth.txt", body)
    command = [sys.executable, SCRIPT, str(tmp_path / "estimate.txt"), str(tmp_path / "truth.txt")]
    if lever_argument is not None:
        command += ["--lever"] + [str(v) for v in lever_argument]
    result = subprocess.run(command, capture_output=True, text=True, check=True)
    numbers = lambda pattern: [float(v) for v in re.search(pattern, result.stdout).groups()]
    return {
        "rotation": numbers(r"fitted body rotation: ([\d.]+) deg")[0],
        "errors": numbers(r"median: ([\d.]+) deg as given, ([\d.]+) deg with"),
        "ate": numbers(r"ATE: ([\d.]+) cm against the ground truth as given")[0],
        "ate_lever": (numbers(r"ATE: ([\d.]+) cm against the camera centres")[0]
                      if lever_argument is not None else None),
    }


def test_finds_the_body_rotation_and_the_lever_arm(tmp_path):
    body_rotation = axis_angle([0.2, 1.0, -0.3], 150)
    lever = np.array([0.03, -0.02, 0.015])
    # The camera centre seen from the body: back along the lever arm, in the body's axes.
    found = run_check(tmp_path, body_rotation, lever, -body_rotation.T @ lever)
    assert abs(found["rotation"] - 150) < 0.5
    before, after = found["errors"]
    assert before > 1.0 and after < 0.01
    assert found["ate"] > 0.5 and found["ate_lever"] < 0.001


def test_finds_nothing_when_the_ground_truth_is_the_camera(tmp_path):
    found = run_check(tmp_path, np.eye(3), np.zeros(3))
    assert found["rotation"] < 0.01
    assert found["errors"][0] < 0.001
    assert found["ate"] < 0.001


def test_a_missing_file_is_one_error_naming_it(tmp_path):
    result = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "none.txt"),
                             str(tmp_path / "none.txt")], capture_output=True, text=True)
    assert result.returncode != 0
    assert "none.txt" in result.stderr and "Traceback" not in result.stderr


def fit_lever(tmp_path, lever, noise_m=0.0):
    """Runs --fit-lever on a ground truth that follows a point `lever` (camera frame) from the
    camera centre; the estimate is the camera's path, with seeded position noise."""
    camera = camera_path()
    body = [(s, R, p + R @ lever) for s, R, p in camera]
    noise = np.random.default_rng(7).normal(0.0, noise_m, (len(camera), 3))
    estimate = [(s, R, p + n) for (s, R, p), n in zip(camera, noise)]
    write_tum(tmp_path / "estimate.txt", estimate)
    write_tum(tmp_path / "truth.txt", body)
    result = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "estimate.txt"),
                             str(tmp_path / "truth.txt"), "--fit-lever"],
                            capture_output=True, text=True, check=True)
    fitted = re.search(r"fitted lever arm \(camera frame\): \[\s*([-\d.]+)\s+([-\d.]+)\s+([-\d.]+)\] "
                       r"cm, [\d.]+ cm long; ATE ([\d.]+) cm", result.stdout)
    halves = re.findall(r"half: ATE ([\d.]+) cm as given, ([\d.]+) cm with", result.stdout)
    return ([float(v) / 100 for v in fitted.groups()[:3]], float(fitted.group(4)),
            [(float(a), float(b)) for a, b in halves])


def test_fits_the_lever_arm_the_ground_truth_follows(tmp_path):
    lever = np.array([0.016, 0.002, -0.013])
    fitted, ate_with, halves = fit_lever(tmp_path, lever, noise_m=0.002)
    assert np.linalg.norm(np.array(fitted) - lever) < 0.002
    # The 2 mm of noise per axis is what is left: sqrt(3) * 0.2 cm.
    assert ate_with < 0.4
    assert len(halves) == 2
    # Each half, with the lever fitted on the other, falls to the noise (0.35 cm).
    for plain, with_other_half in halves:
        assert plain > 0.4 and with_other_half < 0.37


def test_fits_no_lever_arm_where_there_is_none(tmp_path):
    fitted, _, halves = fit_lever(tmp_path, np.zeros(3), noise_m=0.002)
    assert np.linalg.norm(fitted) < 0.003
    # The other half's error gains nothing from a lever fitted to noise.
    for plain, with_other_half in halves:
        assert with_other_half > plain - 0.02
