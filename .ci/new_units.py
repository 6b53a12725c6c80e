#!/usr/bin/env python3
"""Which compilation units a CI stage adds to the ones already built.

A stage that builds with other features or another package selection
reuses a unit only when the unit and all of its dependencies resolved
alike. Give it the unit graphs (nothing is built) of the stages before,
then `--`, then those of the stage to check:

    g() { cargo +nightly "$@" --unit-graph -Z unstable-options; }
    g clippy --workspace --all-targets > /tmp/ws_clippy.json
    g test --workspace --no-run > /tmp/ws_test.json
    g test --workspace --features ctc-verification/meshio --test meshio \\
        --no-run > /tmp/meshio_test.json
    python3 .ci/new_units.py /tmp/ws_clippy.json /tmp/ws_test.json -- \\
        /tmp/meshio_test.json

prints, per stage graph, the units it would compile (package:target:mode).
"""
import json
import sys


def units(path):
    """Unit identity (with its dependencies') -> unit, for one graph."""
    with open(path) as f:
        graph = json.load(f)["units"]
    memo = {}

    def key(i):
        if i not in memo:
            u = graph[i]
            memo[i] = hash((
                u["pkg_id"], u["target"]["name"], u["mode"],
                tuple(sorted(u["features"])),
                json.dumps(u["profile"], sort_keys=True), str(u.get("platform")),
                tuple(sorted(key(d["index"]) for d in u["dependencies"])),
            ))
        return memo[i]

    return {key(i): graph[i] for i in range(len(graph))}


def name(u):
    pkg = u["pkg_id"].split("#")[-1].split("@")[0].split("/")[-1]
    return f'{pkg}:{u["target"]["name"]}:{u["mode"]}'


def main(argv):
    if "--" not in argv:
        sys.exit(__doc__)
    cut = argv.index("--")
    built = {}
    for path in argv[:cut]:
        built.update(units(path))
    for path in argv[cut + 1:]:
        stage = units(path)
        new = sorted({name(u) for k, u in stage.items() if k not in built})
        print(f"{path}: {len(stage)} units, {len(new)} to compile")
        for n in new:
            print("  " + n)


if __name__ == "__main__":
    main(sys.argv[1:])
