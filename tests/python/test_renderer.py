"""caustica.Renderer: step / finished / develop / stats / save / load."""
import numpy as np
import pytest

import caustica
from conftest import CORNELL


def test_step_save_load_round_trip(tmp_path):
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    whole = caustica.render(scene, spp=4, spp_per_pass=1, seed=9)

    first = caustica.Renderer(scene, spp=4, spp_per_pass=1, seed=9)
    assert not first.finished
    first.step()
    first.step()
    assert first.progress()["spp"] == 2 and not first.finished
    ckpt = str(tmp_path / "r.ckpt")
    first.save(ckpt)

    second = caustica.Renderer(scene, spp=4, spp_per_pass=1, seed=9)
    second.load(ckpt)
    assert second.progress()["spp"] == 2
    while not second.finished:
        second.step()
    # The resumed render continues the same sample streams: the same image as one render.
    np.testing.assert_array_equal(second.develop(), whole)


def test_load_refuses_another_render(tmp_path):
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    r = caustica.Renderer(scene, spp=2, seed=1)
    r.step()
    ckpt = str(tmp_path / "r.ckpt")
    r.save(ckpt)
    with pytest.raises(caustica.Error, match="seed"):
        caustica.Renderer(scene, spp=2, seed=2).load(ckpt)
    with pytest.raises(caustica.Error, match="missing.ckpt"):
        r.load(str(tmp_path / "missing.ckpt"))


def test_stats_and_properties():
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    r = caustica.Renderer(scene, integrator="path", spp=2, seed=4, device="cpu")
    with pytest.raises(caustica.Error, match="no image yet"):
        r.develop()
    r.run()
    assert r.finished
    s = r.stats()
    assert s["spp"] == 2 and s["samples"] == 2 * 16 * 16 and s["rays"] > 0
    assert s["integrator"] == "path" and s["seed"] == 4 and s["device"] == "cpu" and s["seconds"] > 0
    assert r.integrator == "path" and r.device == "cpu" and not r.stereo and not r.has_aovs
    assert r.aovs() == {}
