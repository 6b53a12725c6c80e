#!/usr/bin/env bash
# The large 3D contact model of tests/decks/large_contact_3d.ctc at size N
# (12 N^3 hex8 cells, ~36 N^3 dofs) on RANKS MPI ranks, solved by CG + GAMG
# (`--solver petsc`); the figures come out of the run's summary.json
# (`distributed`: Krylov iterations per Newton iteration, per-rank cells,
# ghost nodes, halo, phase times and peak memory):
#   bash petsc/large_contact.sh N RANKS [OUT_DIR] [-- extra PETSc options]
# e.g. bash petsc/large_contact.sh 30 2   (1.0M dofs on 2 ranks)
# Needs a build with the feature: cargo build --release --features petsc
# (or CTC_EXE=target/debug/ctc after cargo build --features petsc)
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:?size N (12 N^3 cells)}"
ranks="${2:?number of MPI ranks}"
shift 2
out="target/large_contact/n${n}_r${ranks}"
if [ $# -gt 0 ] && [ "$1" != "--" ]; then
  out="$1"
  shift
fi
[ "${1:-}" = "--" ] && shift
case "$n" in '' | *[!0-9]*) echo "N must be a whole number" >&2; exit 2 ;; esac
mkdir -p "$out"
deck="$out/large_contact_3d_n$n.ctc"
sed "s/^let n = .*/let n = $n/" tests/decks/large_contact_3d.ctc > "$deck"
# CTC_EXE: another build (e.g. target/debug/ctc of `cargo build --features
# petsc`, whose dependencies are optimised too)
exe="${CTC_EXE:-target/release/ctc}"
if [ ! -x "$exe" ]; then
  echo "build first: cargo build --release --features petsc (or set CTC_EXE)" >&2
  exit 1
fi
mpirun --allow-run-as-root --oversubscribe -n "$ranks" "$exe" run "$deck" -o "$out/run" \
  --solver petsc -- -ksp_type cg -pc_type gamg -ksp_rtol 1e-10 "$@"
if command -v python3 >/dev/null; then
  python3 - "$out/run/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
d = s["distributed"]
print(f"N dofs {s['free_dofs']}, matrix nonzeros {s['matrix_nonzeros']}, "
      f"Newton iterations {s['newton_iterations']}, total {s['timings']['total']:.1f} s")
print(f"solver {d['solver']} on {d['ranks']} rank(s), assembly {d['assembly']}; Krylov "
      f"iterations per Newton iteration (correction, estimate): {d['krylov_per_setup']}")
for r in d["per_rank"]:
    print(f"rank {r['rank']}: cells {r['cells']}, owned nodes {r['owned_nodes']}, ghost nodes "
          f"{r['ghost_nodes']}, rows {r['rows']}, halo columns {r['halo_columns']} "
          f"({r['off_rank_nonzeros']} off-rank entries of {r['nonzeros']}), "
          f"assembly {r['assembly_seconds']:.2f} s, contact {r['contact_seconds']:.2f} s, "
          f"tangent {r['tangent_seconds']:.2f} s (insertion {r['insertion_seconds']:.2f}, "
          f"set-up {r['setup_seconds']:.2f}), solve {r['solve_seconds']:.2f} s, "
          f"peak memory {r['peak_memory_bytes'] / 2**30:.2f} GiB")
    print(f"  rank {r['rank']} CPU s: assembled cells {r['assembled_cells']}, assembly "
          f"{r['assembly_cpu_seconds']:.2f}, contact {r['contact_cpu_seconds']:.2f}, tangent "
          f"{r['tangent_cpu_seconds']:.2f}, solve {r['solve_cpu_seconds']:.2f}, process "
          f"{r['process_cpu_seconds']:.1f}")
PY
fi
