#!/usr/bin/env python3
"""Figures of one drvslam run folder against a TUM ground truth (issue 55); plain Python.

For each of the three trajectories (CameraTrajectory.txt: saved, smoothed after the run;
OnlineCameraTrajectory.txt: the causal poses TrackRGBD returned; TrackedCameraTrajectory.txt:
as tracked): ATE (RMSE of the centres after a rigid alignment, Horn's method, as
evaluate_ate.py) and jitter (RMS of the second difference of consecutive camera centres, over
triples whose intervals are at most 1.5x the median interval). Then the causal velocity
(OnlineCameraVelocity.txt, camera frame) against the ground truth's central differences, both in
the ground truth's world through the causal trajectory's alignment: linear (m/s) and angular
(rad/s) RMSE. The world-frame angular velocity does not depend on where on the rigid body the
ground truth's frame sits.

usage: scripts/pose_figures.py GROUNDTRUTH RUN_DIR [--json]
"""
import bisect
import json
import math
import sys


def read_tum(path):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                rows.append([float(x) for x in line.split()[:8]])
    return [r[0] for r in rows], [r[1:4] for r in rows], [r[4:8] for r in rows]


def sub(a, b): return [x - y for x, y in zip(a, b)]
def add(a, b): return [x + y for x, y in zip(a, b)]
def scale(a, s): return [x * s for x in a]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm2(a): return dot(a, a)
def matvec(m, v): return [dot(row, v) for row in m]
def transpose(m): return [list(r) for r in zip(*m)]
def matmul(a, b): return [[dot(row, col) for col in zip(*b)] for row in a]


def quat_to_matrix(q):  # x y z w
    n = math.sqrt(norm2(q))
    x, y, z, w = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def log_rotation(r):
    angle = math.acos(max(-1.0, min(1.0, (r[0][0] + r[1][1] + r[2][2] - 1) / 2)))
    if angle < 1e-12:
        return [0.0, 0.0, 0.0]
    k = angle / (2 * math.sin(angle))
    return [k * (r[2][1] - r[1][2]), k * (r[0][2] - r[2][0]), k * (r[1][0] - r[0][1])]


def largest_eigenvector(m):
    """Of a symmetric 4x4 matrix, by Jacobi rotations."""
    n = 4
    a = [row[:] for row in m]
    v = [[float(i == j) for j in range(n)] for i in range(n)]
    for _ in range(100):
        off = sum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j)
        if off < 1e-30:
            break
        for p in range(n):
            for q in range(p + 1, n):
                if abs(a[p][q]) < 1e-300:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * a[p][q])
                t = (1 if theta >= 0 else -1) / (abs(theta) + math.sqrt(theta * theta + 1))
                c = 1 / math.sqrt(t * t + 1)
                s = t * c
                for k in range(n):
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(n):
                    vkp, vkq = v[k][p], v[k][q]
                    v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    best = max(range(n), key=lambda i: a[i][i])
    return [v[k][best] for k in range(n)]


def align(est, gt):
    """R, t with gt ~ R est + t (Horn's quaternion method, no scale)."""
    me = scale([sum(c) for c in zip(*est)], 1 / len(est))
    mg = scale([sum(c) for c in zip(*gt)], 1 / len(gt))
    s = [[0.0] * 3 for _ in range(3)]
    for e, g in zip(est, gt):
        de, dg = sub(e, me), sub(g, mg)
        for i in range(3):
            for j in range(3):
                s[i][j] += de[i] * dg[j]
    (sxx, sxy, sxz), (syx, syy, syz), (szx, szy, szz) = s
    n = [[sxx + syy + szz, syz - szy, szx - sxz, sxy - syx],
         [syz - szy, sxx - syy - szz, sxy + syx, szx + sxz],
         [szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy],
         [sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz]]
    w, x, y, z = largest_eigenvector(n)
    r = quat_to_matrix([x, y, z, w])
    return r, sub(mg, matvec(r, me))


