#!/usr/bin/env python3
"""Does a ground truth give the camera's pose, or the pose of something fixed to the camera?

Usage: groundtruth_frame_check.py ESTIMATE GROUND_TRUTH [--step 10] [--lever X Y Z] [--fit-lever]

Both files are TUM trajectories (`t tx ty tz qx qy qz qw`); ESTIMATE is a run's
CameraTrajectory.txt. Motion-capture ground truth often gives the pose of the markers (the Bonn
RGB-D Dynamic dataset does). Then the camera's relative rotations are the ground truth's seen from
another body frame, and the error between them grows with how fast the camera turns. This script
fits that fixed body rotation to the relative rotations over --step frames and prints the
residual before and after, and the ATE against the ground truth as given and, with --lever,
against the camera centres that lever arm gives.

With --fit-lever it also fits the point the ground truth follows, as an offset from the
estimated camera centre in the camera's frame: the offset that, added to every estimated pose,
brings the trajectory closest to the ground truth after the rigid alignment. A fit with three
free numbers always lowers the error a little, so the offset is fitted on each half of the
trajectory in turn and judged on the other half: only an offset that lowers the other half's
error too is something the ground truth holds, not noise fitted.
Needs numpy (Debian: python3-numpy, which scripts/install-deps.sh installs).
"""
import argparse
import sys

try:
    import numpy as np
except ImportError:
    sys.exit("error: groundtruth_frame_check.py needs numpy (Debian: apt install python3-numpy)")


def read_tum(path):
    rows = []
    try:
        with open(path) as f:
            for line in f:
                fields = line.split()
                if fields and not fields[0].startswith("#") and len(fields) >= 8:
                    rows.append([float(v) for v in fields[:8]])
    except (OSError, ValueError) as error:
        sys.exit(f"error: {path}: {error}")
    if len(rows) < 3:
        sys.exit(f"error: {path}: fewer than 3 poses")
    return np.array(rows)


def rotation(q):
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def rotation_vector(R):
    angle = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))
    if angle < 1e-9:
        return np.zeros(3)
    axis = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    return angle / (2 * np.sin(angle)) * axis


def kabsch(target, source):
    """The rotation R minimising sum |target_i - R source_i|^2."""
    U, _, Vt = np.linalg.svd(target.T @ source)
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
    return U @ D @ Vt


def associate(estimate, truth, max_dt=0.02):
    index = np.clip(np.searchsorted(truth[:, 0], estimate[:, 0]), 1, len(truth) - 1)
    earlier = np.abs(truth[index - 1, 0] - estimate[:, 0]) < np.abs(truth[index, 0] - estimate[:, 0])
    index = np.where(earlier, index - 1, index)
    near = np.abs(truth[index, 0] - estimate[:, 0]) < max_dt
    return estimate[near], truth[index[near]]


def ate_cm(estimate_xyz, truth_xyz):
    """RMSE after the rigid alignment of the estimate onto the truth (no scale)."""
    mean_e, mean_t = estimate_xyz.mean(0), truth_xyz.mean(0)
    R = kabsch(truth_xyz - mean_t, estimate_xyz - mean_e)
    aligned = (R @ (estimate_xyz - mean_e).T).T + mean_t
    return 100 * np.sqrt(((aligned - truth_xyz) ** 2).sum(1).mean())


def fit_lever(estimate_xyz, R_est, truth_xyz, rounds=50):
    """The offset l (camera frame, metres) minimising the aligned error of the points
    estimate_xyz_i + R_est_i l: alternately the alignment (Kabsch) and l (linear least squares)."""
    lever = np.zeros(3)
    for _ in range(rounds):
        moved = estimate_xyz + R_est @ lever
        mean_m, mean_t = moved.mean(0), truth_xyz.mean(0)
        R = kabsch(truth_xyz - mean_t, moved - mean_m)
        t = mean_t - R @ mean_m
        # R (x_i + R_i l) + t = y_i, for l: (R R_i) l = y_i - t - R x_i
        A = (R @ R_est).reshape(-1, 3)
        b = (truth_xyz - t - estimate_xyz @ R.T).reshape(-1)
        lever = np.linalg.lstsq(A, b, rcond=None)[0]
    return lever


