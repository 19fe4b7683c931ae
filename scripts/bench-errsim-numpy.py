#!/usr/bin/env python3
"""The NumPy peer of err-sim's chain (docs/performance.md#err-sim): the same model as
lib/vstcal/errsim/chain.h and holloway.h, vectorized over samples with plain NumPy, on a
vstcal/vst-chain@1 file with the pose form of virtual-object alignment and σ's per lens parameter
(datasets/vst/seed001.json). It draws every parameter, evaluates both eyes at every test point,
and computes every measure err-sim reports (pixel errors, per-eye angles, Holloway's linear,
lateral, depth and angular errors, occlusion decisions).

Usage: bench-errsim-numpy.py CHAIN.json [SAMPLES] [REPEATS]
       bench-errsim-numpy.py check CHAIN.json ERR_SIM [SAMPLES]
The first prints the median CPU time per sample and the totals (image RMS px, perceived RMS). The
second runs `ERR_SIM run CHAIN --no-budget` with the same number of samples and checks that both
totals agree within 5 standard errors of their difference (ctest errsim_numpy_peer): an
independent implementation of the same chain, so a disagreement is a bug in one of them.
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


def simulate(chain, directory, n, seed):
    rng = np.random.default_rng(seed)
    src = chain["sources"]
    deg = math.pi / 180
    fr = chain["frames"]
    R_tw, t_tw = transform(fr["tracker_from_world"])
    R_ht, t_ht = transform(fr["hmd_from_tracker"])
    R_wv, t_wv = transform(fr.get("world_from_virtual", {"rotvec_deg": [0, 0, 0], "t": [0, 0, 0]}))
    R_wo, t_wo = transform(fr["world_from_object"])
    cams = [transform(fr["camera_from_hmd"][e]) for e in ("left", "right")]
    K = []
    for e in ("left", "right"):
        c = chain["cameras"][e]
        if "file" in c:
            c = json.load(open(os.path.join(directory, c["file"])))
        k = np.array(c["K"], float)
        d = c["distortion"]
        K.append(np.array([k[0, 0], k[1, 1], k[0, 2], k[1, 2], k[0, 1]] + [d.get(p, 0.0) for p in ("k1", "k2", "p1", "p2", "k3")]))
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

    # Draws.
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
    q, zv, rays, eyes = [], [], [], []
    ipd = ipd0 + d_ipd
    for e in range(2):
        Ee = E(w_e[e])
        Rc = Ee @ cams[e][0]
        tc = Ee @ cams[e][1] + r_e[e] + d_b * step[e][None, :]
        R = Rc @ R_ho
        t = np.einsum("nij,nj->ni", Rc, t_ho) + tc
        x = np.einsum("nij,kj->nki", R, pts_o) + t[:, None, :]
        q.append(project(lens[e], x))
        zv.append(x[:, :, 2])
        # Display: screen mapping, the true K⁻¹, lens residual, nominal camera orientation.
        k = K[e]
        du = (1 + mag[e]) * (q[e][:, :, 0] - k[2]) + shift[e][:, 0:1]
        dv = (1 + mag[e]) * (q[e][:, :, 1] - k[3]) + shift[e][:, 1:2]
        yn = dv / k[1]
        xn = (du - k[4] * yn) / k[0]
        radial = 1 + k1d[e] * (xn * xn + yn * yn)
        d = np.stack([xn * radial, yn * radial, np.ones_like(xn)], axis=-1) @ cams[e][0]
        rays.append(d)
        eyes.append(eye_centre[None, :] + np.hstack([(-0.5 if e == 0 else 0.5) * ipd, np.zeros((n, 2))]) + eyepoint[e])
    # Perceived point: closest approach, cross-product form.
    nrm = np.cross(rays[0], rays[1])
    n2 = np.sum(nrm * nrm, axis=-1)
    between = (eyes[1] - eyes[0])[:, None, :]
    s0 = np.sum(np.cross(between, rays[1]) * nrm, axis=-1) / n2
    s1 = np.sum(np.cross(between, rays[0]) * nrm, axis=-1) / n2
    perceived = 0.5 * (eyes[0][:, None, :] + s0[..., None] * rays[0] + eyes[1][:, None, :] + s1[..., None] * rays[1])
    M = E(w_head[None, :] * tau_d)
    truth = np.einsum("nji,nkj->nki", M, pts_h[None, :, :] - (v_head[None, :] * tau_d)[:, None, :])
    # Measures (holloway.cc).
    out = {}
    for e in range(2):
        out[f"pixel{e}"] = np.linalg.norm(q[e] - real_px[e], axis=-1)
        out[f"angle{e}"] = np.degrees(angle(rays[e], truth - eyes[e][:, None, :]))
    c = 0.5 * (eyes[0] + eyes[1])[:, None, :]
    sight = truth - c
    sight /= np.linalg.norm(sight, axis=-1, keepdims=True)
    delta = perceived - truth
    out["linear"] = np.linalg.norm(delta, axis=-1)
    out["depth"] = np.sum(delta * sight, axis=-1)
    out["lateral"] = np.linalg.norm(delta - out["depth"][..., None] * sight, axis=-1)
    out["angular"] = np.degrees(angle(truth - c, perceived - c))
    surf = np.array([p.get("surface_behind", np.nan) for p in chain["test_points"]])
    for e in range(2):
        fb = K[e][0] * baseline
        z_s = real_z[e][None, :] + surf[None, :]
        disp = fb / z_s + disparity
        measured = np.where(disp > 0, fb / np.where(disp > 0, disp, 1), np.inf)
        out[f"wrong{e}"] = (zv[e] < measured) != (surf[None, :] > 0)
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
    """Per-sample aggregates → (image RMS, its SE, perceived RMS, its SE); SE of √mean by the delta method."""
    image_ms = np.mean(np.concatenate([out["pixel0"] ** 2, out["pixel1"] ** 2], axis=1), axis=1)
    perceived_ms = np.mean(out["linear"] ** 2, axis=1)
    result = []
    for a in (image_ms, perceived_ms):
        rms = math.sqrt(np.mean(a))
        result += [rms, np.std(a, ddof=1) / math.sqrt(len(a)) / (2 * rms)]
    return result


def check(path, err_sim, n):
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report.json")
        subprocess.run([err_sim, "run", path, "--no-budget", "--samples", str(n), "-q", "-o", report], check=True)
        ours = json.load(open(report))["totals"]
    chain = json.load(open(path))
    image, image_se, perceived, perceived_se = totals(simulate(chain, os.path.dirname(path), n, 2024))
    ok = True
    for name, peer, se, cpp in (("image_rms_px", image, image_se, ours["image_rms_px"]),
                                ("perceived_rms", perceived, perceived_se, ours["perceived_rms"])):
        z = (cpp - peer) / (math.sqrt(2) * se)
        print(f"{name}: err-sim {cpp:.4f}, numpy {peer:.4f}, difference {z:+.2f} standard errors")
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
        out = simulate(chain, os.path.dirname(path), n, 1000 + r)
        times.append(time.process_time() - start)
    image = math.sqrt(np.mean([np.mean(out[f"pixel{e}"] ** 2) for e in range(2)]))
    perceived = math.sqrt(np.mean(out["linear"] ** 2))
    print(f"numpy {np.__version__}: {n} samples, median {1e9 * sorted(times)[len(times) // 2] / n:.0f} ns/sample (CPU), "
          f"image {image:.2f} px rms, perceived {perceived:.2f} rms")


if __name__ == "__main__":
    sys.exit(main())
