#!/usr/bin/env python3
"""The NumPy peer of err-sim's chain (docs/performance.md#err-sim): the same model as
lib/vstcal/errsim/chain.h and measures.h, vectorized over samples with plain NumPy, on a
vstcal/vst-chain@1 file with the pose form of virtual-object alignment and σ's per lens parameter
(datasets/vst/seed001.json). It draws every parameter, evaluates both eyes at every test point,
shows the video and the overlay to eyes behind the cameras through a display whose virtual image
is at a finite distance, and computes every measure err-sim reports (pixel errors, Holloway's
linear, lateral, depth and angular terms of the misregistration and of the misperception relative
to the error-free chain's systematic one, occlusion decisions).

Usage: bench-errsim-numpy.py CHAIN.json [SAMPLES] [REPEATS]
       bench-errsim-numpy.py check CHAIN.json ERR_SIM [SAMPLES]
The first prints the median CPU time per sample and the totals (image RMS px, misregistration RMS,
misperception RMS). The second runs `ERR_SIM run CHAIN --no-budget` with the same number of
samples and checks that the three totals agree within 5 standard errors of their difference (ctest
errsim_numpy_peer): an independent implementation of the same chain, so a disagreement is a bug
in one of them.
"""
import json
import math
import os
import sys
import time

import numpy as np


def transform(node):
    if "R" in node:
        return np.array(node["R"], float), np.array(node["t"], float)
    return exp_so3(np.radians(np.array(node["rotvec_deg"], float))[None, :])[0], np.array(node["t"], float)


