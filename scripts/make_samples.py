#!/usr/bin/env python3
"""Make the sample meshes of www/samples/ with a real unstructured mesher, Gmsh.

smoothlab's own generators (`smoothlab generate ...`) make structured and Delaunay
meshes; these samples are what a production mesher hands a smoother instead:
unstructured, graded, quad-dominant and curved. Each is a planar 2D mesh saved as
Gmsh .msh 2.2 ASCII with only its surface elements (a physical surface), so the
boundary is found from the topology and fixed.

    plate_hole_tri.msh   rectangle with an off-centre circular hole; 3-node triangles
                         (Frontal-Delaunay), refined towards the hole
    bracket_quad.msh     L-shaped bracket with a rounded inner corner and a bolt hole;
                         recombined (Blossom) into a quad-dominant mesh: 4-node quads
                         and a few 3-node triangles
    disk_tri6.msh        disk with an elliptic hole; second-order 6-node triangles
                         whose boundary mid-side nodes lie on the circle and ellipse

Rerun (needs the gmsh Python package, e.g. `pip install gmsh`; no display needed):

    python3 scripts/make_samples.py [OUTPUT_DIR]

OUTPUT_DIR defaults to www/samples (beside this script's folder). Gmsh meshes
deterministically for a given Gmsh version and these options (one thread); the script
prints the version, and www/samples/README.md records the one the committed files
were made with.
"""

import math
import os
import sys

import gmsh


def start(name):
    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)  # same mesh on every run
    gmsh.model.add(name)


def domain(surfaces):
    """Save only these surfaces' elements (msh 2.2 writes physical groups only)."""
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(2, surfaces, 1, "domain")


def save(path):
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.SaveAll", 0)
    gmsh.model.mesh.renumberNodes()
    gmsh.model.mesh.renumberElements()
    gmsh.write(path)
    gmsh.finalize()
    kb = os.path.getsize(path) / 1024
    print(f"wrote {path} ({kb:.0f} KB)")
    assert kb < 200, "keep each sample under 200 KB"


def plate_hole_tri(path):
    """A 4 x 2 plate with a hole of radius 0.35 at (1.4, 1.0): triangles, finer near the hole."""
    start("plate_hole_tri")
    occ = gmsh.model.occ
    plate = occ.addRectangle(0, 0, 0, 4.0, 2.0)
    hole = occ.addDisk(1.4, 1.0, 0, 0.35, 0.35)
    (surface,), _ = occ.cut([(2, plate)], [(2, hole)])
    occ.synchronize()
    domain([surface[1]])
    # element size 0.06 at the hole growing to 0.2 a distance 1.2 away
    field = gmsh.model.mesh.field
    r = 0.36
    hole_curves = [c for _, c in gmsh.model.getEntitiesInBoundingBox(1.4 - r, 1.0 - r, -1, 1.4 + r, 1.0 + r, 1, dim=1)]
    assert hole_curves, "the hole's curve"
    dist = field.add("Distance")
    field.setNumbers(dist, "CurvesList", hole_curves)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", 0.06)
    field.setNumber(thr, "SizeMax", 0.2)
    field.setNumber(thr, "DistMin", 0.0)
    field.setNumber(thr, "DistMax", 1.2)
    field.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay
    gmsh.model.mesh.generate(2)
    save(path)


def bracket_quad(path):
    """An L-shaped bracket (legs 3 x 1 and 1 x 3), inner corner rounded with radius 0.5,
    a bolt hole of radius 0.3 in the corner block; recombined into quads."""
    start("bracket_quad")
    occ = gmsh.model.occ
    horizontal = occ.addRectangle(0, 0, 0, 3.0, 1.0)
    vertical = occ.addRectangle(0, 0, 0, 1.0, 3.0)
    fillet = occ.addRectangle(1.0, 1.0, 0, 0.5, 0.5)
    round_off = occ.addDisk(1.5, 1.5, 0, 0.5, 0.5)
    body, _ = occ.fuse([(2, horizontal)], [(2, vertical), (2, fillet)])
    body, _ = occ.cut(body, [(2, round_off)])
    hole = occ.addDisk(0.5, 0.5, 0, 0.3, 0.3)
    body, _ = occ.cut(body, [(2, hole)])
    occ.synchronize()
    surfaces = [tag for dim, tag in body if dim == 2]
    domain(surfaces)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.1)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.14)
    gmsh.option.setNumber("Mesh.Algorithm", 8)  # Frontal-Delaunay for quads
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)  # Blossom
    for s in surfaces:
        gmsh.model.mesh.setRecombine(2, s)
    gmsh.model.mesh.generate(2)
    save(path)


def disk_tri6(path):
    """A disk of radius 1 with an elliptic hole (semi-axes 0.45, 0.25, turned 30 degrees);
    quadratic triangles with the boundary mid-side nodes on the curves."""
    start("disk_tri6")
    occ = gmsh.model.occ
    disk = occ.addDisk(0, 0, 0, 1.0, 1.0)
    hole = occ.addDisk(0.1, 0.05, 0, 0.45, 0.25)
    occ.rotate([(2, hole)], 0.1, 0.05, 0, 0, 0, 1, math.radians(30))
    (surface,), _ = occ.cut([(2, disk)], [(2, hole)])
    occ.synchronize()
    domain([surface[1]])
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.12)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.16)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)  # interior mid nodes at midpoints
    gmsh.model.mesh.generate(2)
    gmsh.model.mesh.setOrder(2)
    save(path)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "www", "samples")
    out = os.path.normpath(out)
    os.makedirs(out, exist_ok=True)
    print(f"gmsh {gmsh.__version__}")
    plate_hole_tri(os.path.join(out, "plate_hole_tri.msh"))
    bracket_quad(os.path.join(out, "bracket_quad.msh"))
    disk_tri6(os.path.join(out, "disk_tri6.msh"))


if __name__ == "__main__":
    main()
