#!/usr/bin/env python3
"""Boundary layers for the stretch target's measurements (docs/formulas.md, Targets).

A layer is graded from a wall at y = 0 (2D) or z = 0 (3D), its interior nodes moved by up
to a fifth of their cell each way (or, with `--across`, only across the rows). Its first
row's median height is what a smoother must keep.

  boundary-layer.py make KIND SEED OUT.vtk [--across]   write a layer (legacy VTK)
  boundary-layer.py row KIND FILE.vtk                   its first row's median height
  boundary-layer.py measure KIND --cli PATH [--across] [--seeds N]
                                   seeds 1 to N (3), `ideal` and `stretch`, the defaults
                                   otherwise: the first row's change and the angles

KIND: quad, tri (40 x 30 cells, 1/40 wide, rows x1.2 to a total of 1), bent-quad,
bent-tri (the same bent a quarter turn about the rows' direction: a surface in 3D), hex,
wedge (10 x 10 columns 0.025 wide, 16 rows x1.25 from a wall row 0.001 high; a wedge is
half a hexahedron). Standard library only.
"""

import argparse
import math
import random
import re
import subprocess
import sys
import tempfile
from pathlib import Path

PLANAR = {"quad": 9, "tri": 5, "bent-quad": 9, "bent-tri": 5}
SOLID = {"hex": 12, "wedge": 13}


def dims(kind):
    """Columns, rows, the column width and each row's top."""
    if kind in PLANAR:
        nx, ny, ratio = 40, 30, 1.2
        return nx, ny, 1 / nx, [(ratio**j - 1) / (ratio**ny - 1) for j in range(ny + 1)]
    nx, nz, ratio, h0 = 10, 16, 1.25, 0.001
    return nx, nz, 0.025, [h0 * (ratio**k - 1) / (ratio - 1) for k in range(nz + 1)]


def make(kind, seed, across):
    """The layer's points and cells (VTK node lists)."""
    nx, rows, w, top = dims(kind)
    rnd = random.Random(seed)
    jitter = lambda: rnd.uniform(-1, 1) / 5
    points, cells = [], []
    if kind in PLANAR:
        index = lambda i, j: j * (nx + 1) + i
        for j in range(rows + 1):
            for i in range(nx + 1):
                x, y = i * w, top[j]
                if 0 < i < nx and 0 < j < rows:
                    h = min(top[j] - top[j - 1], top[j + 1] - top[j])
                    x += 0 if across else jitter() * w
                    y += jitter() * h
                points.append((x, y, 0.0))
        for j in range(rows):
            for i in range(nx):
                a, b, c, d = index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)
                cells += [[a, b, c, d]] if kind.endswith("quad") else [[a, b, c], [a, c, d]]
        if kind.startswith("bent"):
            # x runs a quarter turn around an axis along y, the rows' heights kept
            r = 2 / math.pi
            points = [(r * math.sin(x / r), y, r * (1 - math.cos(x / r))) for x, y, _ in points]
        return points, cells
    index = lambda i, j, k: (k * (nx + 1) + j) * (nx + 1) + i
    for k in range(rows + 1):
        for j in range(nx + 1):
            for i in range(nx + 1):
                x, y, z = i * w, j * w, top[k]
                if 0 < i < nx and 0 < j < nx and 0 < k < rows:
                    h = min(top[k] - top[k - 1], top[k + 1] - top[k])
                    if not across:
                        x, y = x + jitter() * w, y + jitter() * w
                    z += jitter() * h
                points.append((x, y, z))
    for k in range(rows):
        for j in range(nx):
            for i in range(nx):
                a, b, c, d = index(i, j, k), index(i + 1, j, k), index(i + 1, j + 1, k), index(i, j + 1, k)
                e, f, g, h = (index(i, j, k + 1), index(i + 1, j, k + 1), index(i + 1, j + 1, k + 1),
                              index(i, j + 1, k + 1))
                cells += [[a, b, c, d, e, f, g, h]] if kind == "hex" else [[a, b, d, e, f, h], [b, c, d, f, g, h]]
    return points, cells


