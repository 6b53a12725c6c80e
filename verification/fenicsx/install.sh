#!/usr/bin/env bash
# Installs what the FEniCSx reference scripts need: DOLFINx 0.5 from Debian
# (python3-dolfinx, for /usr/bin/python3) and SciPy. Idempotent: does nothing
# when `import dolfinx, scipy` already works with that interpreter.
#
# The other route, the binary wheel `dolfinx-solver-real`, needs Python 3.12
# and ships a newer DOLFINx whose Python API differs from 0.5 (mesh creation,
# function spaces); solve.py targets the 0.5 API (see ../README.md).
#
# Usage: bash verification/fenicsx/install.sh    (root, or sudo available)
set -euo pipefail
PY=${FENICSX_PYTHON:-/usr/bin/python3}
if "$PY" -c "import dolfinx, scipy, ufl, petsc4py" 2>/dev/null; then
  echo "FEniCSx already available: DOLFINx $("$PY" -c 'import dolfinx; print(dolfinx.__version__)') ($PY)"
  exit 0
fi
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends python3-dolfinx python3-scipy build-essential
"$PY" -c "import dolfinx; print('installed DOLFINx', dolfinx.__version__)"
