#!/usr/bin/env python3
"""Prove that two builds of the smoothlab CLI write the same bytes.

Runs a broad matrix of `smoothlab` commands (generate, stats, convert, smooth, render and
every --help) and records a sha256 of everything each run produces: the files it writes,
its stdout, its stderr and its exit code. Refused commands are part of the matrix: their
messages and exit codes must stay the same too. Timings are the only nondeterministic
output; their values are masked before hashing (JSON keys `time_ms`, `elapsed_ms` and
`stats_ms`, and the trailing `… 12.3 ms` of the text summary of `smooth`).

    python3 scripts/compare-outputs.py run --cli PATH --out DIR [--meshes DIR] [--jobs N]
    python3 scripts/compare-outputs.py compare DIR_A DIR_B

`run` writes every output under DIR/runs/NAME/ and one line per run to DIR/manifest.txt;
`--meshes` is the folder of shared test meshes (default ../shared/meshes beside the
repository). The lists of mesh kinds, strategies, objectives, penalties, targets, boundary rules, orders, views,
metrics, themes, .msh versions and figures are read from the CLI's own help and messages,
so a list that changes shows up as runs that differ. `compare` prints the runs whose lines
differ and exits 1, or prints "N runs identical" and exits 0. Give --cli a file named
`smoothlab`: the usage lines of the help and of argument errors carry the binary's file name.
"""

import argparse
import concurrent.futures
import hashlib
import os
import re
import shutil
import subprocess
import sys
import time

# The fields that hold times, and nothing else, are masked before hashing.
JSON_TIME_KEYS = ("time_ms", "elapsed_ms", "stats_ms")
JSON_TIME_RE = re.compile(r'("(?:%s)":)[^,}\]]*' % "|".join(JSON_TIME_KEYS))
TEXT_TIME_RE = re.compile(r"(?m)^((?:pass +[0-9]+|finish +[0-9]+|final):.*[ ;])-?[0-9][0-9.]*( ms)$")

# Small meshes of the shared folder: planar 2D (triangles, quads, mixed, quadratic, tangled,
# off the xy plane, on a sphere) and 3D (hexahedra, tetrahedra, wedges, pyramids, mixed,
# 20-node hexahedra, a file of quads among the hexahedra).
SHARED_2D = [
    "mesquite/tris/tangled/tangled_tri.vtk",
    "mesquite/tris/untangled/tri_5_not_xy.vtk",
    "mesquite/quads/tangled/tangled_quad.vtk",
    "mesquite/quads/tangled/inverted-hole-1.vtk",
    "mesquite/quads/untangled/square_quad_10_rand.vtk",
    "mesquite/mixed/tangled/hybrid_3quad_1tri_tangled.vtk",
    "mesquite/quadratic/triPatch_0_0.vtk",
    "mesquite/quads/untangled/quads_on_sphere_529.vtk",
]
SHARED_3D = [
    "mesquite3d/hexes/tangled/hex_5_tangled.vtk",
    "mesquite3d/tets/tangled/tet_4_tangled.vtk",
    "mesquite3d/pyramids/untangled/6-pyramid-brick.vtk",
    "mesquite3d/prisms/untangled/6-wedge-prism.vtk",
    "mesquite3d/mixed/tangled/mixed-hex-pyr-tet.vtk",
    "mesquite3d/quadratic/6x6x6-hex20.vtk",
    "mesquite3d/hexes/untangled/sph-10-zsquare.vtk",
]


def sha(data):
    return hashlib.sha256(data).hexdigest()


def mask_times(text):
    """The stdout with the values of the timing fields replaced by T."""
    text = JSON_TIME_RE.sub(r"\1T", text)
    return TEXT_TIME_RE.sub(r"\1T\2", text)


# ---------------------------------------------------------------------------------------
# Reading the CLI's lists from its help


def help_text(cli, *args):
    return subprocess.run([cli, *args, "--help"], capture_output=True, text=True, check=True).stdout


def subcommands(text):
    """The names under `Commands:` (without `help`)."""
    names, inside = [], False
    for line in text.splitlines():
        if line.strip() == "Commands:":
            inside = True
            continue
        if inside:
            m = re.match(r"^  ([a-z0-9][a-z0-9-]*)\s", line + " ")
            if not m:
                if line.strip() == "" or not line.startswith("  "):
                    break
                continue
            if m.group(1) != "help":
                names.append(m.group(1))
    return names


def possible_values(text, option):
    """The possible values of `--option` in a long help text."""
    lines = text.splitlines()
    start = next(
        (i for i, l in enumerate(lines) if re.match(r"^\s+(-\w, )?--%s\b" % re.escape(option), l)), None
    )
    if start is None:
        raise SystemExit("no --%s in the help text" % option)
    block = []
    for l in lines[start + 1 :]:
        if re.match(r"^\s+(-\w, )?--[a-z]", l) or (l and not l.startswith(" ")):
            break
        block.append(l)
    joined = "\n".join(block)
    m = re.search(r"\[possible values: ([^\]]*)\]", joined)
    if m:
        return [v.strip() for v in m.group(1).split(",")]
    _, found, listed = joined.partition("Possible values:")
    values = re.findall(r"(?m)^\s+- ([^\s:]+)", listed) if found else []
    if not values:
        raise SystemExit("no possible values of --%s in the help text" % option)
    return values