def exp_so3(w):
    """Rodrigues for an (N, 3) array of rotation vectors → (N, 3, 3)."""
    theta = np.linalg.norm(w, axis=1)
    small = theta < 1e-12
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1.0, np.sin(safe) / safe)
    b = np.where(small, 0.5, (1 - np.cos(safe)) / safe**2)
    K = np.zeros((len(w), 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -w[:, 2], w[:, 1], -w[:, 0]
    K[:, 1, 0], K[:, 2, 0], K[:, 2, 1] = w[:, 2], -w[:, 1], w[:, 0]
    return np.eye(3) + a[:, None, None] * K + b[:, None, None] * (K @ K)


def draw(rng, spec, n, comps, scale=1.0):
    """Draws (n, comps) values of a distribution object (docs/formats.md#vst-chain-distributions)."""
    if spec is None:
        return np.zeros((n, comps))
    vec = lambda key, default=0.0: np.broadcast_to(np.array(spec.get(key, default), float), (comps,)) * scale
    kind = spec["distribution"]
    if kind == "normal":
        return vec("mean") + vec("sigma") * rng.standard_normal((n, comps))
    if kind == "uniform":
        lo, hi = (-vec("half_width"), vec("half_width")) if "half_width" in spec else (vec("min"), vec("max"))
        return lo + (hi - lo) * rng.random((n, comps))
    return np.broadcast_to(vec("value"), (n, comps)).copy()


def eye_terms(source, eye):
    """A per-eye block: "left"/"right", or "both"."""
    return source.get(eye) or source.get("both") or {}


def angle(a, b):
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def triangulate(e0, d0, e1, d1):
    """Midpoint of the closest approach of e0 + s d0 and e1 + s d1 (cross-product form)."""
    nrm = np.cross(d0, d1)
    n2 = np.sum(nrm * nrm, axis=-1)
    between = e1 - e0
    s0 = np.sum(np.cross(between, d1) * nrm, axis=-1) / n2
    s1 = np.sum(np.cross(between, d0) * nrm, axis=-1) / n2
    return 0.5 * (e0 + s0[..., None] * d0 + e1 + s1[..., None] * d1)


def holloway(c, reference, seen):
    """Holloway's terms of seen − reference from the viewpoint c (geometry/registration_error.h)."""
    delta = seen - reference
    sight = reference - c
    sight_unit = sight / np.linalg.norm(sight, axis=-1, keepdims=True)
    depth = np.sum(delta * sight_unit, axis=-1)
    return {"linear": np.linalg.norm(delta, axis=-1), "depth": depth,
            "lateral": np.linalg.norm(delta - depth[..., None] * sight_unit, axis=-1),
            "angular": np.degrees(angle(sight, seen - c))}


def simulate(chain, directory, n, seed, errors=True):
    rng = np.random.default_rng(seed)
    src = chain["sources"]
    deg = math.pi / 180
    fr = chain["frames"]
    R_tw, t_tw = transform(fr["tracker_from_world"])
    R_ht, t_ht = transform(fr["hmd_from_tracker"])
    R_wv, t_wv = transform(fr.get("world_from_virtual", {"rotvec_deg": [0, 0, 0], "t": [0, 0, 0]}))
    R_wo, t_wo = transform(fr["world_from_object"])
    cams = [transform(fr["camera_from_hmd"][e]) for e in ("left", "right")]
    K, image_size = [], []
    for e in ("left", "right"):
        c = chain["cameras"][e]
        if "file" in c:
            c = json.load(open(os.path.join(directory, c["file"])))
        k = np.array(c["K"], float)
        d = c["distortion"]
        K.append(np.array([k[0, 0], k[1, 1], k[0, 2], k[1, 2], k[0, 1]] + [d.get(p, 0.0) for p in ("k1", "k2", "p1", "p2", "k3")]))
        image_size.append(c["image_size"])
    # Nominal pieces (chain.cc).
    R_tv, t_tv = R_tw @ R_wv, R_tw @ t_wv + t_tw
    R_vo, t_vo = R_wv.T @ R_wo, R_wv.T @ (t_wo - t_wv)
    R_hw, t_hw = R_ht @ R_tw, R_ht @ t_tw + t_ht
    pts_w = np.array([p["world"] for p in chain["test_points"]], float)
    pts_o = (pts_w - t_wo) @ R_wo  # object_from_world
    pts_h = pts_w @ R_hw.T + t_hw
    centres = [-(R.T @ t) for R, t in cams]
    baseline = np.linalg.norm(centres[1] - centres[0])
    e_b = (centres[1] - centres[0]) / baseline
    step = [0.5 * cams[0][0] @ e_b, -0.5 * cams[1][0] @ e_b]
    real_px, real_z = [], []
    for e in range(2):
        x = pts_h @ cams[e][0].T + cams[e][1]
        real_px.append(project(K[e][None, :], x[None, :, :]))
        real_z.append(x[:, 2])
    motion = chain.get("head_motion", {})
    w_head = np.radians(np.array(motion.get("angular_velocity_deg_s", [0, 0, 0]), float))
    v_head = np.array(motion.get("linear_velocity", [0, 0, 0]), float)
    display = chain["display"]
    ipd0 = display["ipd"]
    eye_centre = np.array(display.get("eye_centre", 0.5 * (centres[0] + centres[1])), float)
    metres = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}[chain["length_unit"]]
    distance = display.get("virtual_image_distance", 1.5 / metres)
    w = 0.0 if distance == "infinity" else 1.0 / distance

    # Draws (none for the error-free chain).
    if not errors:
        src = {}
    ta, tr = src.get("tracker_alignment", {}), src.get("tracking", {})
    ce, ci, rd, ds, vo = (src.get(k, {}) for k in ("camera_extrinsic", "camera_intrinsic", "rendering", "display", "virtual_object_alignment"))
    w_a, r_a = draw(rng, ta.get("rotation_deg"), n, 3, deg), draw(rng, ta.get("translation"), n, 3)
    w_n, r_n = draw(rng, tr.get("rotation_deg"), n, 3, deg), draw(rng, tr.get("translation"), n, 3)
    age = draw(rng, tr.get("latency_s"), n, 1) + draw(rng, rd.get("latency_s"), n, 1)
    w_rig = draw(rng, ce.get("rig", {}).get("rotation_deg"), n, 3, deg)
    r_rig = draw(rng, ce.get("rig", {}).get("translation"), n, 3)
    w_e = [draw(rng, eye_terms(ce, e).get("rotation_deg"), n, 3, deg) for e in ("left", "right")]
    r_e = [draw(rng, eye_terms(ce, e).get("translation"), n, 3) for e in ("left", "right")]
    d_b = draw(rng, ce.get("baseline"), n, 1)
    names = ("fx", "fy", "cx", "cy", "s", "k1", "k2", "p1", "p2", "k3")
    lens = [K[i][None, :] + np.hstack([draw(rng, eye_terms(ci, e).get(p), n, 1) for p in names]) for i, e in enumerate(("left", "right"))]
    disparity = draw(rng, rd.get("disparity_px"), n, len(pts_w))
    w_o, r_o = draw(rng, vo.get("rotation_deg"), n, 3, deg), draw(rng, vo.get("translation"), n, 3)
    eyepoint = [draw(rng, eye_terms(ds, e).get("eyepoint"), n, 3) for e in ("left", "right")]
    shift = [draw(rng, eye_terms(ds, e).get("screen_shift_px"), n, 2) for e in ("left", "right")]
    mag = [draw(rng, eye_terms(ds, e).get("magnification"), n, 1) for e in ("left", "right")]
    k1d = [draw(rng, eye_terms(ds, e).get("lens_k1"), n, 1) for e in ("left", "right")]
    d_ipd = draw(rng, ds.get("ipd"), n, 1)
    tau_d = draw(rng, ds.get("latency_s"), n, 1)
    eye_offset = draw(rng, ds.get("eye_offset"), n, 3)

    # The virtual path (chain.h).
    E = exp_so3
    R1 = E(w_a) @ R_tv
    t1 = (E(w_a) @ t_tv) + r_a                       # tracker_from_virtual'
    R2 = E(w_o) @ R_vo
    t2 = (E(w_o) @ t_vo) + r_o                       # virtual_from_object'
    L = E(w_head[None, :] * age)
    R3 = E(w_n) @ (L @ R_ht)
    t3 = np.einsum("nij,nj->ni", E(w_n), np.einsum("nij,j->ni", L, t_ht) + v_head[None, :] * age) + r_n
    R_to = R1 @ R2
    t_to = np.einsum("nij,nj->ni", R1, t2) + t1
    R_ho = R3 @ R_to
    t_ho = np.einsum("nij,nj->ni", R3, t_to) + t3
    Er = E(w_rig)
    R_ho, t_ho = Er @ R_ho, np.einsum("nij,nj->ni", Er, t_ho) + r_rig
    q, zv, overlay_rays, seen_rays, eyes, valid = [], [], [], [], [], np.ones((n, len(pts_w)), bool)
    for e in range(2):
        Ee = E(w_e[e])
        Rc = Ee @ cams[e][0]
        tc = Ee @ cams[e][1] + r_e[e] + d_b * step[e][None, :]
        R = Rc @ R_ho
        t = np.einsum("nij,nj->ni", Rc, t_ho) + tc
        x = np.einsum("nij,kj->nki", R, pts_o) + t[:, None, :]
        q.append(project(lens[e], x))
        zv.append(x[:, :, 2])
        size = image_size[e]
        valid &= (x[:, :, 2] > 0) & (q[e][..., 0] >= -0.5) & (q[e][..., 0] <= size[0] - 0.5) & \
                 (q[e][..., 1] >= -0.5) & (q[e][..., 1] <= size[1] - 0.5)
        # The eye: its design eyepoint moved by its own error, both eyes' offset and half the IPD error.
        side = -0.5 if e == 0 else 0.5
        design = eye_centre + np.array([side * ipd0, 0.0, 0.0])
        displacement = eyepoint[e] + eye_offset + np.hstack([side * d_ipd, np.zeros((n, 2))])
        eyes.append(design[None, :] + displacement)
        # Display: screen mapping, the true K⁻¹, lens residual, nominal camera orientation; the
        # virtual image at distance D turns a displaced eye's ray by −Δ/D.
        k = K[e]

        def displayed(pixel):
            du = (1 + mag[e]) * (pixel[..., 0] - k[2]) + shift[e][:, 0:1]
            dv = (1 + mag[e]) * (pixel[..., 1] - k[3]) + shift[e][:, 1:2]
            yn = dv / k[1]
            xn = (du - k[4] * yn) / k[0]
            radial = 1 + k1d[e] * (xn * xn + yn * yn)
            d = np.stack([xn * radial, yn * radial, np.ones_like(xn)], axis=-1) @ cams[e][0]
            return d - w * displacement[:, None, :]

        overlay_rays.append(displayed(q[e]))
        seen_rays.append(displayed(np.broadcast_to(real_px[e], q[e].shape)))
    overlay = triangulate(eyes[0][:, None, :], overlay_rays[0], eyes[1][:, None, :], overlay_rays[1])
    seen = triangulate(eyes[0][:, None, :], seen_rays[0], eyes[1][:, None, :], seen_rays[1])
    M = E(w_head[None, :] * tau_d)
    truth = np.einsum("nji,nkj->nki", M, pts_h[None, :, :] - (v_head[None, :] * tau_d)[:, None, :])
    c = 0.5 * (eyes[0] + eyes[1])[:, None, :]
    out = {"valid": valid, "seen_minus_truth": seen - truth, "truth": truth, "seen": seen, "c": c}
    for e in range(2):
        out[f"pixel{e}"] = np.linalg.norm(q[e] - real_px[e], axis=-1)
    out["misregistration"] = holloway(c, seen, overlay)
    surf = np.array([p.get("surface_behind", np.nan) for p in chain["test_points"]])
    for e in range(2):
        fb = K[e][0] * baseline
        z_s = real_z[e][None, :] + surf[None, :]
        disp = fb / z_s + disparity
        measured = np.where(disp > 0, fb / np.where(disp > 0, disp, 1), np.inf)
        out[f"wrong{e}"] = (zv[e] < measured) != (surf[None, :] > 0)
    return out


def measure(chain, directory, n, seed):
    """simulate() with the misperception measured from the error-free chain's systematic one."""
    systematic = simulate(chain, directory, 1, 0, errors=False)["seen_minus_truth"][0]
    out = simulate(chain, directory, n, seed)
    out["misperception"] = holloway(out["c"], out["truth"] + systematic[None, :, :], out["seen"])
    return out


def project(p, x):
    """Radial-tangential projection (lens_models.h) of (N, P, 3) points with (N, 10) parameters."""
    fx, fy, cx, cy, s, k1, k2, p1, p2, k3 = (p[:, i:i + 1] for i in range(10))
    xn, yn = x[..., 0] / x[..., 2], x[..., 1] / x[..., 2]
    r2 = xn * xn + yn * yn
    radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3))
    xd = xn * radial + 2 * p1 * xn * yn + p2 * (r2 + 2 * xn * xn)
    yd = yn * radial + p1 * (r2 + 2 * yn * yn) + 2 * p2 * xn * yn
    return np.stack([fx * xd + s * yd + cx, fy * yd + cy], axis=-1)


