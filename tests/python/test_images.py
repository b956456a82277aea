"""read_image / write_image / compare: io/ and film/image_compare on numpy arrays."""
import json

import numpy as np
import pytest

import caustica
from conftest import run_cli


def test_write_read_round_trip_and_compare(tmp_path):
    rng = np.random.default_rng(1)
    a = rng.random((5, 7, 3), dtype=np.float32)
    for ext in ("pfm", "exr"):
        path = str(tmp_path / f"a.{ext}")
        caustica.write_image(path, a)
        np.testing.assert_array_equal(caustica.read_image(path), a)
    b = a * 1.1
    m = caustica.compare(b, a.astype(np.float64))  # any real dtype converts
    np.testing.assert_allclose(m["relmse"], np.mean((b - a) ** 2 / (a.astype(np.float64) ** 2 + 0.01)), rtol=1e-5)
    assert caustica.compare(a, a)["relmse"] == 0
    # The same figure as `caustica compare`.
    caustica.write_image(str(tmp_path / "b.exr"), b)
    cli = json.loads(run_cli("compare", "--json", tmp_path / "b.exr", tmp_path / "a.exr").stdout)
    assert m["relmse"] == pytest.approx(cli["relmse"], rel=1e-6)


def test_bad_arrays_and_paths():
    with pytest.raises(caustica.Error, match=r"shape \(height, width, 3\)"):
        caustica.write_image("x.exr", np.zeros((4, 4)))
    with pytest.raises(caustica.Error, match="no-such.exr"):
        caustica.read_image("no-such.exr")
    with pytest.raises(caustica.Error):
        caustica.compare(np.zeros((2, 2, 3)), np.zeros((3, 2, 3)))