class Lists:
    """What the CLI offers, read from its help."""

    def __init__(self, cli):
        gen = help_text(cli, "generate")
        self.generate_kinds = subcommands(gen)
        self.subcommands = subcommands(help_text(cli))
        smooth = help_text(cli, "smooth")
        self.objectives = possible_values(smooth, "objective")
        self.strategies = possible_values(smooth, "strategy")
        self.orders = possible_values(smooth, "order")
        self.penalties = possible_values(smooth, "penalty")
        # a CLI before the targets has no --target: its lists lack those runs
        self.targets = possible_values(smooth, "target") if "--target" in smooth else []
        # and one before the sliding boundaries has no --boundary
        self.boundaries = possible_values(smooth, "boundary") if "--boundary" in smooth else []
        self.msh_versions = possible_values(smooth, "msh-version")
        self.grid_kinds = possible_values(help_text(cli, "generate", "grid"), "kind")
        self.plate_kinds = possible_values(help_text(cli, "generate", "plate"), "kind")
        self.star_kinds = possible_values(help_text(cli, "generate", "star"), "kind")
        self.surface_kinds = possible_values(help_text(cli, "generate", "sphere"), "kind")
        render = help_text(cli, "render")
        self.views = possible_values(render, "view")
        self.metrics = possible_values(render, "metric")
        self.themes = possible_values(render, "theme")
        # the figures: the list the refusal of an unknown name gives
        err = subprocess.run(
            [cli, "render", "--figure", "no-such-figure", "-o", os.devnull], capture_output=True, text=True
        ).stderr
        m = re.search(r"the tour has (.*)$", err.strip())
        if not m:
            raise SystemExit("cannot read the figures from: %r" % err)
        self.figures = [f.strip() for f in m.group(1).split(",")]
        expected_kinds = {"rand2d", "grid", "plate", "star", "sphere", "cylinder", "torus", "rand3d",
                          "cube", "hexgrid", "mixed", "perturb"}
        unknown = set(self.generate_kinds) - expected_kinds
        if unknown:
            raise SystemExit("generate offers kinds this matrix does not know: %s" % ", ".join(sorted(unknown)))


# ---------------------------------------------------------------------------------------
# The matrix: phases of runs; each run is (name, argv after the CLI); every path in argv is
# relative to DIR, the working directory of every run, so messages naming files are the
# same whatever DIR is. A run writes into runs/NAME/; `{o}` in argv stands for that folder.