def associate(stamps, gt_stamps, max_difference=0.02):
    out = []
    for s in stamps:
        i = bisect.bisect_left(gt_stamps, s)
        best = -1
        for j in (i - 1, i):
            if 0 <= j < len(gt_stamps) and abs(gt_stamps[j] - s) <= max_difference:
                if best < 0 or abs(gt_stamps[j] - s) < abs(gt_stamps[best] - s):
                    best = j
        out.append(best)
    return out


def jitter(stamps, centres):
    dt = [b - a for a, b in zip(stamps, stamps[1:])]
    if len(dt) < 3:
        return None
    longest = 1.5 * sorted(dt)[len(dt) // 2]
    total, count = 0.0, 0
    for i in range(1, len(stamps) - 1):
        if 0 < dt[i - 1] <= longest and 0 < dt[i] <= longest:
            total += norm2(add(sub(centres[i + 1], scale(centres[i], 2)), centres[i - 1]))
            count += 1
    return math.sqrt(total / count) if count >= 3 else None


def figures(gt_path, run_dir):
    gt_t, gt_c, gt_q = read_tum(gt_path)
    out = {}
    for name, file in (("saved", "CameraTrajectory.txt"), ("causal", "OnlineCameraTrajectory.txt"),
                       ("tracked", "TrackedCameraTrajectory.txt")):
        t, c, q = read_tum(f"{run_dir}/{file}")
        pairs = [(k, j) for k, j in enumerate(associate(t, gt_t)) if j >= 0]
        r, tr = align([c[k] for k, _ in pairs], [gt_c[j] for _, j in pairs])
        err = [norm2(sub(gt_c[j], add(matvec(r, c[k]), tr))) for k, j in pairs]
        out[name] = {"ate_m": math.sqrt(sum(err) / len(err)), "jitter_m": jitter(t, c),
                     "poses": len(t)}
        if name == "causal":
            causal = (r, {round(s, 6): k for k, s in enumerate(t)}, q)
    out["groundtruth_jitter_m"] = jitter(gt_t, gt_c)
    r_align, by_stamp, q_est = causal
    lin, ang = [], []
    with open(f"{run_dir}/OnlineCameraVelocity.txt") as f:
        rows = [[float(x) for x in line.split()] for line in f if line.strip()
                and not line.startswith("#")]
    for row, j in zip(rows, associate([r[0] for r in rows], gt_t)):
        k = by_stamp.get(round(row[0], 6))
        if j <= 0 or j + 1 >= len(gt_t) or k is None:
            continue
        span = gt_t[j + 1] - gt_t[j - 1]
        if not 0 < span < 0.1:
            continue
        gt_v = scale(sub(gt_c[j + 1], gt_c[j - 1]), 1 / span)
        r0, r1, rj = (quat_to_matrix(gt_q[j - 1]), quat_to_matrix(gt_q[j + 1]),
                      quat_to_matrix(gt_q[j]))
        gt_w = scale(matvec(rj, log_rotation(matmul(transpose(r0), r1))), 1 / span)
        r_wc = matmul(r_align, quat_to_matrix(q_est[k]))
        lin.append(norm2(sub(matvec(r_wc, row[1:4]), gt_v)))
        ang.append(norm2(sub(matvec(r_wc, row[4:7]), gt_w)))
    out["velocity"] = {"linear_rmse_mps": math.sqrt(sum(lin) / len(lin)),
                       "angular_rmse_radps": math.sqrt(sum(ang) / len(ang)), "frames": len(lin)}
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    result = figures(sys.argv[1], sys.argv[2])
    if "--json" in sys.argv:
        print(json.dumps(result))
        return
    for name in ("saved", "causal", "tracked"):
        f = result[name]
        print(f"{name:8s} ATE {100 * f['ate_m']:.2f} cm  jitter {100 * f['jitter_m']:.3f} cm")
    print(f"groundtruth jitter {100 * result['groundtruth_jitter_m']:.3f} cm")
    v = result["velocity"]
    print(f"causal velocity RMSE: linear {v['linear_rmse_mps']:.3f} m/s, angular "
          f"{v['angular_rmse_radps']:.3f} rad/s over {v['frames']} frames")


if __name__ == "__main__":
    main()
