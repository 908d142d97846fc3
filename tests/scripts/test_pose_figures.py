"""scripts/pose_figures.py on a run folder whose errors are known.

The saved trajectory is the ground truth moved rigidly (ATE 0, the ground truth's jitter); the
causal one adds +-2 mm sideways, alternating from frame to frame (ATE 2 mm, second differences
of 8 mm), and its velocity file holds the path's exact velocity in the camera frame (RMSE near 0:
central differences of a smooth path); the as-tracked one is the saved one with frames 100-109
left out (the jitter skips the gap).
"""
import math
import os
import subprocess
import sys
import json

SCRIPT = os.path.join(os.environ.get("DRVSLAM_SOURCE_DIR", "."), "scripts", "pose_figures.py")
PERIOD = 1.0 / 30.0
FRAMES = 300
SIDE_M = 0.002


def pose(t):
    """Centre and yaw of a camera walking at 0.3 m/s and panning slowly."""
    return [0.3 * t, 0.05 * math.sin(t), 0.0], 0.2 * math.sin(0.5 * t)


def quaternion(yaw):  # about z: x y z w
    return [0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]


def line(t, centre, yaw):
    return " ".join("%.9f" % v for v in [t] + centre + quaternion(yaw)) + "\n"


def test_figures_of_known_errors(tmp_path):
    gt, saved, causal, tracked, velocity = [], [], [], [], []
    moved = 0.7  # the estimate's world is the ground truth's turned about z and shifted
    for i in range(FRAMES):
        t = 100.0 + i * PERIOD
        centre, yaw = pose(t - 100.0)
        gt.append(line(t, centre, yaw))
        c, s = math.cos(-moved), math.sin(-moved)
        local = [c * centre[0] - s * centre[1] + 1.0, s * centre[0] + c * centre[1] - 2.0,
                 centre[2] + 0.5]
        saved.append(line(t, local, yaw - moved))
        side = SIDE_M if i % 2 else -SIDE_M
        causal.append(line(t, [local[0], local[1], local[2] + side], yaw - moved))
        if not 100 <= i < 110:
            tracked.append(line(t, local, yaw - moved))
        # The exact velocity, in the camera frame (turned by yaw about z).
        tt = t - 100.0
        vx, vy = 0.3, 0.05 * math.cos(tt)
        cy, sy = math.cos(yaw), math.sin(yaw)
        velocity.append("%.9f %.9f %.9f 0 0 0 %.9f\n" % (t, cy * vx + sy * vy, -sy * vx + cy * vy,
                                                         0.1 * math.cos(0.5 * tt)))
    (tmp_path / "groundtruth.txt").write_text("".join(gt))
    run = tmp_path / "run"
    run.mkdir()
    (run / "CameraTrajectory.txt").write_text("".join(saved))
    (run / "OnlineCameraTrajectory.txt").write_text("".join(causal))
    (run / "TrackedCameraTrajectory.txt").write_text("".join(tracked))
    (run / "OnlineCameraVelocity.txt").write_text("# t vx vy vz wx wy wz\n" + "".join(velocity))
    out = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "groundtruth.txt"), str(run),
                          "--json"], check=True, capture_output=True, text=True).stdout
    f = json.loads(out)
    assert f["saved"]["ate_m"] < 1e-6
    assert abs(f["saved"]["jitter_m"] - f["groundtruth_jitter_m"]) < 1e-6
    assert abs(f["causal"]["ate_m"] - SIDE_M) < 1e-4
    assert abs(f["causal"]["jitter_m"] - 4 * SIDE_M) < 1e-4
    # Across the gap the centre moves 10 cm: a second difference there would be a jump.
    assert abs(f["tracked"]["jitter_m"] - f["groundtruth_jitter_m"]) < 1e-5
    assert f["velocity"]["frames"] == FRAMES - 2
    assert f["velocity"]["linear_rmse_mps"] < 1e-3
    assert f["velocity"]["angular_rmse_radps"] < 1e-3