class Matrix:
    def __init__(self, lists, shared_2d, shared_3d):
        self.l = lists
        self.phases = []
        self.shared_2d = shared_2d  # names of inputs/shared-*.vtk
        self.shared_3d = shared_3d

    def phase(self):
        self.phases.append([])

    def add(self, name, *argv):
        self.phases[-1].append((name, list(argv)))

    def build(self):
        l = self.l
        planar, surfaces, volumes = [], [], []
        tri, quad, mixed = l.plate_kinds[0], l.grid_kinds[-1], l.plate_kinds[-1]
        s_tri, s_mixed = l.surface_kinds[1 % len(l.surface_kinds)], l.surface_kinds[-1]

        # -- phase 1: help texts and generated meshes
        self.phase()
        self.add("help", "--help")
        self.add("version", "--version")
        for sub in l.subcommands:
            self.add("help-" + sub, sub, "--help")
            self.add("help-short-" + sub, sub, "-h")
        for kind in l.generate_kinds:
            self.add("help-generate-" + kind, "generate", kind, "--help")
        self.add("no-subcommand")
        self.add("unknown-subcommand", "frobnicate")

        def gen(name, kind, *args, group=None, ext="vtk"):
            self.add("gen-" + name, "generate", kind, *args, "-o", "{o}/%s.%s" % (name, ext))
            if group is not None:
                group.append("runs/gen-%s/%s.%s" % (name, name, ext))

        gen("rand2d", "rand2d", group=planar)
        gen("rand2d-small", "rand2d", "--points", "60", "--per-side", "6", "--seed", "1", group=planar)
        gen("rand2d-s2", "rand2d", "--points", "150", "--per-side", "10", "--seed", "2", group=planar)
        for k in l.grid_kinds:
            gen("grid-" + k, "grid", "--kind", k, group=planar)
            gen("grid-%s-5x3" % k, "grid", "--nx", "5", "--ny", "3", "--kind", k, group=planar)
        for k in l.plate_kinds:
            for order in ("1", "2"):
                gen("plate-%s-o%s" % (k, order), "plate", "--kind", k, "--order", order, group=planar)
            gen("plate-%s-r2" % k, "plate", "--kind", k, "--resolution", "2", group=planar)
        for k in l.star_kinds:
            gen("star-" + k, "star", "--kind", k, group=planar)
            for n in ("5", "8"):
                gen("star-%s-k%s" % (k, n), "star", "--kind", k, "--k", n, group=planar)
        for shape in ("sphere", "cylinder", "torus"):
            for k in l.surface_kinds:
                for order in ("1", "2"):
                    res = {"sphere": "4", "cylinder": "3", "torus": "2"}[shape]
                    gen("%s-%s-o%s" % (shape, k, order), shape, "--kind", k, "--order", order,
                        "--resolution", res, group=surfaces)
        gen("rand3d", "rand3d", group=volumes)
        gen("rand3d-small", "rand3d", "--points", "80", "--seed", "2", group=volumes)
        gen("cube-o1", "cube", "--cells", "4", group=volumes)
        gen("cube-o2", "cube", "--cells", "3", "--order", "2", group=volumes)
        gen("hexgrid-o1", "hexgrid", "--cells", "4", group=volumes)
        gen("hexgrid-o2", "hexgrid", "--cells", "3", "--order", "2", group=volumes)
        gen("hexgrid-o2s", "hexgrid", "--cells", "3", "--order", "2", "--serendipity", group=volumes)
        gen("hexgrid-bent", "hexgrid", "--cells", "6,2,2", "--size", "2,1,0.5", "--bend", "90", group=volumes)
        gen("mixed-block", "mixed", "--cells", "4", group=volumes)
        gen("mixed-bent", "mixed", "--cells", "4,2,2", "--size", "2,1,0.5", "--bend", "60", group=volumes)
        # the writers of generate: each .msh version and the other formats
        for v in l.msh_versions:
            gen("plate-o2-msh" + v, "plate", "--kind", mixed, "--order", "2", "--resolution", "2",
                "--msh-version", v, ext="msh")
            gen("torus-msh" + v, "torus", "--resolution", "1", "--msh-version", v, ext="msh")
            gen("mixed-msh" + v, "mixed", "--cells", "2", "--msh-version", v, ext="msh")
        for ext in ("node", "obj", "off"):
            gen("grid-" + ext, "grid", "--nx", "3", "--ny", "3", ext=ext)
            gen("sphere-" + ext, "sphere", "--resolution", "1", ext=ext)
        gen("rand3d-node", "rand3d", "--points", "40", ext="node")
        # refusals of generate
        gen("bad-hexgrid-serendipity-o1", "hexgrid", "--cells", "2", "--serendipity")
        gen("bad-hexgrid-o3", "hexgrid", "--cells", "2", "--order", "3")
        gen("bad-cube-o3", "cube", "--cells", "2", "--order", "3")
        gen("bad-plate-o3", "plate", "--order", "3")
        gen("bad-sphere-o3", "sphere", "--order", "3")
        gen("bad-grid-zero", "grid", "--nx", "0")
        gen("bad-rand2d-zero", "rand2d", "--points", "0", "--per-side", "0")
        gen("bad-rand3d-few", "rand3d", "--points", "3")
        gen("bad-hexgrid-cells", "hexgrid", "--cells", "2,2")
        gen("bad-hexgrid-bend", "hexgrid", "--cells", "2", "--bend", "400")
        gen("bad-star-k2", "star", "--k", "2")
        gen("bad-extension", "grid", "--nx", "2", ext="xyz")
        gen("bad-surface-obj-o2", "sphere", "--resolution", "1", "--order", "2", ext="obj")
        gen("bad-volume-off", "cube", "--cells", "1", ext="off")
        self.add("gen-bad-kind", "generate", "nosuch", "-o", "{o}/x.vtk")
        self.add("gen-bad-msh-version", "generate", "grid", "--msh-version", "3.0", "-o", "{o}/x.msh")
        self.add("gen-bad-no-output", "generate", "grid")
        self.add("gen-bad-folder", "generate", "grid", "-o", "{o}/missing-folder/x.vtk")

        # -- phase 2: perturbed (tangled) variants, and every format of the convert sources
        self.phase()
        tangled = {}

        def perturb(src, name, amount, seed, group):
            self.add("perturb-" + name, "generate", "perturb", src, "--amount", amount, "--seed", seed,
                     "-o", "{o}/" + name + ".vtk")
            path = "runs/perturb-%s/%s.vtk" % (name, name)
            group.append(path)
            tangled[name] = path

        g = lambda n: "runs/gen-%s/%s.vtk" % (n, n)
        perturb(g("rand2d"), "rand2d-tangled", "0.8", "1", planar)
        perturb(g("rand2d-small"), "rand2d-small-tangled", "0.8", "1", planar)
        perturb(g("rand2d-s2"), "rand2d-perturbed", "0.3", "3", planar)
        perturb(g("grid-" + quad), "grid-quad-tangled", "0.7", "2", planar)
        for k in l.plate_kinds:
            perturb(g("plate-%s-o1" % k), "plate-%s-tangled" % k, "0.5", "1", planar)
            perturb(g("plate-%s-o2" % k), "plate-%s-o2-tangled" % k, "0.6", "4", planar)
        for shape in ("sphere", "cylinder", "torus"):
            for k in l.surface_kinds:
                perturb(g("%s-%s-o1" % (shape, k)), "%s-%s-tangled" % (shape, k), "0.7", "2", surfaces)
            perturb(g("%s-%s-o2" % (shape, s_mixed)), "%s-o2-tangled" % shape, "0.6", "3", surfaces)
        perturb(g("rand3d"), "rand3d-tangled", "0.5", "1", volumes)
        perturb(g("cube-o1"), "cube-tangled", "0.8", "1", volumes)
        perturb(g("cube-o2"), "cube-o2-tangled", "0.4", "1", volumes)
        perturb(g("hexgrid-o1"), "hexgrid-tangled", "0.8", "1", volumes)
        perturb(g("hexgrid-o2"), "hexgrid-o2-tangled", "0.4", "2", volumes)
        perturb(g("hexgrid-o2s"), "hexgrid-o2s-tangled", "0.4", "3", volumes)
        perturb(g("mixed-block"), "mixed-tangled", "0.5", "1", volumes)
        self.add("perturb-bad-missing", "generate", "perturb", "inputs/no-such-file.vtk", "-o", "{o}/x.vtk")
        self.add("perturb-bad-garbage", "generate", "perturb", "inputs/garbage.vtk", "-o", "{o}/x.vtk")
        self.add("perturb-negative", "generate", "perturb", g("grid-" + l.grid_kinds[0]), "--amount", "-0.3",
                 "-o", "{o}/x.vtk")
        self.add("perturb-zero", "generate", "perturb", g("plate-%s-o2" % tri), "--amount", "0", "-o", "{o}/x.vtk")
        for i, p in enumerate((self.shared_2d[0], self.shared_2d[-1], self.shared_3d[0], self.shared_3d[1])):
            self.add("perturb-shared-%d" % i, "generate", "perturb", p, "--seed", "5", "-o", "{o}/x.msh")

        formats = ["msh" + v for v in l.msh_versions] + ["vtk", "node", "obj", "off"]

        def target(fmt):
            if fmt.startswith("msh"):
                return ".msh", ["--msh-version", fmt[3:]]
            return "." + fmt, []

        # what each format holds differs (.node: planar triangles or tetrahedra; .obj/.off:
        # linear surfaces): a mesh of each family, the refusals recorded too
        convert_meshes = {
            "planar-tri": g("plate-%s-r2" % tri),
            "planar-mixed": g("plate-%s-r2" % mixed),
            "planar-quadratic": g("plate-%s-o2" % tri),
            "surface-tri": g("torus-%s-o1" % s_tri),
            "surface-mixed": g("sphere-%s-o1" % s_mixed),
            "volume-tet": g("rand3d-small"),
            "volume-mixed": g("mixed-block"),
            "volume-hex27": g("hexgrid-o2"),
        }
        sources = {}
        for what, src in convert_meshes.items():
            for fmt in formats:
                ext, extra = target(fmt)
                name = "conv-src-%s-%s" % (what, fmt)
                self.add(name, "convert", src, "{o}/m" + ext, *extra)
                sources[(what, fmt)] = "runs/%s/m%s" % (name, ext)

        # -- phase 3: everything that reads those meshes
        self.phase()
        for what in convert_meshes:
            for a in formats:
                for b in formats:
                    ext, extra = target(b)
                    self.add("conv-%s-%s-to-%s" % (what, a, b), "convert", sources[(what, a)], "{o}/m" + ext, *extra)
        self.add("conv-bad-missing", "convert", "inputs/no-such-file.msh", "{o}/m.vtk")
        self.add("conv-bad-extension", "convert", g("grid-" + quad), "{o}/m.xyz")
        self.add("conv-bad-msh-version", "convert", g("grid-" + quad), "{o}/m.msh", "--msh-version", "1.0")
        self.add("conv-bad-garbage", "convert", "inputs/garbage.vtk", "{o}/m.msh")
        for p in self.shared_2d + self.shared_3d:
            stem = os.path.basename(p)[:-4]
            self.add("conv-%s-msh" % stem, "convert", p, "{o}/m.msh")
            self.add("conv-%s-vtk" % stem, "convert", p, "{o}/m.vtk")

        all_meshes = planar + surfaces + volumes + self.shared_2d + self.shared_3d
        for p in all_meshes:
            stem = os.path.splitext(os.path.basename(p))[0]
            self.add("stats-" + stem, "stats", p)
            self.add("stats-json-" + stem, "stats", p, "--json")
        for what in convert_meshes:
            for fmt in formats:
                self.add("stats-json-conv-%s-%s" % (what, fmt), "stats", sources[(what, fmt)], "--json")
        self.add("stats-bad-missing", "stats", "inputs/no-such-file.vtk")
        self.add("stats-bad-garbage", "stats", "inputs/garbage.vtk", "--json")

        def smooth(name, src, *args, ext="vtk", json=True, out=None):
            argv = ["smooth", src, "-o", out or "{o}/out." + ext, *args]
            if json:
                argv.append("--json")
            self.add("smooth-" + name, *argv)

        # every strategy x objective: planar triangles, quads, mixed, quadratic; a surface of
        # quads, one of mixed elements; tetrahedra, hexahedra, a mixed block
        full = ["rand2d-tangled", "grid-quad-tangled", "plate-%s-tangled" % mixed, "plate-%s-o2-tangled" % mixed,
                "sphere-%s-tangled" % l.surface_kinds[0], "torus-%s-tangled" % s_mixed,
                "rand3d-tangled", "hexgrid-tangled", "mixed-tangled"]
        for mesh in full:
            for s in l.strategies:
                for obj in l.objectives:
                    smooth("all-%s-%s-%s" % (mesh, s, obj), tangled[mesh], "--strategy", s, "--objective", obj,
                           "--passes", "2")
        # the other quadratic meshes (planar, surfaces, volumes): every strategy, default objective
        for mesh in ["plate-%s-o2-tangled" % k for k in l.plate_kinds if k != mixed] + \
                ["sphere-o2-tangled", "cylinder-o2-tangled", "torus-o2-tangled",
                 "cube-o2-tangled", "hexgrid-o2-tangled", "hexgrid-o2s-tangled"]:
            for s in l.strategies:
                smooth("quadratic-%s-%s" % (mesh, s), tangled[mesh], "--strategy", s, "--passes", "2")
        # penalties, orders, thresholds, iterations, passes, folds
        for pen in l.penalties:
            for s in l.strategies:
                for mesh in ("rand2d-tangled", "plate-%s-o2-tangled" % tri, "grid-quad-tangled"):
                    smooth("penalty-%s-%s-%s" % (pen, s, mesh), tangled[mesh], "--objective", "new",
                           "--penalty", pen, "--strategy", s)
            smooth("penalty-%s-default-objective" % pen, tangled["plate-%s-tangled" % mixed], "--penalty", pen)
            smooth("penalty-%s-surface" % pen, tangled["sphere-%s-tangled" % s_tri], "--penalty", pen)
        for order in l.orders:
            for s in l.strategies:
                for mesh in ("rand2d-perturbed", "plate-%s-tangled" % tri, "cube-tangled", "cylinder-%s-tangled" % s_tri):
                    smooth("order-%s-%s-%s" % (order, s, mesh), tangled[mesh], "--strategy", s, "--order", order)
        for s in ("c1", "c2", "c3"):
            for t in ("5", "18.5", "45", "90"):
                for mesh in ("rand2d-perturbed", "grid-quad-tangled"):
                    smooth("threshold-%s-%s-%s" % (s, t, mesh), tangled[mesh], "--strategy", s, "--threshold", t)
            for t in ("0", "-5", "90.5", "nan", "x"):
                smooth("bad-threshold-%s-%s" % (s, t), tangled["rand2d-perturbed"], "--strategy", s,
                       "--threshold=" + t)
        for s in l.strategies:
            if s not in ("c1", "c2", "c3"):
                smooth("bad-threshold-with-%s" % s, tangled["rand2d-perturbed"], "--strategy", s, "--threshold", "30")
        for k in ("1", "2", "10", "50"):
            for s in ("opt", "rules", "c3"):
                smooth("max-iter-%s-%s" % (k, s), tangled["rand2d-tangled"], "--strategy", s, "--max-iter", k)
            smooth("max-iter-%s-volume" % k, tangled["hexgrid-tangled"], "--max-iter", k, "--passes", "1")
        for k in ("0", "100000", "-1"):
            smooth("bad-max-iter-%s" % k, tangled["rand2d-tangled"], "--max-iter=" + k)
        for s in ("laplace", "smart"):
            smooth("bad-max-iter-with-%s" % s, tangled["rand2d-tangled"], "--strategy", s, "--max-iter", "3")
        for n in ("1", "5", "10"):
            smooth("passes-%s" % n, tangled["grid-quad-tangled"], "--passes", n)
            smooth("passes-%s-laplace" % n, tangled["rand2d-tangled"], "--passes", n, "--strategy", "laplace")
            smooth("passes-%s-volume" % n, tangled["cube-tangled"], "--passes", n)
        for n in ("0", "100000"):
            smooth("bad-passes-%s" % n, tangled["rand2d-tangled"], "--passes", n)
        for flag in ("--pass-through-folds", "--no-pass-through-folds"):
            f = flag[2:]
            for obj in l.objectives:
                for mesh in ("rand2d-tangled", "plate-%s-o2-tangled" % mixed, "hexgrid-tangled"):
                    smooth("%s-%s-%s" % (f, obj, mesh), tangled[mesh], flag, "--objective", obj, "--strategy", "opt")
            for s in ("laplace", "smart"):
                smooth("bad-%s-%s" % (f, s), tangled["rand2d-tangled"], flag, "--strategy", s)
        smooth("folds-both", tangled["rand2d-tangled"], "--pass-through-folds", "--no-pass-through-folds")
        for obj in l.objectives:
            if obj != "new":
                smooth("bad-penalty-with-%s" % obj, tangled["rand2d-tangled"], "--objective", obj,
                       "--penalty", l.penalties[0])
        smooth("bad-strategy", tangled["rand2d-tangled"], "--strategy", "nosuch")
        smooth("bad-objective", tangled["rand2d-tangled"], "--objective", "nosuch")
        smooth("bad-order", tangled["rand2d-tangled"], "--order", "nosuch")
        smooth("bad-penalty", tangled["rand2d-tangled"], "--penalty", "nosuch")
        smooth("bad-missing", "inputs/no-such-file.vtk")
        smooth("bad-garbage", "inputs/garbage.vtk")
        smooth("bad-no-output-folder", tangled["rand2d-tangled"], out="{o}/missing-folder/out.vtk")
        smooth("bad-output-extension", tangled["rand2d-tangled"], ext="xyz")
        # the targets: every objective on every kind with opt and rules, and the refusals
        for t in l.targets:
            for obj in l.objectives:
                for mesh in ("rand2d-tangled", "plate-%s-o2-tangled" % mixed, "sphere-%s-tangled" % s_tri,
                             "hexgrid-tangled", "mixed-tangled"):
                    for s in ("opt", "rules"):
                        smooth("target-%s-%s-%s-%s" % (t, obj, s, mesh), tangled[mesh], "--target", t,
                               "--objective", obj, "--strategy", s)
            for s in l.strategies:
                smooth("target-%s-text-%s" % (t, s), tangled["grid-quad-tangled"], "--target", t, "--strategy", s,
                       json=False)
        if l.targets:
            smooth("bad-target", tangled["rand2d-tangled"], "--target", "nosuch")
        # the boundary rules: every strategy on the volume kinds, a feature angle, the refusals
        for b in l.boundaries:
            for mesh in ("cube-tangled", "hexgrid-tangled", "mixed-tangled"):
                for s in l.strategies:
                    smooth("boundary-%s-%s-%s" % (b, s, mesh), tangled[mesh], "--boundary", b, "--strategy", s)
                smooth("boundary-%s-text-%s" % (b, mesh), tangled[mesh], "--boundary", b, json=False)
            for mesh in ("rand2d-tangled", "sphere-%s-tangled" % s_tri):
                smooth("boundary-%s-%s" % (b, mesh), tangled[mesh], "--boundary", b)
        if l.boundaries:
            for a in ("15", "45", "90", "0", "180", "x"):
                smooth("feature-angle-%s" % a, tangled["hexgrid-tangled"], "--boundary", "slide", "--feature-angle=" + a)
            smooth("bad-feature-angle-fixed", tangled["hexgrid-tangled"], "--feature-angle", "45")
            smooth("bad-boundary", tangled["hexgrid-tangled"], "--boundary", "nosuch")
        # the text summary (its timings masked)
        for mesh in ("rand2d-tangled", "plate-%s-o2-tangled" % mixed, "sphere-%s-tangled" % l.surface_kinds[0],
                     "torus-o2-tangled", "rand3d-tangled", "hexgrid-tangled", "mixed-tangled"):
            for s in l.strategies:
                smooth("text-%s-%s" % (mesh, s), tangled[mesh], "--strategy", s, json=False)
        for p in self.shared_2d[:2]:
            smooth("text-shared-" + os.path.basename(p)[:-4], p, json=False)
        # every output format
        for mesh in ("rand2d-tangled", "grid-quad-tangled", "plate-%s-o2-tangled" % mixed,
                     "torus-%s-tangled" % s_mixed, "rand3d-tangled", "mixed-tangled"):
            for fmt in formats:
                ext, extra = target(fmt)
                smooth("format-%s-%s" % (mesh, fmt), tangled[mesh], "--passes", "1", *extra, ext=ext[1:])
        # surfaces: the other tangled ones, a subset of strategies and objectives; sliding curves
        for k in l.surface_kinds:
            for shape in ("sphere", "cylinder", "torus"):
                name = "%s-%s-tangled" % (shape, k)
                if name in full:
                    continue
                for obj in l.objectives:
                    smooth("surface-%s-obj-%s" % (name, obj), tangled[name], "--objective", obj, "--passes", "2")
                for s in l.strategies:
                    smooth("surface-%s-%s" % (name, s), tangled[name], "--strategy", s, "--passes", "2")
        for k in l.surface_kinds:
            src = tangled["cylinder-%s-tangled" % k]
            smooth("slide-curves-cylinder-%s" % k, src, "--slide-curves", "--passes", "2")
            smooth("slide-curves-cylinder-%s-laplace" % k, src, "--slide-curves", "--strategy", "laplace")
            smooth("slide-curves-cylinder-%s-old" % k, src, "--slide-curves", "--objective", "old")
        smooth("slide-curves-cylinder-o2", tangled["cylinder-o2-tangled"], "--slide-curves", "--passes", "1")
        smooth("slide-curves-sphere", tangled["sphere-%s-tangled" % s_tri], "--slide-curves", "--passes", "1")
        smooth("slide-curves-shared", self.shared_2d[-1], "--slide-curves", "--passes", "1")
        smooth("bad-slide-curves-planar", tangled["rand2d-tangled"], "--slide-curves")
        smooth("bad-slide-curves-volume", tangled["rand3d-tangled"], "--slide-curves")
        # volumes: the others with every objective and a subset of strategies
        for mesh in ("cube-tangled",):
            for obj in l.objectives:
                smooth("volume-%s-obj-%s" % (mesh, obj), tangled[mesh], "--objective", obj, "--passes", "2")
            for s in l.strategies:
                smooth("volume-%s-%s" % (mesh, s), tangled[mesh], "--strategy", s, "--passes", "2")
        for p in ("hexgrid-o2s", "hexgrid-bent", "mixed-bent", "rand3d-small", "cube-o1", "hexgrid-o1"):
            smooth("volume-%s" % p, g(p), "--passes", "1")
            smooth("volume-%s-old" % p, g(p), "--passes", "1", "--objective", "old")
        smooth("volume-c3-threshold", tangled["mixed-tangled"], "--strategy", "c3", "--threshold", "20")
        smooth("bad-penalty-volume", tangled["rand3d-tangled"], "--penalty", l.penalties[0])
        # the shared meshes
        for p in self.shared_2d:
            stem = os.path.basename(p)[:-4]
            for s in l.strategies:
                smooth("shared-%s-%s" % (stem, s), p, "--strategy", s, "--passes", "2")
            for obj in ("old", "condition", "untangle"):
                smooth("shared-%s-%s" % (stem, obj), p, "--objective", obj, "--passes", "2")
        for p in self.shared_3d:
            stem = os.path.basename(p)[:-4]
            for s in ("laplace", "smart", "opt", "rules"):
                smooth("shared-%s-%s" % (stem, s), p, "--strategy", s, "--passes", "1")
            for obj in ("old", "untangle"):
                smooth("shared-%s-%s" % (stem, obj), p, "--objective", obj, "--passes", "1")

        # render: every view on planar meshes, the views of surfaces and volumes, every figure
        def render(name, src, *args, size="360x300"):
            argv = ["render"] + ([src] if src else []) + ["-o", "{o}/out.png"]
            if size:
                argv += ["--size", size]
            self.add("render-" + name, *argv, *args)

        rt = tangled["rand2d-small-tangled"]
        for v in l.views:
            for mesh in ("rand2d-small-tangled", "grid-quad-tangled", "plate-%s-o2-tangled" % mixed):
                render("planar-%s-%s" % (v, mesh), tangled[mesh], "--view", v, "--passes", "1")
            render("planar-%s-node" % v, rt, "--view", v, "--node", "50", "--passes", "1")
            for obj in ("old", "new"):
                render("planar-%s-only-%s" % (v, obj), rt, "--view", v, "--objective", obj, "--passes", "1")
            for m in l.metrics:
                render("planar-%s-metric-%s" % (v, m), rt, "--view", v, "--metric", m)
            for t in l.themes:
                render("planar-%s-theme-%s" % (v, t), rt, "--view", v, "--theme", t, "--passes", "1")
            render("planar-%s-default" % v, tangled["rand2d-tangled"], "--view", v, size=None)
            render("planar-%s-penalty" % v, rt, "--view", v, "--penalty", l.penalties[-1], "--passes", "2")
        for s in l.strategies:
            render("planar-strategy-%s" % s, rt, "--view", "history", "--strategy", s, "--passes", "2")
            render("planar-strategy-%s-compare" % s, rt, "--view", "compare", "--strategy", s, "--passes", "1")
        for o in l.orders:
            render("planar-order-%s" % o, rt, "--view", "compare", "--order", o, "--passes", "1",
                   "--max-iter", "2", "--threshold", "20", "--strategy", "c1")
        render("planar-max-iter", rt, "--view", "levelset", "--max-iter", "8", "--node", "50")
        render("planar-dpr2", rt, "--view", "levelset", "--dpr", "2", size="300x200")
        render("planar-dpr-half", rt, "--view", "mesh", "--dpr", "0.5")
        render("planar-passes-5", rt, "--view", "history", "--passes", "5")
        for p in self.shared_2d[:-1]:
            render("shared-%s" % os.path.basename(p)[:-4], p, "--view", "compare", "--passes", "1")
        render("bad-node-missing", rt, "--view", "levelset", "--node", "100000")
        render("bad-node-fixed", rt, "--view", "levelset", "--node", "0")
        render("bad-objective", rt, "--objective", "sine")
        render("bad-compare-one-side", rt, "--view", "compare", "--objective", "old")
        render("bad-view", rt, "--view", "nosuch")
        render("bad-dpr", rt, "--dpr", "5")
        render("bad-dpr-zero", rt, "--dpr", "0")
        render("bad-size", rt, "--size", "big")
        render("bad-passes", rt, "--passes", "100000")
        render("bad-camera-planar", rt, "--camera", "10,20")
        render("bad-cut-planar", rt, "--cut", "z=0.5")
        render("bad-no-input", None)
        render("bad-input-and-figure", rt, "--figure", l.figures[0])
        render("bad-missing", "inputs/no-such-file.vtk")
        for mesh in ("sphere-%s-tangled" % l.surface_kinds[0], "torus-%s-tangled" % s_mixed, "cylinder-o2-tangled"):
            for v in l.views:
                render("surface-%s-%s" % (v, mesh), tangled[mesh], "--view", v, "--passes",
                       "1" if v != "levelset" else "0")
        sq = tangled["sphere-%s-tangled" % l.surface_kinds[0]]
        tm = tangled["torus-%s-tangled" % s_mixed]
        render("surface-mesh-camera", tm, "--view", "mesh", "--camera", "-40,60,1.5")
        render("surface-compare-camera", tm, "--view", "compare", "--camera", "10,-20", "--passes", "1")
        render("surface-compare-default", tm, "--view", "compare", size=None)
        render("surface-levelset-node", tm, "--view", "levelset", "--node", "5")
        render("surface-levelset-new", sq, "--view", "levelset", "--objective", "new")
        for m in l.metrics:
            render("surface-metric-%s" % m, tangled["torus-o2-tangled"], "--view", "mesh", "--metric", m)
        render("surface-dark", g("cylinder-%s-o1" % s_tri), "--view", "compare", "--theme", "dark", "--passes", "1")
        render("surface-shared", self.shared_2d[-1], "--view", "mesh")
        render("bad-surface-levelset-passes", sq, "--view", "levelset", "--passes", "1")
        render("bad-camera", sq, "--view", "mesh", "--camera", "a,b")
        for mesh in ("rand3d-tangled", "hexgrid-tangled", "mixed-tangled", "cube-o2-tangled"):
            for v in l.views:
                render("volume-%s-%s" % (v, mesh), tangled[mesh], "--view", v, "--passes", "1")
        for cut in ("x=0.3", "y=0.5", "z=0.8"):
            render("volume-cut-%s" % cut[0], tangled["mixed-tangled"], "--view", "mesh", "--cut", cut)
        render("volume-compare-hex", tangled["hexgrid-tangled"], "--view", "compare", "--cut", "y=0.5",
               "--passes", "1", "--camera", "20,30,1.2", "--theme", "dark")
        render("volume-compare-default", tangled["rand3d-tangled"], "--view", "compare", size=None)
        render("volume-shared", self.shared_3d[3], "--view", "mesh", "--cut", "x=0.5")
        render("bad-cut", tangled["rand3d-tangled"], "--view", "mesh", "--cut", "w=2")
        for f in l.figures:
            render("figure-%s" % f, None, "--figure", f, size=None)
        for f in l.figures[:3]:
            render("figure-%s-small" % f, None, "--figure", f, size="400x300")
            render("figure-%s-dark" % f, None, "--figure", f, "--theme", "dark", size="400x300")
            render("figure-%s-dpr" % f, None, "--figure", f, "--dpr", "1.5", size="300x200")
        render("figure-unknown", None, "--figure", "no-such-figure")
        return self.phases


