"""The solvers from Python against the tools on the same files (calib-dlt, calib-tsai, calib-stereo
solve), and the planar calibration with its covariance against OpenCV's cv2.calibrateCameraExtended."""
import shutil

import cv2
import numpy as np
import pytest

from conftest import DATASETS, OPENCV_DATA, assert_documents_close, load, run_tool, tool_error, without_provenance


def arrays(corners):
    rows = np.array([p for v in corners["views"] for p in v["points"]])
    return np.ascontiguousarray(rows[:, :3]), np.ascontiguousarray(rows[:, 3:5])


def test_solve_dlt_is_calib_dlts_p(vstcal, tmp_path):
    source = DATASETS / "seed000" / "noisy.json"
    run_tool("calib-dlt", source, "-o", tmp_path / "camera.json")
    camera = load(tmp_path / "camera.json")
    points, pixels = arrays(vstcal.read(source))
    for solver in ("normal-equations", "svd"):
        s = vstcal.solve_dlt(points, pixels, solver=solver)
        np.testing.assert_allclose(s.P, np.array(camera["P"]), rtol=1e-9, atol=0)
        np.testing.assert_allclose(s.K, np.array(camera["K"]), rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(s.R, np.array(camera["camera_from_world"]["R"]), rtol=0, atol=1e-9)
        np.testing.assert_allclose(s.t, np.array(camera["camera_from_world"]["t"]), rtol=1e-9, atol=0)
    kept = vstcal.Observations(points, pixels)
    assert len(kept) == len(points)
    np.testing.assert_array_equal(vstcal.solve_dlt(kept).P, vstcal.solve_dlt(points, pixels).P)


def test_solve_dlt_on_observations_is_the_arrays_solve(vstcal):
    """solve_dlt on an Observations takes a fast entry (python/solvers.cc, docs/performance.md#python);
    every call form gives what the arrays' path (pybind11's) gives, and the same errors."""
    points, pixels = arrays(vstcal.read(DATASETS / "seed000" / "noisy.json"))
    kept = vstcal.Observations(points, pixels)
    fields = ("P", "K", "R", "t", "sigma_11", "sigma_12", "conditioning", "extents", "warnings", "n_points")
    for kwargs in ({}, {"solver": "svd"}, {"exact_diagnostics": True}, {"solver": "svd", "exact_diagnostics": True}):
        expected = vstcal.solve_dlt(points, pixels, **kwargs)
        calls = [vstcal.solve_dlt(kept, **kwargs), vstcal.solve_dlt(points=kept, pixels=None, **kwargs),
                 vstcal.solve_dlt(kept, None, kwargs.get("solver", "normal-equations"), kwargs.get("exact_diagnostics", False)),
                 vstcal.solve_dlt(kept, exact_diagnostics=int(kwargs.get("exact_diagnostics", False)),  # converted by pybind11
                                  solver=kwargs.get("solver", "normal-equations"))]
        for s in calls:
            assert type(s) is vstcal.DltSolution
            for name in fields:
                np.testing.assert_array_equal(getattr(s, name), getattr(expected, name), err_msg=f"{kwargs} {name}")
    assert vstcal.solve_dlt.__doc__.startswith("solve_dlt(points: object, pixels: object = None, solver: str = 'normal-equations', "
                                               "exact_diagnostics: bool = False) -> vstcal.DltSolution")
    with pytest.raises(vstcal.InputError, match=r'^solver: unknown DLT solver "qr"; use "normal-equations" or "svd"$'):
        vstcal.solve_dlt(kept, solver="qr")
    with pytest.raises(vstcal.InputError, match=r"^pixels: already in the Observations; leave it out$"):
        vstcal.solve_dlt(kept, pixels)
    with pytest.raises(TypeError, match=r"^solve_dlt\(\): incompatible function arguments"):
        vstcal.solve_dlt(kept, solver=3)
    with pytest.raises(TypeError, match=r"^solve_dlt\(\): incompatible function arguments"):
        vstcal.solve_dlt(kept, colour="red")
    with pytest.raises(TypeError, match=r"^solve_dlt\(\): incompatible function arguments"):
        vstcal.solve_dlt(kept, None, "svd", False, points=kept)
    with pytest.raises(TypeError, match=r"^solve_dlt\(\): incompatible function arguments"):
        vstcal.solve_dlt()
    coplanar = points.copy()
    coplanar[:, 2] = 0
    with pytest.raises(vstcal.DegenerateError) as from_arrays:
        vstcal.solve_dlt(coplanar, pixels)
    with pytest.raises(vstcal.DegenerateError) as from_observations:
        vstcal.solve_dlt(vstcal.Observations(coplanar, pixels))
    assert str(from_observations.value) == str(from_arrays.value) and from_observations.value.exit_code == 3


def test_calibrate_is_calib_dlt_and_calib_tsai(vstcal, tmp_path):
    source = DATASETS / "seed000" / "distorted-noisy.json"
    for tool, method, flags, kwargs in [
        ("calib-dlt", "dlt", [], {}),
        ("calib-dlt", "dlt", ["--refine", "--distortion", "k1,k2"], {"refine": True, "distortion": "k1,k2"}),
        ("calib-tsai", "tsai", [], {}),
        ("calib-tsai", "tsai", ["--no-refine"], {"refine": False}),
        ("calib-tsai", "tsai", ["--prior", "cx=320,5", "--prior", "k2=0,0.01", "--hold", "p1,p2"],
         {"priors": {"cx": (320, 5), "k2": (0, 0.01)}, "hold": ["p1", "p2"]}),
    ]:
        run_tool(tool, source, "-o", tmp_path / "camera.json", *flags)
        assert without_provenance(vstcal.calibrate(str(source), method=method, **kwargs)) == \
            without_provenance(load(tmp_path / "camera.json")), (tool, flags)
    # a dict in memory is the same input
    refined = vstcal.calibrate(vstcal.read(source), method="tsai")
    assert refined["covariance"]["parameters"][:4] == ["fx", "fy", "cx", "cy"]


def test_calibrate_fisheye_is_calib_tsai_lens_model(vstcal, tmp_path):
    """lens_model="kannala-brandt" is calib-tsai --lens-model kannala-brandt on the same file (k1..k4 by
    default, fewer when distortion names them); an unknown model is the tool's refusal."""
    source = tmp_path / "views.json"
    run_tool("calib-synth", "--image-size", "1280x720", "--fx", "700", "--rig", "planar-views", "--seed", "4",
             "--noise", "0.3", "-o", source)
    for flags, kwargs in [([], {}), (["--distortion", "k1,k2"], {"distortion": "k1,k2"})]:
        run_tool("calib-tsai", source, "--lens-model", "kannala-brandt", "-o", tmp_path / "camera.json", *flags)
        camera = vstcal.calibrate(str(source), lens_model="kannala-brandt", **kwargs)
        assert without_provenance(camera) == without_provenance(load(tmp_path / "camera.json")), flags
        assert camera["distortion"]["model"] == "kannala-brandt"
        if not flags:  # k1..k4 stand for a rectilinear lens's tan θ; k1, k2 alone leave a bias
            truth = load(tmp_path / "views.truth.json")
            assert abs(camera["K"][0][0] - truth["K"][0][0]) < 5 * np.sqrt(camera["covariance"]["matrix"][0][0])
    message = tool_error("calib-tsai", source, "-o", tmp_path / "camera.json", "--lens-model", "fisheye9")
    with pytest.raises(vstcal.InputError) as e:
        vstcal.calibrate(str(source), lens_model="fisheye9")
    assert message.startswith("--lens-model: ") and str(e.value) == "lens_model: " + message[len("--lens-model: "):]


def test_failures_raise_the_tools_message_and_exit_code(vstcal, tmp_path):
    corners = vstcal.read(DATASETS / "seed000" / "clean.json")
    corners["views"] = corners["views"][:1]  # one plane: coplanar for DLT
    vstcal.write(tmp_path / "plane.json", corners)
    message = tool_error("calib-dlt", tmp_path / "plane.json", "-o", tmp_path / "camera.json", code=3)
    with pytest.raises(vstcal.DegenerateError) as e:
        vstcal.calibrate(str(tmp_path / "plane.json"), method="dlt")
    assert str(e.value) == message and e.value.exit_code == 3
    points, pixels = arrays(corners)
    with pytest.raises(vstcal.DegenerateError) as e:
        vstcal.solve_dlt(points, pixels)
    assert str(e.value) in message  # the tool prefixes its input file
    # Holds and priors: the tool's messages, with the keyword where the tool names its flag.
    source = DATASETS / "seed000" / "distorted-noisy.json"
    message = tool_error("calib-tsai", source, "-o", tmp_path / "camera.json", "--hold", "cx")
    with pytest.raises(vstcal.InputError) as e:
        vstcal.calibrate(str(source), hold=["cx"])
    assert message.startswith("--hold: ") and str(e.value) == "hold: " + message[len("--hold: "):]
    message = tool_error("calib-tsai", source, "-o", tmp_path / "camera.json", "--prior", "kx=0,1")
    with pytest.raises(vstcal.InputError) as e:
        vstcal.calibrate(str(source), priors={"kx": (0, 1)})
    assert str(e.value) == message

    planar = DATASETS / "zedmini" / "planar-noisy.json"
    message = tool_error("calib-dlt", planar, "-o", tmp_path / "camera.json")
    with pytest.raises(vstcal.InputError) as e:
        vstcal.calibrate(str(planar), method="dlt")
    assert str(e.value).split("; ")[0] == message.split("; ")[0]  # the fix names the binding's method


def test_bad_solver_arguments_name_the_argument(vstcal):
    points = np.zeros((10, 3))
    with pytest.raises(vstcal.InputError, match=r"^pixels: 9 rows for 10 points"):
        vstcal.solve_dlt(points, np.zeros((9, 2)))
    with pytest.raises(vstcal.InputError, match=r"^pixels\[2, 0\]: NaN"):
        vstcal.solve_dlt(points, np.array([[1.0, 2.0]] * 2 + [[np.nan, 0.0]] + [[1.0, 2.0]] * 7))
    with pytest.raises(vstcal.InputError, match=r"^points: expected dtype float64, got int64"):
        vstcal.solve_dlt(np.zeros((10, 3), dtype=np.int64), np.zeros((10, 2)))
    with pytest.raises(vstcal.InputError, match=r"^weights\[0\]: must be positive"):
        vstcal.Observations(points, np.zeros((10, 2)), np.zeros(10))
    with pytest.raises(vstcal.InputError, match=r'^loss_scale: has no effect with loss "none"'):
        vstcal.calibrate(str(DATASETS / "seed000" / "noisy.json"), loss_scale=2.0)
    with pytest.raises(vstcal.InputError, match=r'^distortion: "k1" is named twice'):
        vstcal.calibrate(str(DATASETS / "seed000" / "noisy.json"), distortion="k1,k1")


def test_planar_views_against_calib_tsai_and_opencv_calibrate_camera(vstcal, tmp_path):
    """Zhang's start and the refinement with covariance, against calib-tsai on the same file and against
    cv2.calibrateCameraExtended on the same points: the same least-squares problem (k1, k2, p1, p2 free,
    k3 and skew fixed), so the same optimum, and OpenCV's standard deviations of the intrinsics are the
    square roots of the covariance's diagonal (up to OpenCV's degrees of freedom, below)."""
    source = DATASETS / "zedmini" / "planar-noisy.json"
    run_tool("calib-tsai", source, "-o", tmp_path / "camera.json")
    camera = vstcal.calibrate(str(source))
    assert without_provenance(camera) == without_provenance(load(tmp_path / "camera.json"))

    corners = vstcal.read(source)
    object_points = [np.ascontiguousarray(np.array(v["points"], dtype=np.float32)[:, :3]) for v in corners["views"]]
    image_points = [np.ascontiguousarray(np.array(v["points"], dtype=np.float32)[:, 3:5]) for v in corners["views"]]
    size = tuple(corners["image_size"])
    flags = cv2.CALIB_FIX_K3
    criteria = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 200, 1e-15)
    rms, K, dist, _, _, std_intrinsics, _, _ = cv2.calibrateCameraExtended(
        object_points, image_points, size, None, None, flags=flags, criteria=criteria)
    np.testing.assert_allclose(np.array(camera["K"]), K, rtol=1e-5, atol=1e-3)
    coefficients = camera["distortion"]
    np.testing.assert_allclose([coefficients[k] for k in ("k1", "k2", "p1", "p2")], dist.ravel()[:4], rtol=1e-3, atol=1e-5)
    names = camera["covariance"]["parameters"]
    sigma = np.sqrt(np.diag(np.array(camera["covariance"]["matrix"])))
    # OpenCV's σ² divides the squared residuals by (points − parameters) (calibration.cpp, `total` counts
    # points), vstcal's by the residuals' degrees of freedom, 2·points − parameters: the same covariance
    # otherwise, so OpenCV's deviations are rescaled by that ratio's square root.
    n_points = sum(len(v) for v in image_points)
    n_parameters = 8 + 6 * len(image_points)
    scale = np.sqrt((n_points - n_parameters) / (2 * n_points - n_parameters))
    opencv_sigma = dict(zip(["fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"], scale * std_intrinsics.ravel()[:8]))
    for name in ("fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"):
        assert sigma[names.index(name)] == pytest.approx(opencv_sigma[name], rel=1e-3), name


