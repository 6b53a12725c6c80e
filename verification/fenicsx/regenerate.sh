#!/usr/bin/env bash
# Regenerates the FEniCSx references of issue 9:
#  1. ctc exports the problem of every FEniCSx case (mesh, numbering,
#     boundary conditions, contact, tributary areas) to <out>/<case>.problem.json;
#  2. solve.py solves each with DOLFINx and writes <out>/<case>.json.
# Usage: bash verification/fenicsx/regenerate.sh [out_dir] [case_filter]
#   out_dir      default verification/reference (the committed files)
#   case_filter  only cases whose name contains it (e.g. patch)
# FENICSX_PYTHON selects the interpreter with DOLFINx (default /usr/bin/python3).
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${1:-verification/reference}
FILTER=${2:-}
PY=${FENICSX_PYTHON:-/usr/bin/python3}
mkdir -p "$OUT"
EXPORT=$(mktemp -d)
trap 'rm -rf "$EXPORT"' EXIT
cargo run --quiet -p ctc-verification --example fenicsx_export -- "$EXPORT" >/dev/null
for problem in "$EXPORT"/*.problem.json; do
  case_name=$(basename "$problem" .problem.json)
  if [ -n "$FILTER" ] && [[ "$case_name" != *"$FILTER"* ]]; then
    continue
  fi
  cp "$problem" "$OUT/"
  # FFCx logs its JIT compilation on stderr; keep only real errors visible.
  "$PY" verification/fenicsx/solve.py "$OUT/$case_name.problem.json" "$OUT/$case_name.json" \
    2> >(grep -v '^INFO:' >&2)
done
