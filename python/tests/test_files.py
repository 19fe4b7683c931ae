"""vstcal.read / vstcal.write / vstcal.convert_camera against the tools on the same files: what the
binding writes the tools read and solve to the same numbers, bad files give the tools' one-line
message, and nothing is written for a refused document."""
import json
import shutil

import pytest

from conftest import DATASETS, SOURCE_DIR, load, run_tool, tool_error, without_provenance


@pytest.mark.parametrize("path", [
    "seed000/clean.json", "seed000/clean.truth.json", "zedmini/planar-noisy.json", "vst/seed001.json",
])
def test_read_gives_the_file_as_python_objects(vstcal, path):
    document = vstcal.read(DATASETS / path)
    assert document == load(DATASETS / path)
    assert list(document) == list(load(DATASETS / path))  # file order kept


def test_write_then_the_tool_solves_the_same(vstcal, tmp_path):
    corners = vstcal.read(DATASETS / "seed000" / "noisy.json")
    corners["views"] = corners["views"][:7]  # a document edited in Python
    vstcal.write(tmp_path / "edited.json", corners)
    assert vstcal.read(tmp_path / "edited.json") == corners
    shutil.copy(tmp_path / "edited.json", tmp_path / "copy.json")
    # vstcal's layout: writing what was read gives the same bytes
    vstcal.write(tmp_path / "again.json", vstcal.read(tmp_path / "copy.json"))
    assert (tmp_path / "again.json").read_bytes() == (tmp_path / "edited.json").read_bytes()
    run_tool("calib-dlt", tmp_path / "edited.json", "-o", tmp_path / "camera.json")
    camera = load(tmp_path / "camera.json")
    assert camera["fit"]["n_points"] == sum(len(v["points"]) for v in corners["views"])


def test_a_bad_file_gives_the_tools_message(vstcal, tmp_path):
    corners = load(DATASETS / "seed000" / "clean.json")
    corners["image_size"] = [1280, -1]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(corners))
    message = tool_error("calib-dlt", bad, "-o", tmp_path / "camera.json")
    with pytest.raises(vstcal.InputError) as e:
        vstcal.read(bad)
    assert str(e.value) == message
    assert not (tmp_path / "camera.json").exists()


def test_format_expected_and_unknown(vstcal, tmp_path):
    with pytest.raises(vstcal.InputError, match=r'format: this is a "vstcal/camera@1" file, expected "vstcal/correspondences@1"'):
        vstcal.read(DATASETS / "seed000" / "clean.truth.json", format="vstcal/correspondences@1")
    (tmp_path / "x.json").write_text('{"format": "colmap"}')
    with pytest.raises(vstcal.InputError, match=r'format: "colmap" is not a vstcal format'):
        vstcal.read(tmp_path / "x.json")
    assert "vstcal/stereo@1" in vstcal.formats()


def test_write_refuses_a_bad_document_and_writes_nothing(vstcal, tmp_path):
    camera = vstcal.read(DATASETS / "seed000" / "clean.truth.json")
    camera["K"][1][0] = 3.0
    with pytest.raises(vstcal.InputError, match=r"^<document>: K"):
        vstcal.write(tmp_path / "camera.json", camera)
    camera["K"][1][0] = float("nan")
    with pytest.raises(vstcal.InputError, match=r"^document: not a JSON document"):
        vstcal.write(tmp_path / "camera.json", camera)
    assert not (tmp_path / "camera.json").exists()


def test_chain_written_beside_its_cameras_is_what_err_sim_reads(vstcal, tmp_path):
    chain = vstcal.read(DATASETS / "vst" / "seed001.json")
    (tmp_path / "vst").mkdir()
    # Its cameras are "../zedmini/clean.truth.json", resolved against the file's folder, as err-sim does.
    with pytest.raises(vstcal.InputError, match=r"zedmini/clean.truth.json"):
        vstcal.write(tmp_path / "vst" / "chain.json", chain)
    assert not (tmp_path / "vst" / "chain.json").exists()
    (tmp_path / "zedmini").mkdir()
    shutil.copy(DATASETS / "zedmini" / "clean.truth.json", tmp_path / "zedmini")
    vstcal.write(tmp_path / "vst" / "chain.json", chain)
    run_tool("err-sim", "normalize", DATASETS / "vst" / "seed001.json", "-o", tmp_path / "vst" / "a.json")
    run_tool("err-sim", "normalize", tmp_path / "vst" / "chain.json", "-o", tmp_path / "vst" / "b.json")
    a, b = load(tmp_path / "vst" / "a.json"), load(tmp_path / "vst" / "b.json")
    assert b["cameras"] == chain["cameras"]  # as written, now beside the copy
    assert {k: v for k, v in a.items() if k not in ("provenance", "cameras")} == \
        {k: v for k, v in b.items() if k not in ("provenance", "cameras")}


@pytest.mark.parametrize("to, extension", [("opencv", "yaml"), ("mrcal", "cameramodel"), ("camera", "json")])
def test_convert_camera_is_calib_convert(vstcal, tmp_path, to, extension):
    source = DATASETS / "seed000" / "distorted-noisy.truth.json"
    out = tmp_path / f"camera.{extension}"
    cli = run_tool("calib-convert", source, "-o", out)
    text, notes = vstcal.convert_camera(source, to)
    expected = out.read_text()
    if to == "camera":
        assert without_provenance(json.loads(text)) == without_provenance(json.loads(expected))
    else:  # the provenance is one comment line
        strip = lambda t: [line for line in t.splitlines() if "vstcal provenance" not in line]
        assert strip(text) == strip(expected)
    assert [f"calib-convert: note: {n}" for n in notes] == [l for l in cli.stderr.splitlines() if ": note: " in l]
