#!/usr/bin/env python3
"""APE of replay_pipeline's BIM-frame poses against the bag's ground truth, without alignment.

    ape_tum.py PREFIX.pose_bim.tum PREFIX.truth.tum

Each pose is paired with the ground-truth sample of the same stamp (within 20 ms); prints the
number of pairs, the x-y error RMSE and max [m] and the yaw error RMSE and max [deg]. Exits 1
when there are no poses (not localized).
"""
import sys
import warnings

import numpy as np


def yaw(q):
    x, y, z, w = q.T
    return np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an empty file: not localized
        est = np.loadtxt(argv[1], ndmin=2)
        truth = np.loadtxt(argv[2], ndmin=2)
    if est.size == 0:
        print("no poses in the BIM frame (not localized)")
        return 1
    idx = np.clip(np.searchsorted(truth[:, 0], est[:, 0]), 0, len(truth) - 1)
    ok = np.abs(truth[idx, 0] - est[:, 0]) < 0.02
    est, ref = est[ok], truth[idx[ok]]
    e = np.linalg.norm(est[:, 1:3] - ref[:, 1:3], axis=1)
    dyaw = np.degrees(np.abs((yaw(est[:, 4:8]) - yaw(ref[:, 4:8]) + np.pi) % (2 * np.pi) - np.pi))
    print(f"n={len(e)} xy RMSE {np.sqrt((e ** 2).mean()):.3f} max {e.max():.3f} | "
          f"yaw RMSE {np.sqrt((dyaw ** 2).mean()):.2f} max {dyaw.max():.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