def totals(out):
    """Per-sample aggregates → (RMS, its SE) of the image, misregistration and misperception totals;
    undefined points left out of their means; SE of √mean by the delta method."""
    valid = out["valid"]
    per_point = {
        "image_rms_px": 0.5 * (out["pixel0"] ** 2 + out["pixel1"] ** 2),
        "misregistration_rms": out["misregistration"]["linear"] ** 2,
        "misperception_rms": out["misperception"]["linear"] ** 2,
    }
    result = {}
    for name, squares in per_point.items():
        # The total is √(mean over points of each point's mean square over its defined samples).
        ms = np.array([np.mean(squares[valid[:, k], k]) for k in range(squares.shape[1])])
        rms = math.sqrt(np.mean(ms))
        # SE: each point's mean square has SE std/√N_k; the mean over points adds them in quadrature.
        se_ms = math.sqrt(sum(np.var(squares[valid[:, k], k], ddof=1) / np.sum(valid[:, k])
                              for k in range(squares.shape[1]))) / squares.shape[1]
        result[name] = (rms, se_ms / (2 * rms) if rms > 0 else 0.0)
    return result


def check(path, err_sim, n):
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report.json")
        subprocess.run([err_sim, "run", path, "--no-budget", "--samples", str(n), "-q", "-o", report], check=True)
        ours = json.load(open(report))["totals"]
    chain = json.load(open(path))
    peer = totals(measure(chain, os.path.dirname(path), n, 2024))
    ok = True
    for name, (value, se) in peer.items():
        cpp = ours[name]
        z = (cpp - value) / (math.sqrt(2) * se) if se > 0 else (0.0 if abs(cpp - value) < 1e-9 else float("inf"))
        print(f"{name}: err-sim {cpp:.4f}, numpy {value:.4f}, difference {z:+.2f} standard errors")
        ok &= abs(z) <= 5
    print("1 passed, 0 failed" if ok else "0 passed, 1 failed")
    return 0 if ok else 1


def main():
    if sys.argv[1] == "check":
        return check(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 200000)
    path = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 100000
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    chain = json.load(open(path))
    times = []
    for r in range(repeats):
        start = time.process_time()
        out = measure(chain, os.path.dirname(path), n, 1000 + r)
        times.append(time.process_time() - start)
    t = totals(out)
    print(f"numpy {np.__version__}: {n} samples, median {1e9 * sorted(times)[len(times) // 2] / n:.0f} ns/sample (CPU), "
          f"image {t['image_rms_px'][0]:.2f} px rms, misregistration {t['misregistration_rms'][0]:.2f} rms, "
          f"misperception {t['misperception_rms'][0]:.2f} rms")


if __name__ == "__main__":
    sys.exit(main())
