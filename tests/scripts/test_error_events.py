"""scripts/error_events.py on a run whose error is known: white noise on top of a slow drift.

The estimate is the ground-truth path plus a slow sway (the drift) plus independent noise per
frame. The script must find the noise's sigma from the second differences, and averaging over a
window must leave about the sway alone. Frames left out of the estimate (skipped, as in a realtime
run) must not be read as noise.
"""
import json
import math
import os
import random
import re
import subprocess
import sys

SCRIPT = os.path.join(os.environ.get("DRVSLAM_SOURCE_DIR", "."), "scripts", "error_events.py")
FRAMES = 450
PERIOD = 1.0 / 30.0
NOISE_M = 0.004
SWAY_M = 0.01


def truth_position(i, speed):
    """A handheld-like path at about `speed` m/s: far from constant velocity only slowly."""
    t = i * PERIOD
    return [speed * t, 0.1 * math.sin(0.8 * t), 0.05 * math.cos(0.5 * t)]


def write_files(tmp_path, truth_lines, estimate_lines, log_lines):
    """The run folder the script reads, with an identity alignment in eval.json."""
    (tmp_path / "truth.txt").write_text("\n".join(truth_lines) + "\n")
    (tmp_path / "CameraTrajectory.txt").write_text("\n".join(estimate_lines) + "\n")
    (tmp_path / "frames.tsv").write_text("\n".join(log_lines) + "\n")
    identity = {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "translation": [0, 0, 0],
                "scale": 1.0}
    (tmp_path / "eval.json").write_text(json.dumps({"alignment": identity}))


def write_run(tmp_path, skipped=(), speed=0.3):
    rng = random.Random(7)
    truth_lines, estimate_lines, log_lines = [], [], ["frame\ttimestamp\ttracked\tkeyframe"]
    for i in range(FRAMES):
        stamp = 1000.0 + i * PERIOD
        g = truth_position(i, speed)
        truth_lines.append("%.6f %.9f %.9f %.9f 0 0 0 1" % (stamp, *g))
        # The noise is drawn for every frame, so a skipped frame leaves the others' unchanged.
        noise = [rng.gauss(0.0, NOISE_M) for _ in range(3)]
        if i in skipped:
            continue
        sway = SWAY_M * math.sin(2 * math.pi * i / 150.0)
        e = [g[0] + sway + noise[0], g[1] + noise[1], g[2] + noise[2]]
        estimate_lines.append("%.6f %.9f %.9f %.9f 0 0 0 1" % (stamp, *e))
        log_lines.append("%d\t%.6f\t1\t0" % (i + 1, stamp))
    write_files(tmp_path, truth_lines, estimate_lines, log_lines)


def script_output(tmp_path):
    return subprocess.run([sys.executable, SCRIPT, str(tmp_path), str(tmp_path / "truth.txt")],
                          capture_output=True, text=True, check=True).stdout


def run_script(tmp_path):
    stdout = script_output(tmp_path)
    found = re.search(r"ATE RMSE ([\d.]+) cm", stdout)
    split = re.search(r"per-frame noise ([\d.]+) cm \(second difference RMS ([\d.]+) cm, "
                      r"ground truth's ([\d.]+) cm\); averaged over 9 frames: ATE ([\d.]+) cm",
                      stdout)
    assert found and split, stdout
    noise, jitter, truth_jitter, slow = (float(v) for v in split.groups())
    return float(found.group(1)), noise, jitter, truth_jitter, slow


def test_splits_per_frame_noise_from_slow_error(tmp_path):
    write_run(tmp_path)
    ate, noise, jitter, truth_jitter, slow = run_script(tmp_path)
    # White noise of sigma per axis: a 3-D norm of sigma * sqrt(3), so about 0.69 cm here.
    expected_noise_cm = 100 * NOISE_M * math.sqrt(3)
    assert abs(noise - expected_noise_cm) < 0.08 * expected_noise_cm
    assert abs(jitter - math.sqrt(6) * expected_noise_cm) < 0.1 * math.sqrt(6) * expected_noise_cm
    assert truth_jitter < 0.05
    # The sway's RMS is SWAY_M / sqrt(2), 0.71 cm; averaging 9 frames leaves a third of the noise.
    sway_cm = 100 * SWAY_M / math.sqrt(2)
    assert ate > 0.9
    assert abs(slow - sway_cm) < 0.12


