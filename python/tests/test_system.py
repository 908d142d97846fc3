"""drvslam.System: poses and states from numpy frames, trajectories, files, and bad input."""
import os
import sys
import threading
import time

import numpy as np
import pytest

import drvslam
from conftest import read_tum, sequence_frames

TRACKED = 15


def make_system(sequence, **overrides):
    options = dict(dataset=str(sequence), sequential=True, segmenter="gt", dense=False)
    options.update(overrides)
    return drvslam.System(str(sequence / "settings.yaml"), **options)


def load(frame):
    timestamp, rgb, depth = frame
    return drvslam.read_image(str(rgb)), drvslam.read_image(str(depth)), timestamp


def test_track_rgbd_returns_pose_and_state(sequence):
    system = make_system(sequence)
    assert system.oracle and system.segmenter.startswith("gt")
    gt_stamps, gt_poses = read_tum(sequence / "groundtruth.txt")
    frames = sequence_frames(sequence)[:TRACKED]
    results = [system.track_rgbd(*load(frame)) for frame in frames]

    first = results[0]
    assert first.frame_id == 0 and first.keyframe_id == 0
    assert first.state == drvslam.TrackingState.OK and first.pose_valid
    assert first.timestamp == frames[0][0]
    np.testing.assert_array_equal(first.T_wc, np.eye(4))  # the first frame is the map's origin
    origin = np.linalg.inv(gt_poses[np.searchsorted(gt_stamps, frames[0][0])])
    for k, (result, frame) in enumerate(zip(results, frames)):
        assert result.frame_id == k
        assert result.state == drvslam.TrackingState.OK, result
        assert result.pose_valid and result.inliers > 50
        assert result.quality == drvslam.LocalizationQuality.VERIFIED, result
        assert result.T_wc.shape == (4, 4) and result.T_wc.dtype == np.float64
        np.testing.assert_allclose(result.T_cw @ result.T_wc, np.eye(4), atol=1e-9)
        # Against the ground truth moved into the map's frame (frame 0 at the origin).
        truth = origin @ gt_poses[np.searchsorted(gt_stamps, frame[0])]
        assert np.linalg.norm(result.T_wc[:3, 3] - truth[:3, 3]) < 0.02, k
        # T_wc is the causal pose; the pose as tracked is beside it, a few millimetres away.
        np.testing.assert_allclose(result.T_cw_tracked @ result.T_wc_tracked, np.eye(4),
                                   atol=1e-9)
        assert np.linalg.norm(result.T_wc[:3, 3] - result.T_wc_tracked[:3, 3]) < 0.01, k
        assert result.linear_velocity.shape == (3,) and result.angular_velocity.shape == (3,)
        assert result.pose_covariance.shape == (6, 6) and result.twist_covariance.shape == (6, 6)
        if k > 0:
            # Both covariances are symmetric and positive definite after the first frame.
            for covariance in (result.pose_covariance, result.twist_covariance):
                np.testing.assert_allclose(covariance, covariance.T, atol=1e-15)
                assert np.linalg.eigvalsh(covariance).min() > 0, k
    # The camera moves through the sequence: the velocity says so (centimetres per second).
    speeds = [np.linalg.norm(result.linear_velocity) for result in results[TRACKED // 2:]]
    assert np.median(speeds) > 0.01, speeds
    system.shutdown()
    online_stamps, online_poses = system.online_trajectory()
    np.testing.assert_array_equal(online_stamps, [frame[0] for frame in frames])
    np.testing.assert_array_equal(online_poses[-1], results[-1].T_wc)

    stamps, poses = system.trajectory()
    assert stamps.shape == (TRACKED,) and poses.shape == (TRACKED, 4, 4)
    np.testing.assert_array_equal(stamps, [frame[0] for frame in frames])
    # The saved trajectory is smoothed; the tracked one keeps the frames and stays within the
    # per-frame scatter of it.
    tracked_stamps, tracked_poses = system.tracked_trajectory()
    np.testing.assert_array_equal(tracked_stamps, stamps)
    assert np.abs(tracked_poses[:, :3, 3] - poses[:, :3, 3]).max() < 0.01
    key_stamps, key_poses = system.keyframe_trajectory()
    assert 1 <= len(key_stamps) <= TRACKED and key_poses.shape == (len(key_stamps), 4, 4)
    stats = system.stats()
    assert stats["frames"] == TRACKED and stats["tracked"] == TRACKED


def test_raw_uint16_depth_tracks_as_float_metres(sequence):
    """uint16 depth is divided by DepthMapFactor in double and rounded once to float32, as the
    dataset reader does: float32 metres computed that way give the same trajectory bit for bit."""
    frames = sequence_frames(sequence)[:8]
    trajectories = []
    for as_metres in (False, True):
        system = make_system(sequence)
        for frame in frames:
            bgr, depth, timestamp = load(frame)
            assert depth.dtype == np.uint16
            if as_metres:
                depth = (depth.astype(np.float64) / system.depth_map_factor).astype(np.float32)
            system.track_rgbd(bgr, depth, timestamp)
        system.shutdown()
        trajectories.append(system.trajectory())
    np.testing.assert_array_equal(trajectories[0][0], trajectories[1][0])
    np.testing.assert_array_equal(trajectories[0][1], trajectories[1][1])


def expect_error(call, *needles):
    with pytest.raises(drvslam.Error) as raised:
        call()
    for needle in needles:
        assert needle in str(raised.value), str(raised.value)
    assert isinstance(raised.value, ValueError)


def test_bad_input_raises_and_changes_nothing(sequence):
    system = make_system(sequence)
    frames = sequence_frames(sequence)
    bgr, depth, timestamp = load(frames[0])
    assert system.track_rgbd(bgr, depth, timestamp).frame_id == 0
    bgr, depth, timestamp = load(frames[1])
    track = system.track_rgbd
    expect_error(lambda: track(bgr.astype(np.float64), depth, timestamp),
                 "bgr has dtype float64; expected uint8")
    expect_error(lambda: track(np.zeros(bgr.shape[:2] + (4,), np.uint8), depth, timestamp),
                 "bgr has shape (480, 640, 4)")
    expect_error(lambda: track(bgr[:, ::-1], depth, timestamp), "bgr is not C-contiguous")
    expect_error(lambda: track(bgr, depth.T, timestamp), "depth is not C-contiguous")
    expect_error(lambda: track(bgr, depth.astype(np.int32), timestamp),
                 "depth has dtype int32; expected float32 (metres) or uint16")
    expect_error(lambda: track(bgr, depth[None], timestamp), "depth has shape (1, 480, 640)")
    # The library's own checks come through with its message.
    expect_error(lambda: track(bgr[:240].copy(), depth[:240].copy(), timestamp),
                 "TrackRGBD: colour image is 640x240; Camera.width/height is 640x480")
    expect_error(lambda: track(bgr, depth, float("nan")), "timestamp is nan")
    # None of that counted as a frame: the next good frame is frame 1, tracked.
    result = system.track_rgbd(bgr, depth, timestamp)
    assert result.frame_id == 1 and result.state == drvslam.TrackingState.OK
    expect_error(lambda: system.write_trajectories("unused", "csv"),
                 "format = 'csv' must be tum, kitti or euroc")
    system.shutdown()


def test_bad_settings_and_options_raise(sequence, tmp_path):
    missing = str(tmp_path / "missing.yaml")
    expect_error(lambda: drvslam.System(missing), missing)
    bad = tmp_path / "bad.yaml"
    bad.write_text("%YAML:1.0\nCamera.fx: -5\n")
    expect_error(lambda: drvslam.System(str(bad)), "Camera.fx")
    expect_error(lambda: drvslam.System(segmenter="magic"),
                 "segmenter = 'magic' must be yolo, masks, gt or none")
    expect_error(lambda: drvslam.System(segmenter="yolo"), "needs --model")


def test_writes_trajectories_as_the_cli_formats(sequence, tmp_path):
    system = make_system(sequence)
    frames = sequence_frames(sequence)[:5]
    for frame in frames:
        system.track_rgbd(*load(frame))
    system.shutdown()
    assert system.write_trajectories(str(tmp_path / "tum")) == str(
        tmp_path / "tum" / "CameraTrajectory.txt")
    stamps, poses = read_tum(tmp_path / "tum" / "CameraTrajectory.txt")
    np.testing.assert_array_equal(stamps, [frame[0] for frame in frames])
    np.testing.assert_allclose(poses, system.trajectory()[1], atol=2e-9)
    _, tracked = read_tum(tmp_path / "tum" / "TrackedCameraTrajectory.txt")
    np.testing.assert_allclose(tracked, system.tracked_trajectory()[1], atol=2e-9)

    kitti = system.write_trajectories(str(tmp_path / "kitti"), "kitti")
    rows = np.loadtxt(kitti, ndmin=2)
    assert rows.shape == (5, 12)
    np.testing.assert_allclose(rows.reshape(5, 3, 4), system.trajectory()[1][:, :3], atol=1e-9)
    times = np.loadtxt(tmp_path / "kitti" / "CameraTrajectory_times.txt")
    np.testing.assert_array_equal(times, stamps)

    euroc = system.write_trajectories(str(tmp_path / "euroc"), "euroc")
    assert euroc.endswith("CameraTrajectory.csv")
    with open(euroc) as lines:
        header, first = lines.readline(), lines.readline()
    assert header.startswith("#timestamp, p_RS_R_x [m]")
    assert first.split(",")[0] == str(round(frames[0][0] * 1e6) * 1000)


def test_tracking_releases_the_gil(sequence):
    """With a huge switch interval, another Python thread runs only while the main thread has
    released the GIL: its counter advances during track_rgbd only if tracking released it."""
    system = make_system(sequence)
    frames = [load(frame) for frame in sequence_frames(sequence)[:6]]
    counter = [0]
    stop = threading.Event()

    def count():
        while not stop.is_set():
            counter[0] += 1
            time.sleep(0)  # gives the GIL back at once when the main thread wants it

    interval = sys.getswitchinterval()
    worker = threading.Thread(target=count)
    advanced = 0
    try:
        sys.setswitchinterval(100.0)
        worker.start()
        for frame in frames:
            before = counter[0]
            system.track_rgbd(*frame)
            advanced += counter[0] - before
    finally:
        stop.set()
        sys.setswitchinterval(interval)
        worker.join()
    system.shutdown()
    assert advanced > 0


def test_read_image_and_associate(sequence, tmp_path):
    _, rgb, depth = sequence_frames(sequence)[0]
    colour = drvslam.read_image(str(rgb))
    assert colour.shape == (480, 640, 3) and colour.dtype == np.uint8
    assert drvslam.read_image(str(depth)).dtype == np.uint16
    missing = str(tmp_path / "none.png")
    expect_error(lambda: drvslam.read_image(missing), missing)
    # Closest pairs first, each stamp used once, sorted by the first list.
    assert drvslam.associate([1.0, 2.0, 3.0], [2.005, 0.99, 5.0]) == [(0, 1), (1, 0)]
    assert drvslam.associate([1.0], [1.5], max_difference=0.6) == [(0, 0)]


def test_saved_map_is_loaded_and_localized_in(sequence, tmp_path):
    mapper = make_system(sequence)
    frames = sequence_frames(sequence)[:TRACKED]
    for frame in frames:
        mapper.track_rgbd(*load(frame))
    mapper.shutdown()
    path = tmp_path / "map.bin"
    mapper.save_map(str(path))
    assert path.stat().st_size > 1000

    localizer = make_system(sequence, load_map=str(path), localization=True)
    # Found again: tentative until it has tracked three frames in a row against the map.
    results = [localizer.track_rgbd(*load(frame)) for frame in frames[-3:]]
    assert [r.state for r in results] == [drvslam.TrackingState.OK] * 3
    assert [r.quality for r in results] == [
        drvslam.LocalizationQuality.TENTATIVE,
        drvslam.LocalizationQuality.TENTATIVE,
        drvslam.LocalizationQuality.VERIFIED,
    ]
    # Relocalized in the saved map's frame: the pose the mapper had for that frame.
    _, mapped = mapper.trajectory()
    np.testing.assert_allclose(results[-1].T_wc[:3, 3], mapped[-1][:3, 3], atol=0.01)
    with pytest.raises(drvslam.Error, match="map"):
        make_system(sequence, load_map=str(tmp_path / "missing.bin"))
