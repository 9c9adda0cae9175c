#!/bin/bash
# Installs the 2D anchors of issue 66 on a fresh Debian/Ubuntu: CGAL (headers) and the
# CGAL Mesh_2 driver tools/cgal_mesh2/cgal_mesh2, gmsh, and a Python venv with Triangle
# (the `triangle` package, Shewchuk's C code inside), numpy and meshio.
#
# Usage: tools/install_refs_2d.sh [VENV]   (default VENV: .venv in the checkout)
# Then: tests/mesh2d_anchors.rs finds the venv through FEPRE_PYTHON=VENV/bin/python (or
# .venv/bin/python), the driver at tools/cgal_mesh2/cgal_mesh2 (or FEPRE_CGAL_MESH2), and
# gmsh on PATH; tools/bench_mesh2d_anchors.py runs under VENV/bin/python.
# apt-get needs root (or sudo); set SKIP_APT=1 where the packages are already there.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
VENV=${1:-$ROOT/.venv}
if [ "${SKIP_APT:-0}" != 1 ]; then
  SUDO=; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends \
    g++ make libcgal-dev libgmp-dev libmpfr-dev libboost-dev gmsh python3 python3-venv
fi
make -C "$ROOT/tools/cgal_mesh2"
python3 -m venv "$VENV"
"$VENV/bin/pip" install --quiet triangle numpy meshio
"$VENV/bin/python" -c "import triangle, numpy, meshio; print('triangle, numpy, meshio: ok')"
"$ROOT/tools/cgal_mesh2/cgal_mesh2" "$ROOT/cad_fixtures/regions/convex.poly" --area 0.01 >/dev/null && echo "cgal_mesh2: ok"
gmsh --version >/dev/null 2>&1 && echo "gmsh: ok"
