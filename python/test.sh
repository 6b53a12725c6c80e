#!/bin/sh
# Builds the Python package `ctc` into a virtual environment and runs its
# tests against the CLI binary (called by .ci/run after `cargo test`, which
# builds target/debug/ctc). Usage: sh python/test.sh
set -e
here=$(cd "$(dirname "$0")" && pwd)
venv=${CTC_VENV:-$here/target/venv}
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q "maturin>=1.5,<2" numpy
cd "$here"
# The repository's target directory: the registry crates the workspace's
# `cargo test` built are reused (python/Cargo.toml says how they resolve
# alike); only pyo3 and the ctc crates of this package are compiled.
CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$here/../target}
export CARGO_TARGET_DIR
VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" maturin develop -q
CTC_BIN=${CTC_BIN:-$here/../target/debug/ctc} "$venv/bin/python" -m unittest discover -s "$here/tests" -v