def write(kind, points, cells, out):
    cell_type = {**PLANAR, **SOLID}[kind]
    lines = ["# vtk DataFile Version 2.0", f"boundary layer ({kind})", "ASCII", "DATASET UNSTRUCTURED_GRID",
             f"POINTS {len(points)} double"]
    lines += ["%r %r %r" % p for p in points]
    lines.append(f"CELLS {len(cells)} {sum(len(c) + 1 for c in cells)}")
    lines += [" ".join(map(str, [len(c)] + c)) for c in cells]
    lines.append(f"CELL_TYPES {len(cells)}")
    lines += [str(cell_type)] * len(cells)
    Path(out).write_text("\n".join(lines) + "\n")


def points_of(path):
    words = Path(path).read_text().split()
    at = words.index("POINTS")
    n = int(words[at + 1])
    return [tuple(float(v) for v in words[at + 3 + 3 * k: at + 6 + 3 * k]) for k in range(n)]


def first_row(kind, path):
    """The median height of the first row: each interior column's node above the wall."""
    nx = dims(kind)[0]
    p = points_of(path)
    if kind in PLANAR:
        heights = [p[nx + 1 + i][1] - p[i][1] for i in range(1, nx)]
    else:
        index = lambda i, j, k: (k * (nx + 1) + j) * (nx + 1) + i
        heights = [p[index(i, j, 1)][2] - p[index(i, j, 0)][2] for i in range(1, nx) for j in range(1, nx)]
    heights.sort()
    return heights[len(heights) // 2]


def measure(kind, cli, across, seeds):
    print(f"{kind}{' across the rows' if across else ''}: first row's change, angles (input -> after)")
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(1, seeds + 1):
            layer, out = Path(tmp, "layer.vtk"), Path(tmp, "out.vtk")
            write(kind, *make(kind, seed, across), layer)
            h0 = first_row(kind, layer)
            stats = subprocess.run([cli, "stats", str(layer)], capture_output=True, text=True, check=True).stdout
            lo, hi = re.search(r"angles\s+min ([-\d.]+)°\s+max ([-\d.]+)°", stats).groups()
            row = [f"seed {seed}: input {lo}°–{hi}°"]
            for target in ("ideal", "stretch"):
                run = subprocess.run([cli, "smooth", str(layer), "-o", str(out), "--target", target],
                                     capture_output=True, text=True, check=True).stdout
                final = next(line for line in run.splitlines() if line.startswith("final"))
                angles = re.search(r"angles ([-\d.]+°–[-\d.]+°)", final).group(1)
                row.append(f"{target} {100 * (first_row(kind, out) / h0 - 1):+.1f} % {angles}")
            print("  " + "; ".join(row))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    kinds = sorted({**PLANAR, **SOLID})
    m = sub.add_parser("make")
    m.add_argument("kind", choices=kinds)
    m.add_argument("seed", type=int)
    m.add_argument("out")
    m.add_argument("--across", action="store_true", help="move the interior only across the rows")
    r = sub.add_parser("row")
    r.add_argument("kind", choices=kinds)
    r.add_argument("file")
    s = sub.add_parser("measure")
    s.add_argument("kind", choices=kinds)
    s.add_argument("--cli", default="target/release/smoothlab")
    s.add_argument("--across", action="store_true")
    s.add_argument("--seeds", type=int, default=3, help="seeds 1 to this")
    a = parser.parse_args()
    if a.command == "make":
        write(a.kind, *make(a.kind, a.seed, a.across), a.out)
    elif a.command == "row":
        print("%.6g" % first_row(a.kind, a.file))
    else:
        measure(a.kind, a.cli, a.across, a.seeds)


if __name__ == "__main__":
    sys.exit(main())
