#!/usr/bin/env bash
# Installs what the `petsc` feature of ctc-petsc needs on Debian: the system
# PETSc (real scalars, with Open MPI, MUMPS, hypre, ParMETIS) and libclang for
# bindgen. Idempotent: a second run only checks that everything is there.
#   bash petsc/install.sh           the feature
#   bash petsc/install.sh --probe   and what the diagnostic replay
#                                   petsc/gamg_probe.py needs (petsc4py, scipy)
set -euo pipefail

# libopenblas0-serial: an optimised BLAS for MUMPS's dense kernels (Debian's
# default is the reference BLAS, with which a MUMPS factorization of a 14k-dof
# 3D tangent took 2.5 s instead of 0.2 s); serial, since MPI ranks already
# use the cores.
packages=(libpetsc-real-dev libclang-dev clang pkg-config openmpi-bin libopenmpi-dev libmetis-dev libopenblas0-serial)
if [ "${1:-}" = "--probe" ]; then
  packages+=(python3-petsc4py python3-scipy python3-numpy)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
fi

# The feature finds PETSc through pkg-config (PETSc.pc) or PETSC_DIR.
if ! pkg-config --exists PETSc && [ -z "${PETSC_DIR:-}" ]; then
  echo "PETSc installed but not found by pkg-config; set PETSC_DIR" >&2
  exit 1
fi
command -v mpirun >/dev/null
echo "PETSc $(pkg-config --modversion PETSc 2>/dev/null || echo "at $PETSC_DIR") ready"
