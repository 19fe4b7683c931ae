#!/usr/bin/python3
"""Independent NumPy reference for calib-dlt's golden numbers (datasets/golden/).

Written separately from the C++ code, from the textbook: build the Hartley-normalized 2N×12 DLT
system (centroid to the origin, RMS distance √3 for world points and √2 for pixels), take the
right singular vector of the smallest singular value (LAPACK through numpy.linalg.svd),
denormalize, scale P to a unit third row with the scene in front, and decompose P = K[R|t] by an
RQ decomposition written with numpy.linalg.qr. Residuals are computed from K, R, t.

Usage:
  dlt_reference.py write   # regenerate datasets/golden/dlt-*.json
  dlt_reference.py check   # recompute and compare with the committed files (ctest: golden_reference)
"""
import json
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATASETS = ["seed000/clean", "seed000/noisy", "zedmini/clean", "zedmini/noisy"]


def load(path):
    with open(path) as f:
        doc = json.load(f)
    points = np.array([p for view in doc["views"] for p in view["points"]], dtype=float)
    return doc, points[:, :3], points[:, 3:5]


def normalization(x, dim):
    centroid = x.mean(axis=0)
    rms = np.sqrt(((x - centroid) ** 2).sum(axis=1).mean())
    s = np.sqrt(dim) / rms
    T = np.eye(dim + 1)
    T[:dim, :dim] *= s
    T[:dim, dim] = -s * centroid
    return T


def dlt(X, uv):
    T3, T2 = normalization(X, 3), normalization(uv, 2)
    Xh = (T3 @ np.c_[X, np.ones(len(X))].T).T
    q = (T2 @ np.c_[uv, np.ones(len(uv))].T).T
    A = np.zeros((2 * len(X), 12))
    A[0::2, 0:4] = Xh
    A[0::2, 8:12] = -q[:, [0]] * Xh
    A[1::2, 4:8] = Xh
    A[1::2, 8:12] = -q[:, [1]] * Xh
    _, sv, Vt = np.linalg.svd(A)
    P = np.linalg.inv(T2) @ Vt[-1].reshape(3, 4) @ T3
    P /= np.linalg.norm(P[2, :3])
    depth = P[2, :3] @ X.T + P[2, 3]
    if (depth > 0).sum() < len(X) / 2:
        P = -P
    return P, sv


def rq_decompose(P):
    """P = K [R | t] with K upper triangular, positive diagonal, K[2,2] = 1."""
    M = P[:, :3]
    # RQ from QR: reverse the rows, transpose, QR, undo.
    Q, U = np.linalg.qr(np.flipud(M).T)
    K = np.flipud(np.fliplr(U.T))
    R = np.flipud(Q.T)
    D = np.diag(np.sign(np.diag(K)))
    K, R = K @ D, D @ R
    t = np.linalg.solve(K, P[:, 3])
    return K / K[2, 2], R, t


def project(K, R, t, X):
    x = (R @ X.T).T + t
    return (K @ (x / x[:, [2]]).T).T[:, :2]


def reference(name):
    doc, X, uv = load(os.path.join(ROOT, "datasets", name + ".json"))
    P, sv = dlt(X, uv)
    K, R, t = rq_decompose(P)
    r = np.linalg.norm(project(K, R, t, X) - uv, axis=1)
    tests = []
    for tp in doc.get("test_points", []):
        pred = project(K, R, t, np.array([tp["world"]], dtype=float))[0]
        tests.append({"name": tp["name"], "predicted": pred.tolist(),
                      "error_px": float(np.linalg.norm(pred - np.array(tp["pixel"])))})
    return {
        "format": "vstcal/golden-dlt@1",
        "dataset": "datasets/" + name + ".json",
        "generator": "scripts/golden/dlt_reference.py (NumPy %s, LAPACK SVD of the 2N×12 system)" % np.__version__,
        "P": P.tolist(), "K": K.tolist(), "R": R.tolist(), "t": t.tolist(),
        "sigma_11": float(sv[10]), "sigma_12": float(sv[11]),
        "rms_px": float(np.sqrt((r ** 2).mean())), "max_px": float(r.max()),
        "test_points": tests,
    }


def golden_path(name):
    return os.path.join(ROOT, "datasets", "golden", "dlt-" + name.replace("/", "-") + ".json")


def compare(a, b, path, tol):
    """Relative/absolute agreement of nested numbers; returns a list of mismatches."""
    if isinstance(a, dict):
        return [m for k in a if k not in ("generator",) for m in compare(a[k], b[k], path + "." + k, tol)]
    if isinstance(a, list):
        return [m for i, (x, y) in enumerate(zip(a, b)) for m in compare(x, y, "%s[%d]" % (path, i), tol)] + \
            ([] if len(a) == len(b) else [path + ": length"])
    if isinstance(a, float):
        scale = max(1.0, abs(a))
        return [] if abs(a - b) <= tol * scale else ["%s: %r vs %r" % (path, a, b)]
    return [] if a == b else ["%s: %r vs %r" % (path, a, b)]


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else "check"
    failures = []
    for name in DATASETS:
        ref = reference(name)
        if mode == "write":
            with open(golden_path(name), "w") as f:
                json.dump(ref, f, indent=2)
                f.write("\n")
        else:
            with open(golden_path(name)) as f:
                committed = json.load(f)
            failures += [name + m for m in compare(committed, ref, "", 1e-11)]
    for f in failures:
        print("golden mismatch: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
