"""vstcal.Camera: project, unproject and Jacobians of every lens model, against OpenCV's Python API
(cv2.projectPoints and its Jacobian, cv2.undistortPoints), against calib-synth's pixels, and bad
arrays refused naming the argument."""
import cv2
import numpy as np
import pytest

from conftest import DATASETS, load, run_tool

# A 640×480 camera and the distortion of each model in OpenCV's coefficient order.
K = np.array([[600.0, 0.0, 322.5], [0.0, 590.0, 241.0], [0.0, 0.0, 1.0]])
DISTORTION = {
    "none": np.zeros(0),
    "radial-tangential": np.array([-0.21, 0.07, 0.001, -0.0015, -0.01]),
    "rational": np.array([-0.21, 0.07, 0.001, -0.0015, -0.01, 0.05, 0.01, 0.002]),
}


def points_in_view(n=200, seed=1):
    rng = np.random.default_rng(seed)
    z = rng.uniform(500.0, 2000.0, n)
    x = rng.uniform(-0.45, 0.45, n) * z
    y = rng.uniform(-0.35, 0.35, n) * z
    return np.ascontiguousarray(np.stack([x, y, z], axis=1))


def test_lens_models_list_every_model(vstcal):
    models = vstcal.lens_models()
    assert list(models) == ["none", "radial-tangential", "rational", "kannala-brandt"]
    assert models["kannala-brandt"][5:] == ["k1", "k2", "k3", "k4"]
    assert models["rational"][-3:] == ["k4", "k5", "k6"]
    for name, d in DISTORTION.items():
        assert len(models[name]) == 5 + len(d)


@pytest.mark.parametrize("model", list(DISTORTION))
def test_project_matches_opencv_project_points_and_its_jacobian(vstcal, model):
    d = DISTORTION[model]
    cam = vstcal.Camera.from_K(K, (640, 480), model, d if len(d) else None)
    assert cam.model == model and cam.image_size == (640, 480)
    np.testing.assert_array_equal(cam.K, K)
    p = points_in_view()
    px, d_params, d_points = cam.project_jacobians(p)
    np.testing.assert_allclose(px, cam.project(p), rtol=0, atol=1e-10)  # one projection (Jets: to an ulp)

    cv_d = np.zeros(4) if len(d) == 0 else d
    cv_px, cv_jac = cv2.projectPoints(p, np.zeros(3), np.zeros(3), K, cv_d)
    np.testing.assert_allclose(px, cv_px.reshape(-1, 2), rtol=0, atol=1e-9)
    # OpenCV's Jacobian columns: rvec(3), tvec(3), fx, fy, cx, cy, distortion; rows u0, v0, u1, ...
    cv_jac = cv_jac.reshape(-1, 2, cv_jac.shape[1])
    np.testing.assert_allclose(d_points, cv_jac[:, :, 3:6], rtol=1e-7, atol=1e-9)  # R = I: d/dt = d/dp
    np.testing.assert_allclose(d_params[:, :, 0:4], cv_jac[:, :, 6:10], rtol=1e-7, atol=1e-9)
    if len(d):
        np.testing.assert_allclose(d_params[:, :, 5:], cv_jac[:, :, 10:10 + len(d)], rtol=1e-7, atol=1e-9)
    # The skew column (OpenCV has none): d u / d s = y_d, d v / d s = 0 — from the pixels themselves.
    np.testing.assert_allclose(d_params[:, 0, 4], (px[:, 1] - K[1, 2]) / K[1, 1], rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(d_params[:, 1, 4], 0.0)


@pytest.mark.parametrize("model", list(DISTORTION))
def test_unproject_inverts_project_and_matches_opencv_undistort(vstcal, model):
    d = DISTORTION[model]
    cam = vstcal.Camera.from_K(K, (640, 480), model, d if len(d) else None)
    p = points_in_view(seed=2)
    rays = cam.unproject(cam.project(p))
    np.testing.assert_allclose(rays[:, :2], p[:, :2] / p[:, 2:], rtol=0, atol=1e-10)
    np.testing.assert_array_equal(rays[:, 2], 1.0)
    cv_d = np.zeros(4) if len(d) == 0 else d
    cv_xy = cv2.undistortPointsIter(cam.project(p).reshape(-1, 1, 2), K, cv_d, None, None,
                                    (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 200, 1e-15)).reshape(-1, 2)
    np.testing.assert_allclose(rays[:, :2], cv_xy, rtol=0, atol=1e-6)  # OpenCV's fixed-point iteration


def test_one_point_and_points_behind_the_camera(vstcal):
    cam = vstcal.Camera("radial-tangential", np.array([600.0, 590, 322.5, 241, 0, *DISTORTION["radial-tangential"]]),
                        (640, 480))
    one = cam.project(np.array([10.0, -20.0, 1000.0]))
    assert one.shape == (2,)
    np.testing.assert_array_equal(one, cam.project(np.array([[10.0, -20.0, 1000.0]]))[0])
    behind = cam.project(np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]))
    assert np.isnan(behind[0]).all() and np.isfinite(behind[1]).all()
    assert cam.in_image(np.array([[-0.5, -0.5], [639.6, 0.0]])).tolist() == [True, False]
    assert cam.param_names[5:] == ["k1", "k2", "p1", "p2", "k3"]


