"""err-sim runs, reproj-report and corner detection from Python, against the tools on the same files
(and detection against OpenCV's cv2.findChessboardCorners); the statistics against NumPy."""
import cv2
import numpy as np
import pytest

from conftest import DATASETS, OPENCV_DATA, load, run_tool, tool_error, without_provenance


def test_err_sim_is_err_sim_run(vstcal, tmp_path):
    chain = DATASETS / "vst" / "seed001.json"
    run_tool("err-sim", "run", chain, "--samples", "3000", "--seed", "11", "-o", tmp_path / "report.json")
    report = vstcal.err_sim(str(chain), samples=3000, seed=11)
    assert report["format"] == "vstcal/err-sim-report@3"
    assert without_provenance(report) == without_provenance(load(tmp_path / "report.json"))
    # the thread count does not change a number (err-sim's sharding and merging rely on it)
    assert without_provenance(vstcal.err_sim(str(chain), samples=3000, seed=11, threads=1)) == without_provenance(report)


def test_err_sim_options_and_errors_as_the_tool(vstcal, tmp_path):
    chain = DATASETS / "vst" / "seed001.json"
    run_tool("err-sim", "run", chain, "--samples", "2000", "--seed", "5", "--only", "tracking,display",
             "-o", tmp_path / "report.json")
    assert without_provenance(vstcal.err_sim(str(chain), samples=2000, seed=5, only=["tracking", "display"])) == \
        without_provenance(load(tmp_path / "report.json"))
    message = tool_error("err-sim", "run", chain, "--samples", "100", "--only", "trackng", "-o", tmp_path / "x.json")
    with pytest.raises(vstcal.InputError) as e:
        vstcal.err_sim(str(chain), samples=100, only=["trackng"])
    # The same message, the option named as the caller named it: --only for the tool, only here.
    assert message.startswith("--only: ")
    assert str(e.value) == "only: " + message[len("--only: "):]


def test_reproj_report_is_the_tools(vstcal, tmp_path):
    corners = str(DATASETS / "seed000" / "distorted-noisy.json")
    run_tool("calib-tsai", corners, "-o", tmp_path / "a.json")
    run_tool("calib-dlt", corners, "-o", tmp_path / "b.json")
    cameras = [str(tmp_path / "a.json"), str(tmp_path / "b.json")]
    run_tool("reproj-report", *cameras, corners, "--grid", "4x3", "-o", tmp_path / "report.json")
    report = vstcal.reproj_report(cameras, corners, grid=(4, 3))
    assert without_provenance(report) == without_provenance(load(tmp_path / "report.json"))


def test_error_statistics_are_numpys(vstcal):
    values = np.random.default_rng(4).rayleigh(0.3, 1001)
    s = vstcal.error_statistics(values)
    assert s["n"] == 1001
    assert s["mean"] == pytest.approx(values.mean(), rel=1e-13)
    assert s["rms"] == pytest.approx(np.sqrt(np.mean(values ** 2)), rel=1e-13)
    assert s["median"] == pytest.approx(np.median(values), rel=1e-13)
    assert s["p95"] == pytest.approx(np.percentile(values, 95), rel=1e-13)
    assert s["max"] == values.max()
    assert vstcal.error_statistics(np.zeros(0)) is None
    with pytest.raises(vstcal.InputError, match=r"^values\[3\]: NaN"):
        vstcal.error_statistics(np.array([1.0, 2.0, 3.0, np.nan]))
    with pytest.raises(vstcal.InputError, match=r"^values: expected shape \(N,\), got \(2, 2\)"):
        vstcal.error_statistics(np.zeros((2, 2)))


@pytest.mark.skipif(not (OPENCV_DATA / "left01.jpg").exists(), reason="needs Debian's opencv-doc")
def test_detect_corners_is_calib_capture_detect_and_near_opencvs(vstcal, tmp_path):
    run_tool("calib-capture", "target", "--rows", "6", "--cols", "9", "--square-size", "25", "--dpi", "0",
             "-o", tmp_path / "board")
    target = tmp_path / "board.target.json"
    images = [OPENCV_DATA / f"left0{i}.jpg" for i in (1, 2, 3)]
    run_tool("calib-capture", "detect", target, *images, "-o", tmp_path / "corners.json")
    views = load(tmp_path / "corners.json")["views"]
    for image, view in zip(images, views):
        grey = cv2.imread(str(image), cv2.IMREAD_GRAYSCALE)
        found = vstcal.detect_corners(grey, str(target))
        assert found["status"] == "found" and found["reason"] == ""
        expected = np.array(view["points"])
        np.testing.assert_array_equal(found["points"], expected[:, :3])
        np.testing.assert_array_equal(found["pixels"], expected[:, 3:5])
        assert found["ids"].tolist() == list(range(54))
        # OpenCV's own detector and refinement on the same image: the same corners, in the same order
        # (vstcal's corner 0 is the board's top-left; OpenCV may start from the other end).
        ok, cv_corners = cv2.findChessboardCorners(grey, (9, 6))
        assert ok
        cv_corners = cv2.cornerSubPix(grey, cv_corners, (5, 5), (-1, -1),
                                      (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 50, 1e-3)).reshape(-1, 2)
        if np.linalg.norm(cv_corners[0] - found["pixels"][0]) > np.linalg.norm(cv_corners[-1] - found["pixels"][0]):
            cv_corners = cv_corners[::-1]
        assert np.abs(cv_corners - found["pixels"]).max() < 0.5
    blank = np.full((480, 640), 128, dtype=np.uint8)
    assert vstcal.detect_corners(blank, str(target))["status"] == "not-found"


def test_detect_corners_refuses_bad_images(vstcal, tmp_path):
    run_tool("calib-capture", "target", "--rows", "6", "--cols", "9", "--square-size", "25", "--dpi", "0",
             "-o", tmp_path / "board")
    target = str(tmp_path / "board.target.json")
    with pytest.raises(vstcal.InputError, match=r"^image: expected dtype uint8, got float64"):
        vstcal.detect_corners(np.zeros((10, 10)), target)
    with pytest.raises(vstcal.InputError, match=r"^image: expected a grey image of shape \(H, W\), got 3 dimensions"):
        vstcal.detect_corners(np.zeros((10, 10, 3), dtype=np.uint8), target)
    with pytest.raises(vstcal.InputError, match=r"^image: the array is not C-contiguous"):
        vstcal.detect_corners(np.zeros((20, 20), dtype=np.uint8)[::2], target)