# ---------------------------------------------------------------------------------------
# Running


def run_one(cli, out, name, argv):
    folder = os.path.join(out, "runs", name)
    os.makedirs(folder, exist_ok=True)
    args = [a.replace("{o}", "runs/" + name) for a in argv]
    t0 = time.time()
    p = subprocess.run([cli, *args], cwd=out, capture_output=True, timeout=300)
    seconds = time.time() - t0
    files = sorted(
        os.path.relpath(os.path.join(d, f), folder) for d, _, fs in os.walk(folder) for f in fs
    )
    entries = ["exit=%d" % p.returncode]
    for f in files:
        with open(os.path.join(folder, f), "rb") as fh:
            entries.append("%s=%s" % (f, sha(fh.read())))
    stdout = mask_times(p.stdout.decode("utf-8", "replace")).encode()
    entries.append("stdout=" + sha(stdout))
    entries.append("stderr=" + sha(p.stderr))
    with open(os.path.join(folder, "_stdout.txt"), "wb") as fh:
        fh.write(stdout)
    with open(os.path.join(folder, "_stderr.txt"), "wb") as fh:
        fh.write(p.stderr)
    with open(os.path.join(folder, "_command.txt"), "w") as fh:
        fh.write(" ".join(["smoothlab", *args]) + "\n")
    return name + " " + " ".join(entries), seconds


