#!/usr/bin/env bash
# ctest python_pip_install: `pip install .` of the source tree into a fresh virtual environment
# (with the system's site packages, for Debian's numpy), then imports caustica and renders a tiny
# image. Usage: pip_install_check.sh PYTHON VENV_DIR PIP_BUILD_DIR
# Environment (python/CMakeLists.txt): CAUSTICA_SOURCE_DIR; CAUSTICA_CXX_COMPILER and
# CAUSTICA_CXX_LAUNCHER (ccache) and,
# for a CUDA build, CAUSTICA_CUDA_BUILD=ON and CAUSTICA_CUDA_COMPILER. The wheel is compiled with
# the build's launcher and flags in a folder beside the build folder (same depth below the source,
# so ccache's base_dir makes every path the same): the libraries come out of the cache.
set -euo pipefail
python="$1" venv="$2" build="$3"
src="${CAUSTICA_SOURCE_DIR:?}"

rm -rf "$venv"
"$python" -m venv --system-site-packages "$venv"
# scikit-build-core comes from the package index (build isolation): say so clearly when it cannot.
probe="$(mktemp -d)"
if ! "$venv/bin/python" -m pip download --quiet --no-deps --dest "$probe" --timeout 30 scikit-build-core; then
    echo "python_pip_install: FAILED: cannot download scikit-build-core from the package index (PyPI):" \
         "'pip install .' needs it; check the network or PIP_INDEX_URL" >&2
    exit 1
fi
rm -rf "$probe"

args=(--config-settings="build-dir=$build")
# The build's compiler by its path: ccache's hash tells /usr/bin/c++ and x86_64-linux-gnu-g++ apart.
if [ -n "${CAUSTICA_CXX_COMPILER:-}" ]; then
    args+=(--config-settings="cmake.define.CMAKE_CXX_COMPILER=$CAUSTICA_CXX_COMPILER")
fi
launcher="${CAUSTICA_CXX_LAUNCHER:-}"
if [ -n "$launcher" ]; then
    export CCACHE_BASEDIR="$src"
    args+=(--config-settings="cmake.define.CMAKE_CXX_COMPILER_LAUNCHER=$launcher")
fi
if [ "${CAUSTICA_CUDA_BUILD:-OFF}" = ON ]; then
    args+=(--config-settings=cmake.define.CAUSTICA_CUDA=ON
           --config-settings="cmake.define.CMAKE_CUDA_COMPILER=$CAUSTICA_CUDA_COMPILER")
    if [ -n "$launcher" ]; then
        args+=(--config-settings="cmake.define.CMAKE_CUDA_COMPILER_LAUNCHER=$launcher")
    fi
fi
start=$(date +%s)
(cd "$src" && "$venv/bin/python" -m pip install --no-cache-dir "${args[@]}" .)
echo "python_pip_install: pip install . took $(( $(date +%s) - start )) s"

cd "$venv"  # not the source tree: the installed package must be the one imported
"$venv/bin/python" - "$src" "$venv" <<'PY'
import os, sys
import numpy as np
import caustica
src, venv = sys.argv[1], sys.argv[2]
assert os.path.realpath(caustica.__file__).startswith(os.path.realpath(venv)), caustica.__file__
scene = caustica.load_scene(os.path.join(src, "scenes", "cornell-box", "scene.xml"), width=8, height=6)
image = caustica.render(scene, spp=2, seed=1)
assert image.shape == (6, 8, 3) and image.dtype == np.float32 and image.mean() > 0, image.shape
print("python_pip_install: imported", caustica.__file__, "and rendered", image.shape)
PY
