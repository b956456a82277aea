"""Shared helpers of the Python module's tests (run by ctest: python/CMakeLists.txt sets
PYTHONPATH to BUILD/python, CAUSTICA_BINARY and CAUSTICA_SOURCE_DIR)."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("CAUSTICA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = os.environ.get("CAUSTICA_BINARY", str(SOURCE_DIR / "build" / "caustica"))
CORNELL = str(SOURCE_DIR / "scenes" / "cornell-box" / "scene.xml")
GLASS = str(SOURCE_DIR / "scenes" / "glass-caustic" / "scene.xml")


def run_cli(*args, check=True):
    """Runs `caustica ARGS`; returns the CompletedProcess (text)."""
    p = subprocess.run([BINARY, *map(str, args)], capture_output=True, text=True, timeout=120)
    if check and p.returncode != 0:
        raise AssertionError(f"caustica {' '.join(map(str, args))} failed:\n{p.stderr}")
    return p


def cli_error(*args):
    """The one-line message the CLI prints for a failing command (after 'caustica: error: ')."""
    p = run_cli(*args, check=False)
    assert p.returncode != 0, p.stdout
    lines = [l for l in p.stderr.splitlines() if l.startswith("caustica: error: ")]
    assert len(lines) == 1, p.stderr
    return lines[0][len("caustica: error: "):]


def read_pfm(path):
    """A colour PFM as float32 (H, W, 3), rows top first (PFM stores them bottom first)."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1].astype(np.float32)


@pytest.fixture
def cli_image(tmp_path):
    """cli_image(scene, *args) renders with the CLI to a PFM and returns it as an array."""
    def render(scene, *args):
        out = tmp_path / f"cli{len(list(tmp_path.iterdir()))}.pfm"
        run_cli("render", scene, "-q", "--checkpoint-every", "0", "-o", out, *args)
        return read_pfm(out)
    return render
