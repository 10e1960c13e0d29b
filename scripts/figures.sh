#!/usr/bin/env bash
# Regenerates the docs' pictures in docs/images/ with the smoothlab CLI
# (run by `make figures`). Every input is made by smoothlab's own generators.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
S=target/release/smoothlab
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p docs/images
# a plate with a hole, tangled by a seeded perturbation
$S generate plate --kind tri -o "$tmp/plate.vtk"
$S generate perturb "$tmp/plate.vtk" --amount 0.5 --seed 1 -o "$tmp/tangled.vtk"
$S render "$tmp/tangled.vtk" -o docs/images/compare-tangled-plate.png --view compare --passes 3 --size 1200x680
# node 120 (0-based) of Freitag's rand2d, a six-element star: the kinked max-min contours beside the smooth ones
$S generate rand2d --seed 1 -o "$tmp/rand2d.vtk"
$S render "$tmp/rand2d.vtk" -o docs/images/levelset-rand2d.png --view levelset --node 120 --size 1100x560
# Freitag's Figure 3: angle histograms after 3 passes
$S render "$tmp/rand2d.vtk" -o docs/images/histogram-rand2d.png --view histogram --passes 3 --size 900x480
# a surface (Chen et al.'s Figs. 18-19 in spirit): a mixed torus tangled in its tangent
# planes, as loaded, then old and new after one pass
$S generate torus --kind mixed --resolution 3 -o "$tmp/torus.vtk"
$S generate perturb "$tmp/torus.vtk" --amount 0.7 --seed 2 -o "$tmp/torus-tangled.vtk"
$S render "$tmp/torus-tangled.vtk" -o docs/images/surface-torus-tangled.png --view mesh --size 700x520
$S render "$tmp/torus-tangled.vtk" -o docs/images/surface-torus-compare.png --view compare --passes 1 --size 1400x560
# tetrahedra: Freitag's rand3D cut half way up z, and a cube of tetrahedra tangled by
# Knupp's random moves, old and new after one pass, cut across y
$S generate rand3d --seed 1 -o "$tmp/rand3d.vtk"
$S render "$tmp/rand3d.vtk" -o docs/images/rand3d-cut.png --view mesh --cut z=0.5 --size 700x560
$S generate cube --cells 8 -o "$tmp/cube.vtk"
$S generate perturb "$tmp/cube.vtk" --amount 0.8 --seed 1 -o "$tmp/cube-tangled.vtk"
$S render "$tmp/cube-tangled.vtk" -o docs/images/cube-tangled-compare.png --view compare --passes 1 --cut y=0.5 --size 1400x560
echo "wrote docs/images/{compare-tangled-plate,levelset-rand2d,histogram-rand2d,surface-torus-tangled,surface-torus-compare,rand3d-cut,cube-tangled-compare}.png"