def report_fitted_lever(estimate_xyz, R_est, truth_xyz, ate_given):
    lever = fit_lever(estimate_xyz, R_est, truth_xyz)
    ate_fitted = ate_cm(estimate_xyz + R_est @ lever, truth_xyz)
    print(f"fitted lever arm (camera frame): {np.array2string(100 * lever, precision=2)} cm, "
          f"{100 * np.linalg.norm(lever):.2f} cm long; ATE {ate_fitted:.3f} cm with it "
          f"(the offset alone: {np.sqrt(max(ate_given**2 - ate_fitted**2, 0.0)):.3f} cm)")
    half = len(estimate_xyz) // 2
    halves = [slice(0, half), slice(half, None)]
    for fitted_on, judged_on, name in ((halves[0], halves[1], "second"),
                                       (halves[1], halves[0], "first")):
        lever_half = fit_lever(estimate_xyz[fitted_on], R_est[fitted_on], truth_xyz[fitted_on])
        plain = ate_cm(estimate_xyz[judged_on], truth_xyz[judged_on])
        moved = estimate_xyz[judged_on] + R_est[judged_on] @ lever_half
        print(f"  {name} half: ATE {plain:.3f} cm as given, {ate_cm(moved, truth_xyz[judged_on]):.3f} "
              f"cm with the lever fitted on the other half "
              f"({np.array2string(100 * lever_half, precision=2)} cm)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("estimate")
    parser.add_argument("ground_truth")
    parser.add_argument("--step", type=int, default=10, help="frames between compared poses")
    parser.add_argument("--lever", type=float, nargs=3, metavar=("X", "Y", "Z"),
                        help="the camera centre in the ground truth's body frame, metres")
    parser.add_argument("--fit-lever", action="store_true",
                        help="fit the offset between the camera centre and the point the ground "
                        "truth follows, checked across the trajectory's two halves")
    args = parser.parse_args()
    if args.step < 1:
        sys.exit("error: --step must be at least 1")
    estimate, truth = associate(read_tum(args.estimate), read_tum(args.ground_truth))
    if len(estimate) <= args.step + 2:
        sys.exit(f"error: {args.estimate}: too few poses match {args.ground_truth} in time")
    R_est = [rotation(q) for q in estimate[:, 4:8]]
    R_gt = [rotation(q) for q in truth[:, 4:8]]
    pairs = range(len(R_est) - args.step)
    moved_est = np.array([rotation_vector(R_est[i].T @ R_est[i + args.step]) for i in pairs])
    moved_gt = np.array([rotation_vector(R_gt[i].T @ R_gt[i + args.step]) for i in pairs])
    # In body frames that differ by a fixed rotation X, relative rotation vectors differ by X.
    X = kabsch(moved_est, moved_gt)
    before = np.degrees(np.linalg.norm(moved_est - moved_gt, axis=1))
    after = np.degrees(np.linalg.norm(moved_est - (X @ moved_gt.T).T, axis=1))
    print(f"{len(estimate)} poses matched; relative rotations over {args.step} frames")
    print(f"ground truth turns {np.degrees(np.median(np.linalg.norm(moved_gt, axis=1))):.3f} deg "
          "(median)")
    print(f"fitted body rotation: {np.degrees(np.linalg.norm(rotation_vector(X))):.1f} deg")
    print(f"relative-rotation error, median: {np.median(before):.3f} deg as given, "
          f"{np.median(after):.3f} deg with the fitted body rotation")

    ate_given = ate_cm(estimate[:, 1:4], truth[:, 1:4])
    print(f"ATE: {ate_given:.3f} cm against the ground truth as given")
    if args.lever is not None:
        # The camera centre is the body's origin moved by the lever arm, in the body's frame.
        lever = np.array(args.lever)
        centres = truth[:, 1:4] + np.array([R @ lever for R in R_gt])
        ate_lever = ate_cm(estimate[:, 1:4], centres)
        print(f"ATE: {ate_lever:.3f} cm against the camera centres the lever arm gives")
    if args.fit_lever:
        report_fitted_lever(estimate[:, 1:4], np.array(R_est), truth[:, 1:4], ate_given)


if __name__ == "__main__":
    main()
