"""Errors raise caustica.Error (a RuntimeError) with the command line's one-line message."""
import pytest

import caustica
from conftest import CORNELL, cli_error


def test_error_is_a_runtime_error():
    assert issubclass(caustica.Error, RuntimeError)


def error_of_scene(tmp_path, name, xml):
    """Loads the scene `xml` from Python and renders it with the CLI: the same one-line message."""
    scene = tmp_path / name
    scene.write_text(xml)
    with pytest.raises(caustica.Error) as e:
        caustica.load_scene(str(scene))
    assert str(e.value) == cli_error("render", scene, "-o", tmp_path / "x.exr")
    return str(e.value)


def test_bad_scene_has_the_cli_message(tmp_path):
    message = error_of_scene(tmp_path, "bad.xml", '<scene version="3.0.0">\n  <shape type="sphere">\n'
                             '    <float name="radius" value="abc"/>\n  </shape>\n</scene>\n')
    assert str(tmp_path / "bad.xml") in message


def test_missing_mesh_has_the_cli_message(tmp_path):
    message = error_of_scene(tmp_path, "mesh.xml", '<scene version="3.0.0">\n  <shape type="ply">\n'
                             '    <string name="filename" value="no-such-mesh.ply"/>\n  </shape>\n</scene>\n')
    assert "no-such-mesh.ply" in message


def test_missing_scene_file_names_it(tmp_path):
    missing = str(tmp_path / "nothing.xml")
    with pytest.raises(caustica.Error, match="nothing.xml"):
        caustica.load_scene(missing)


def test_defines_reach_the_scene_and_bad_ones_fail_as_in_the_cli(tmp_path):
    assert caustica.load_scene(CORNELL, width=40, height=30).resolution == (40, 30)
    with pytest.raises(caustica.Error) as e:
        caustica.load_scene(CORNELL, width="wide")
    assert str(e.value) == cli_error("render", CORNELL, "-D", "width=wide", "-o", tmp_path / "x.exr")


def test_bad_keyword_values():
    scene = caustica.load_scene(CORNELL, width=8, height=8)
    with pytest.raises(caustica.Error, match="unknown integrator 'nope'.*path"):
        caustica.render(scene, integrator="nope")
    cases = {
        "spp=-1": dict(spp=-1), "spp=0": dict(spp=0), "spp=2.5": dict(spp=2.5),
        "time=-1": dict(time=-1), "time=nan": dict(time=float("nan")),
        "resolution=(0, 10)": dict(resolution=(0, 10)), "resolution=(10,)": dict(resolution=(10,)),
        "resolution=(40000, 10)": dict(resolution=(40000, 10)),
        "device='gpu'": dict(device="gpu"), "threads=0": dict(threads=0),
        "stereo='sideways'": dict(stereo="sideways"), "aovs='dd:nodepth'": dict(aovs="dd:nodepth"),
    }
    for what, kwargs in cases.items():
        with pytest.raises(caustica.Error) as e:
            caustica.render(scene, **kwargs)
        assert len(str(e.value).splitlines()) == 1, what
    with pytest.raises(caustica.Error, match=r"^spp=-1: expected an integer in \[1, 16777216\]$"):
        caustica.render(scene, spp=-1)


def test_bad_integrator_parameter_value():
    scene = caustica.load_scene(CORNELL, width=8, height=8)
    with pytest.raises(caustica.Error, match="keyword chains"):
        caustica.render(scene, integrator="mlt", chains=-3)