def cmd_run(a):
    cli = os.path.abspath(a.cli)
    if os.path.basename(cli) != "smoothlab":
        print("warning: %s is not named smoothlab; usage lines will name it as it is named" % cli,
              file=sys.stderr)
    out = os.path.abspath(a.out)
    meshes = a.meshes or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "meshes")
    if os.path.exists(out):
        shutil.rmtree(out)
    os.makedirs(os.path.join(out, "inputs"))
    t0 = time.time()
    shared_2d, shared_3d = [], []
    for group, rels in ((shared_2d, SHARED_2D), (shared_3d, SHARED_3D)):
        for rel in rels:
            src = os.path.join(meshes, rel)
            if not os.path.isfile(src):
                raise SystemExit("missing shared mesh %s (give --meshes DIR)" % src)
            dst = "inputs/shared-" + os.path.basename(rel)
            shutil.copyfile(src, os.path.join(out, dst))
            group.append(dst)
    with open(os.path.join(out, "inputs", "garbage.vtk"), "w") as fh:
        fh.write("# vtk DataFile Version 3.0\nnot a mesh\nASCII\nDATASET POLYDATA\nPOINTS 2 float\n0 0\n")
    phases = Matrix(Lists(cli), shared_2d, shared_3d).build()
    names = [n for ph in phases for n, _ in ph]
    dupes = sorted({n for n in names if names.count(n) > 1})
    if dupes:
        raise SystemExit("duplicate run names: %s" % ", ".join(dupes))
    lines, seconds = {}, {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for ph in phases:
            futures = [pool.submit(run_one, cli, out, n, argv) for n, argv in ph]
            for (n, _), f in zip(ph, futures):
                lines[n], seconds[n] = f.result()
    with open(os.path.join(out, "manifest.txt"), "w") as fh:
        for n in sorted(lines):
            fh.write(lines[n] + "\n")
    # the times are not part of the manifest
    with open(os.path.join(out, "timings.txt"), "w") as fh:
        for n in sorted(seconds, key=seconds.get, reverse=True):
            fh.write("%8.3f s  %s\n" % (seconds[n], n))
    failed = sum(1 for line in lines.values() if " exit=0 " not in line)
    print("%d runs (%d refused with a non-zero exit code) in %.1f s; manifest %s"
          % (len(lines), failed, time.time() - t0, os.path.join(out, "manifest.txt")))


def read_manifest(folder):
    runs = {}
    with open(os.path.join(folder, "manifest.txt")) as fh:
        for line in fh:
            name, _, rest = line.rstrip("\n").partition(" ")
            runs[name] = rest
    return runs


def cmd_compare(a):
    x, y = read_manifest(a.a), read_manifest(a.b)
    differ = 0
    for name in sorted(set(x) | set(y)):
        if name not in x or name not in y:
            differ += 1
            print("%s: only in %s" % (name, a.a if name in x else a.b))
        elif x[name] != y[name]:
            differ += 1
            ex, ey = dict(e.split("=", 1) for e in x[name].split()), dict(e.split("=", 1) for e in y[name].split())
            what = [k for k in sorted(set(ex) | set(ey)) if ex.get(k) != ey.get(k)]
            print("%s: %s differ" % (name, ", ".join(what)))
    if differ:
        print("%d of %d runs differ (each run's command, outputs, stdout and stderr are in DIR/runs/NAME/)"
              % (differ, len(set(x) | set(y))))
        return 1
    print("%d runs identical" % len(x))
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run the CLI over the matrix and write DIR/manifest.txt")
    r.add_argument("--cli", required=True, help="the smoothlab binary")
    r.add_argument("--out", required=True, help="output folder (replaced)")
    r.add_argument("--meshes", help="the shared test meshes (default ../shared/meshes beside the repository)")
    r.add_argument("--jobs", type=int, default=2, help="runs at once (default 2)")
    c = sub.add_parser("compare", help="compare two output folders' manifests")
    c.add_argument("a")
    c.add_argument("b")
    a = p.parse_args()
    if a.command == "run":
        cmd_run(a)
    else:
        sys.exit(cmd_compare(a))


if __name__ == "__main__":
    main()