def test_skipped_frames_are_not_read_as_noise(tmp_path):
    # A brisk walk: across a skipped frame the camera moves 4 cm more than between two frames.
    write_run(tmp_path, skipped=set(range(20, FRAMES, 25)), speed=1.2)
    _, noise, jitter, truth_jitter, _ = run_script(tmp_path)
    expected_noise_cm = 100 * NOISE_M * math.sqrt(3)
    assert abs(noise - expected_noise_cm) < 0.08 * expected_noise_cm
    # Neither path's second difference spans a gap.
    assert abs(jitter - math.sqrt(6) * expected_noise_cm) < 0.1 * math.sqrt(6) * expected_noise_cm
    assert truth_jitter < 0.05


def write_run_with_people(tmp_path, people_from, free_error_m, busy_error_m):
    """A run whose frames from `people_from` on have two people in view (frame-log `objects`):
    the error is free_error_m before them and busy_error_m with them, its sign alternating."""
    truth_lines, estimate_lines = [], []
    log_lines = ["frame\ttimestamp\ttracked\tkeyframe\tobjects"]
    for i in range(FRAMES):
        stamp = 1000.0 + i * PERIOD
        g = truth_position(i, 0.3)
        truth_lines.append("%.6f %.9f %.9f %.9f 0 0 0 1" % (stamp, *g))
        people = 2 if i >= people_from else 0
        error = (busy_error_m if people else free_error_m) * (1 if i % 2 else -1)
        estimate_lines.append("%.6f %.9f %.9f %.9f 0 0 0 1" % (stamp, g[0], g[1] + error, g[2]))
        log_lines.append("%d\t%.6f\t1\t0\t%d" % (i + 1, stamp, people))
    write_files(tmp_path, truth_lines, estimate_lines, log_lines)


def test_error_split_by_people_in_view(tmp_path):
    write_run_with_people(tmp_path, people_from=200, free_error_m=0.01, busy_error_m=0.03)
    stdout = script_output(tmp_path)
    split = re.search(r"without potentially-moving objects in view: (\d+), RMS error ([\d.]+) cm; "
                      r"with them: (\d+), RMS error ([\d.]+) cm", stdout)
    assert split, stdout
    free, free_cm, busy, busy_cm = split.groups()
    assert (int(free), int(busy)) == (200, FRAMES - 200)
    assert abs(float(free_cm) - 1.0) < 0.01
    assert abs(float(busy_cm) - 3.0) < 0.01


def test_no_split_without_an_objects_column(tmp_path):
    write_run(tmp_path)
    assert "potentially-moving" not in script_output(tmp_path)


def test_reports_the_poses_as_tracked_beside_a_smoothed_trajectory(tmp_path):
    # The run's saved trajectory has no noise (as if smoothed); the poses as tracked beside it
    # carry the noise, and the script reports it from them.
    write_run(tmp_path)
    noisy = (tmp_path / "CameraTrajectory.txt").read_text()
    (tmp_path / "TrackedCameraTrajectory.txt").write_text(noisy)
    clean = []
    for i in range(FRAMES):
        g = truth_position(i, 0.3)
        clean.append("%.6f %.9f %.9f %.9f 0 0 0 1" % (1000.0 + i * PERIOD, *g))
    (tmp_path / "CameraTrajectory.txt").write_text("\n".join(clean) + "\n")
    stdout = script_output(tmp_path)
    found = re.search(r"as tracked \(TrackedCameraTrajectory.txt\): ATE ([\d.]+) cm, per-frame "
                      r"noise ([\d.]+) cm", stdout)
    assert found, stdout
    ate, noise = (float(v) for v in found.groups())
    expected_noise_cm = 100 * NOISE_M * math.sqrt(3)
    assert abs(noise - expected_noise_cm) < 0.08 * expected_noise_cm
    assert ate > 0.9
    assert re.search(r"ATE RMSE 0.00 cm", stdout), stdout


def test_no_tracked_line_without_the_tracked_file(tmp_path):
    write_run(tmp_path)
    assert "as tracked" not in script_output(tmp_path)
