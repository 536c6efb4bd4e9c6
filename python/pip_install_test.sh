#!/bin/bash
# The pip route of docs/python.md end to end, without network: a venv that sees Debian's
# packages, `pip install --no-build-isolation --no-deps` of the source tree into it (setup.py
# builds the module with CMake in a folder of its own), then nsbridge imported from the venv
# (not from build/python) runs a short scene.
#   pip_install_test.sh SOURCE_DIR PYTHON
set -euo pipefail
src=$1
python=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/nsbridge-pip.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
unset PYTHONPATH
"$python" -m venv --system-site-packages "$tmp/venv"
NSBRIDGE_BUILD_DIR="$tmp/build" "$tmp/venv/bin/pip" install --no-build-isolation --no-deps \
  --no-index --quiet "$src"
cd "$tmp"
"$tmp/venv/bin/python" - "$src" <<'PY'
import pathlib, sys
import nsbridge
here = pathlib.Path(nsbridge.__file__).resolve()
assert pathlib.Path(sys.prefix).resolve() in here.parents, f"imported from {here}"
r = nsbridge.run(pathlib.Path(sys.argv[1]) / "scenes/bouncing-ball.toml",
                 overrides=["solver.end_time=0.5"])
assert r.status == "completed" and r.history["t"][-1] == 0.5, r
print(f"nsbridge {nsbridge.__version__} from {here.parent}: {r}")
PY