@pytest.mark.skipif(not (OPENCV_DATA / "left01.jpg").exists(), reason="needs Debian's opencv-doc")
def test_solve_stereo_is_calib_stereo_solve(vstcal, tmp_path):
    run_tool("calib-capture", "target", "--rows", "6", "--cols", "9", "--square-size", "25", "--dpi", "0",
             "-o", tmp_path / "board")
    for side in ("left", "right"):
        images = sorted(str(p) for p in OPENCV_DATA.glob(f"{side}0[1-6].jpg"))
        run_tool("calib-capture", "detect", tmp_path / "board.target.json", *images, "--camera-name", side,
                 "-o", tmp_path / f"{side}.json")
    left, right = str(tmp_path / "left.json"), str(tmp_path / "right.json")
    run_tool("calib-stereo", "solve", left, right, "--match-views", "([0-9]+)$", "-o", tmp_path / "rig.json")
    rig = vstcal.solve_stereo(left, right, match_views="([0-9]+)$")
    # Bit for bit as the tool when NumPy is not loaded; NumPy loads Debian's libblas.so.3 first, and then
    # ATLAS's LAPACK, which the stereo covariance calls, binds its BLAS there instead of libf77blas
    # (LD_DEBUG=bindings): the same numbers to a few ulps.
    assert_documents_close(without_provenance(rig), without_provenance(load(tmp_path / "rig.json")), rel=1e-9)
    assert len(rig["covariance"]["parameters"]) == 6
    with pytest.raises(vstcal.InputError) as e:
        vstcal.solve_stereo(left, right, match_views="(x)")
    message = tool_error("calib-stereo", "solve", left, right, "--match-views", "(x)", "-o", tmp_path / "r.json")
    # The same message, the option named as each caller named it: the tool's flag, Python's keyword.
    assert "does not match --match-views " in message
    assert str(e.value) == message.replace("--match-views", "match_views")
