"""caustica.render(): arrays equal to the CLI's image, AOVs, stereo pairs, progress."""
import numpy as np
import pytest

import caustica
from conftest import CORNELL, GLASS


def test_image_is_float32_hwc_and_equals_the_cli_image(cli_image):
    # Same scene, seed and spp: the same samples, accumulated in the same order per pixel, so the
    # images are bit-identical (the CLI's PFM stores the float32 values unchanged).
    scene = caustica.load_scene(CORNELL, width=24, height=16)
    image = caustica.render(scene, spp=4, seed=7)
    assert isinstance(image, np.ndarray)
    assert image.dtype == np.float32 and image.shape == (16, 24, 3)
    assert image.mean() > 0
    np.testing.assert_array_equal(image, cli_image(CORNELL, "-D", "width=24", "-D", "height=16",
                                                   "--spp", 4, "--seed", 7))


def test_sppm_equals_the_cli_image(cli_image):
    scene = caustica.load_scene(GLASS, width=16, height=16)
    image = caustica.render(scene, integrator="sppm", spp=2, seed=3, photon_count=20000)
    cli = cli_image(GLASS, "-D", "width=16", "-D", "height=16", "--integrator", "sppm", "--spp", 2,
                    "--seed", 3, "--sppm-photons", 20000)
    np.testing.assert_array_equal(image, cli)


def test_scene_serves_several_renders_and_resolution_overrides():
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    a = caustica.render(scene, spp=2, seed=1)
    b = caustica.render(scene, spp=2, seed=1)
    c = caustica.render(scene, spp=2, seed=2)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)
    assert caustica.render(scene, spp=1, resolution=(20, 10)).shape == (10, 20, 3)
    assert scene.resolution == (16, 16)  # the scene itself is unchanged


def test_integrator_parameters_are_keywords():
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    direct_only = caustica.render(scene, spp=2, seed=1, max_depth=2)
    full = caustica.render(scene, spp=2, seed=1)
    assert direct_only.mean() < full.mean()
    with pytest.warns(RuntimeWarning, match="no_such_parameter"):
        caustica.render(scene, spp=1, no_such_parameter=3)


def test_aovs_dict():
    scene = caustica.load_scene(CORNELL, width=16, height=12)
    out = caustica.render(scene, spp=2, seed=1, aovs="dd:depth,nn:sh_normal,alb:albedo")
    assert list(out) == [caustica.IMAGE_KEY, "dd", "nn", "alb"]
    assert out["image"].shape == (12, 16, 3)
    np.testing.assert_array_equal(out["image"], caustica.render(scene, spp=2, seed=1))
    assert out["dd"].shape == (12, 16, 1) and out["dd"].dtype == np.float32
    assert out["nn"].shape == (12, 16, 3) and out["alb"].shape == (12, 16, 3)
    # The box is open towards the camera: rays through the middle hit (depth beyond the box front),
    # some at the border miss (depth 0, normal 0). Normals are pixel averages: unit length inside
    # a face, shorter where a pixel straddles an edge.
    hit = out["dd"][..., 0] > 0
    assert hit[4:8, 6:10].all() and (out["dd"][hit] > 1.0).all()
    norm = np.linalg.norm(out["nn"], axis=-1)
    assert (norm <= 1 + 1e-5).all() and (abs(norm[hit] - 1) < 1e-5).mean() > 0.5
    assert (out["nn"][~hit] == 0).all()
    assert (out["alb"] >= 0).all() and (out["alb"] <= 1).all() and out["alb"][hit].max() > 0.1


def test_stereo_pair_equals_the_cli_side_by_side_image(cli_image):
    scene = caustica.load_scene(CORNELL, width=16, height=12)
    left, right = caustica.render(scene, spp=2, seed=5, stereo={"mode": "off-axis", "interocular": 0.2})
    assert left.shape == right.shape == (12, 16, 3)
    assert not np.array_equal(left, right)
    both = cli_image(CORNELL, "-D", "width=16", "-D", "height=12", "--spp", 2, "--seed", 5,
                     "--stereo", "off-axis", "--interocular", 0.2)
    np.testing.assert_array_equal(np.concatenate([left, right], axis=1), both)


def test_progress_callback_between_passes_and_stopping_early():
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    seen = []
    caustica.render(scene, spp=6, spp_per_pass=2, progress=seen.append)
    assert [p["spp"] for p in seen] == [2, 4, 6]
    assert all(p["target"] == 6 for p in seen) and seen[-1]["seconds"] > 0

def test_progress_callback_returning_false_stops_quietly(capfd):
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    calls = []
    r = caustica.Renderer(scene, spp=8, spp_per_pass=1)
    assert r.run(lambda p: calls.append(p) or len(calls) < 3)  # stopped by the callback
    assert len(calls) == 3 and r.progress()["spp"] == 3 and not r.finished
    assert capfd.readouterr().err == ""  # none of the CLI's "continue with --resume" lines
