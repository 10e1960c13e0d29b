#!/usr/bin/env python3
"""Issue 33's speed-ups measured before and after in one run (`make performance`).

Builds the `smoothlab` CLI of a base commit (default: the code of the day issue 33 was
measured) beside this tree's release CLI, makes the meshes with this tree's CLI, then
times one pass of each target with both binaries, alternating, each several times on the
same file: the pass's own time (`--json`: `elapsed_ms` of the node loop, no reading,
writing or statistics). A short pass is run more often (about a second of its time, at
most MAX_RUNS), as a few runs of a pass of some milliseconds on a shared machine are
mostly noise. Writes JSON for `examples/perf.rs --before-after`.

    scripts/before_after.py [--base COMMIT] [--reps N] > target/perf/before_after.json

`BASE_BIN=path` uses an already built base CLI instead of building one.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

# a pass is timed at least --reps times by each binary, and more when short: about
# SECOND_MS of this tree's pass time in all, at most MAX_RUNS
SECOND_MS = 1000.0
MAX_RUNS = 25

BASE = "0e644a2"  # the code of issue 33's day: main before its first change (the merge of 2D condition's Newton trial, b54eb09)

# (target, mesh, smooth options) — the meshes are made below
TARGETS = [
    ("3D opt+new", "rand3d", ["--strategy", "opt", "--objective", "new"]),
    ("3D rules+new, priority order", "rand3d", ["--strategy", "rules", "--objective", "new", "--order", "priority"]),
    ("3D opt+old, 20 it", "rand3d", ["--strategy", "opt", "--objective", "old", "--max-iter", "20"]),
    ("hexahedra opt+new", "hexes", ["--strategy", "opt", "--objective", "new"]),
    ("hexahedra rules+new, priority order", "hexes", ["--strategy", "rules", "--objective", "new", "--order", "priority"]),
    ("hexahedra opt+old, 20 it", "hexes", ["--strategy", "opt", "--objective", "old", "--max-iter", "20"]),
    ("2D opt+condition", "rand2d", ["--strategy", "opt", "--objective", "condition"]),
    ("2D opt+old, 20 it", "rand2d", ["--strategy", "opt", "--objective", "old", "--max-iter", "20"]),
    ("2D opt+sine, 20 it", "rand2d", ["--strategy", "opt", "--objective", "sine", "--max-iter", "20"]),
    ("2D opt+untangle", "plate", ["--strategy", "opt", "--objective", "untangle"]),
]

# how each mesh is made, by this tree's CLI: (description, commands)
MESHES = {
    "rand3d": ("Freitag's rand3D of 8000 points (seed 1)", [["generate", "rand3d", "--points", "8000", "--seed", "1", "-o", "{out}"]]),
    "hexes": (
        "a 10³ block of hexahedra, free nodes moved by 0.3 mean edge lengths (seed 3; all valid)",
        [["generate", "hexgrid", "--cells", "10", "-o", "{tmp}"], ["generate", "perturb", "{tmp}", "--amount", "0.3", "--seed", "3", "-o", "{out}"]],
    ),
    "rand2d": ("Freitag's rand2D of 20000 points (seed 7)", [["generate", "rand2d", "--points", "20000", "--seed", "7", "-o", "{out}"]]),
    "plate": (
        "a plate with a hole of mixed elements tangled by 0.6 mean edge lengths (seed 1)",
        [["generate", "plate", "--kind", "mixed", "--resolution", "12", "-o", "{tmp}"], ["generate", "perturb", "{tmp}", "--amount", "0.6", "--seed", "1", "-o", "{out}"]],
    ),
}


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def base_binary(root, base):
    if os.environ.get("BASE_BIN"):
        return os.environ["BASE_BIN"]
    tree = os.path.join(root, "target", "before-after", "tree")
    if os.path.isdir(tree):
        run(["git", "-C", root, "worktree", "remove", "--force", tree])
    run(["git", "-C", root, "worktree", "add", "--detach", tree, base])
    try:
        print(f"before_after: building the CLI of {base} …", file=sys.stderr)
        run(["cargo", "build", "--release", "--bin", "smoothlab", "--manifest-path", os.path.join(tree, "Cargo.toml"),
             "--target-dir", os.path.join(root, "target", "before-after", "target")])
    finally:
        run(["git", "-C", root, "worktree", "remove", "--force", tree])
    return os.path.join(root, "target", "before-after", "target", "release", "smoothlab")


def pass_ms(binary, mesh, options, tmp):
    out = run([binary, "smooth", mesh, "-o", os.path.join(tmp, "out.vtk"), "--passes", "1", "--json", *options]).stdout
    p = json.loads(out)["passes"][0]
    return p["elapsed_ms"], p["visits"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--base", default=BASE)
    ap.add_argument("--reps", type=int, default=5)
    a = ap.parse_args()
    root = run(["git", "rev-parse", "--show-toplevel"]).stdout.strip()
    after = os.path.join(root, "target", "release", "smoothlab")
    before = base_binary(root, a.base)
    base_commit = run(["git", "-C", root, "rev-parse", "--short", a.base]).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        paths = {}
        for name, (_, cmds) in MESHES.items():
            out, scratch = os.path.join(tmp, f"{name}.vtk"), os.path.join(tmp, f"{name}-0.vtk")
            for c in cmds:
                run([after, *[w.format(out=out, tmp=scratch) for w in c]])
            paths[name] = out
        rows = []
        for target, mesh, options in TARGETS:
            print(f"before_after: {target} …", file=sys.stderr)
            times = {"before": [], "after": []}
            visits = {}
            # one untimed run of each first (the file cached, the binaries loaded); this
            # tree's tells how short the pass is
            pass_ms(before, paths[mesh], options, tmp)
            first, _ = pass_ms(after, paths[mesh], options, tmp)
            runs = max(a.reps, min(MAX_RUNS, math.ceil(SECOND_MS / max(first, 1e-3))))
            for _ in range(runs):
                for side, binary in (("before", before), ("after", after)):
                    ms, v = pass_ms(binary, paths[mesh], options, tmp)
                    times[side].append(ms)
                    visits[side] = v
            rows.append({
                "target": target,
                "mesh": MESHES[mesh][0],
                "options": " ".join(options),
                "runs": runs,
                "before_ms": statistics.median(times["before"]),
                "after_ms": statistics.median(times["after"]),
                "before_visits": visits["before"],
                "after_visits": visits["after"],
            })
    json.dump({"base": base_commit, "reps": a.reps, "rows": rows}, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