def test_project_reproduces_calib_synth_pixels(vstcal, tmp_path):
    """calib-synth projects its grid through the truth camera, noise 0: the binding's projection of the same
    points through the same camera file gives the same pixels."""
    out = tmp_path / "clean.json"
    run_tool("calib-synth", "-o", out, "--image-size", "640x480", "--fx", "600",
             "--distortion=-0.2,0.05,0.001,-0.002,0", "--noise", "0", "--seed", "3")
    truth = load(tmp_path / "clean.truth.json")
    cam = vstcal.load_camera(tmp_path / "clean.truth.json")
    assert cam.model == "radial-tangential"
    R = np.array(truth["camera_from_world"]["R"])
    t = np.array(truth["camera_from_world"]["t"])
    rows = np.array([p for v in load(out)["views"] for p in v["points"]])
    p_cam = np.ascontiguousarray(rows[:, :3] @ R.T + t)
    np.testing.assert_allclose(cam.project(p_cam), rows[:, 3:5], rtol=0, atol=1e-9)


@pytest.mark.parametrize("bad, message", [
    (np.zeros((4, 2)), "points: expected shape (N, 3) or (3,), got (4, 2)"),
    (np.zeros((4, 3), dtype=np.float32), "points: expected dtype float64, got float32"),
    (np.zeros((3, 4)).T, "points: the array is not C-contiguous"),
    (np.array([[1.0, 2.0, 3.0], [4.0, np.nan, 6.0]]), "points[1, 1]: NaN"),
    (np.array([[1.0, 2.0, np.inf]]), "points[0, 2]: an infinite value"),
    ([[1.0, 2.0, 3.0]], "points: expected a NumPy array of shape (N, 3) or (3,), got a list"),
])
def test_bad_arrays_are_refused_naming_the_argument(vstcal, bad, message):
    cam = vstcal.Camera.from_K(K, (640, 480))
    with pytest.raises(vstcal.InputError) as e:
        cam.project(bad)
    assert str(e.value).startswith(message)
    assert e.value.exit_code == 2 and isinstance(e.value, ValueError)


def test_bad_camera_arguments(vstcal):
    with pytest.raises(vstcal.InputError, match=r'^model: unknown lens model "fisheye"; use one of'):
        vstcal.Camera("fisheye", np.zeros(5), (640, 480))
    with pytest.raises(vstcal.InputError, match=r"^params: expected shape \(10,\), got \(5,\)"):
        vstcal.Camera("radial-tangential", np.array([600.0, 600, 320, 240, 0]), (640, 480))
    with pytest.raises(vstcal.InputError, match=r"^image_size:"):
        vstcal.Camera("none", np.array([600.0, 600, 320, 240, 0]), (0, 480))
    with pytest.raises(vstcal.InputError, match=r"^unproject|^pixels\[0, 0\]: NaN"):
        vstcal.Camera.from_K(K, (640, 480)).unproject(np.array([[np.nan, 1.0]]))
