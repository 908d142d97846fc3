"""examples/python/run_folder.py reproduces `drvslam run --sequential` bit for bit."""
import os
import subprocess
import sys

import pytest


@pytest.mark.parametrize("segmenter, trajectory_format", [("none", "tum"), ("gt", "euroc")])
def test_example_matches_the_cli_byte_for_byte(cli, source_dir, sequence, tmp_path, segmenter,
                                               trajectory_format):
    options = ["--sequential", "--segmenter", segmenter, "--dense", "off",
               "--trajectory-format", trajectory_format]
    subprocess.run([cli, "run", "--dataset", str(sequence), "--out", str(tmp_path / "cli")] +
                   options, check=True, capture_output=True)
    example = os.path.join(source_dir, "examples", "python", "run_folder.py")
    done = subprocess.run([sys.executable, example, str(sequence), "--out",
                           str(tmp_path / "python")] + options,
                          check=True, capture_output=True, text=True)
    assert "frames: 60" in done.stdout, done.stdout
    extension = ".csv" if trajectory_format == "euroc" else ".txt"
    for name in ("CameraTrajectory" + extension, "TrackedCameraTrajectory" + extension,
                 "OnlineCameraTrajectory" + extension, "KeyFrameTrajectory" + extension):
        cli_bytes = (tmp_path / "cli" / name).read_bytes()
        python_bytes = (tmp_path / "python" / name).read_bytes()
        assert len(cli_bytes.splitlines()) > 5, name  # keyframes too, not just headers
        assert python_bytes == cli_bytes, name
