#!/usr/bin/env bash
# Installs DOLFINx 0.11 for the side-by-side speed comparison (SPEED.md,
# speed.py variant B): the binary wheel `dolfinx-solver-real` (DOLFINx with
# real-scalar PETSc, MUMPS included) in a Python 3.12 venv, since the wheel
# needs Python 3.12. DOLFINx 0.5 from Debian (install.sh, /usr/bin/python3)
# stays the reference of the same-discretization (exactness) comparison.
#
# The venv goes to $FENICSX_011_VENV, default ~/.cache/ctc/dolfinx-0.11.
# Python 3.12 is taken from pyenv (`pyenv prefix 3.12`), else python3.12 on
# the PATH. Idempotent: does nothing when the venv already imports dolfinx.
# `import dolfinx_solver` must come before `import dolfinx` (it sets up the
# wheel's shared libraries); speed.py does that when it finds the module.
#
# Usage: bash verification/fenicsx/install-0.11.sh
# Then:  FENICSX_PYTHON=$(bash verification/fenicsx/install-0.11.sh --python)
set -euo pipefail
VENV=${FENICSX_011_VENV:-$HOME/.cache/ctc/dolfinx-0.11}
probe() {
  "$VENV/bin/python" -c "import dolfinx_solver, dolfinx, ufl, petsc4py, scipy; print(dolfinx.__version__)" 2>/dev/null
}
if [ "${1:-}" = "--python" ]; then
  probe >/dev/null && { echo "$VENV/bin/python"; exit 0; }
  echo "DOLFINx 0.11 is not installed in $VENV: run install-0.11.sh" >&2
  exit 1
fi
if v=$(probe); then
  echo "DOLFINx $v already available ($VENV/bin/python)"
  exit 0
fi
PY312=""
if command -v pyenv >/dev/null 2>&1; then
  prefix=$(pyenv prefix 3.12 2>/dev/null || true)
  if [ -z "$prefix" ]; then
    v=$(pyenv versions --bare 2>/dev/null | grep -E '^3\.12(\.|$)' | tail -n 1 || true)
    [ -n "$v" ] && prefix=$(pyenv prefix "$v")
  fi
  [ -n "$prefix" ] && [ -x "$prefix/bin/python3.12" ] && PY312="$prefix/bin/python3.12"
fi
if [ -z "$PY312" ] && command -v python3.12 >/dev/null 2>&1; then
  PY312=$(command -v python3.12)
fi
if [ -z "$PY312" ]; then
  echo "install-0.11.sh: no Python 3.12 (pyenv install 3.12, or python3.12 on the PATH)" >&2
  exit 1
fi
mkdir -p "$(dirname "$VENV")"
"$PY312" -m venv "$VENV"
"$VENV/bin/python" -m pip install --quiet --upgrade pip
"$VENV/bin/python" -m pip install --quiet dolfinx-solver-real scipy
v=$(probe) || {
  echo "install-0.11.sh: the venv $VENV does not import dolfinx_solver + dolfinx:" >&2
  "$VENV/bin/python" -c "import dolfinx_solver, dolfinx" >&2 || true
  exit 1
}
echo "installed DOLFINx $v ($VENV/bin/python)"
