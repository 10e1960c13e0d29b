#!/usr/bin/env bash
# Writes the seed corpora (fuzz/seeds/<target>/) from the project's own fixtures
# (tests/data) and small meshes made by `smoothlab generate`. Run from anywhere:
#   bash fuzz/make_seeds.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
seeds="$here/seeds"
gen="$(mktemp -d)"
trap 'rm -rf "$gen"' EXIT

cargo build --quiet --manifest-path "$root/Cargo.toml" --bin smoothlab
sl="$root/target/debug/smoothlab"

# Small generated meshes: every element kind, linear and quadratic, both .msh versions.
for v in 2.2 4.1; do
  $sl generate star --kind regular -o "$gen/star-regular-$v.msh" --msh-version "$v"
  $sl generate star --kind quad -o "$gen/star-quad-$v.msh" --msh-version "$v"
  $sl generate grid --nx 2 --ny 2 --kind tri -o "$gen/grid-tri-$v.msh" --msh-version "$v"
  $sl generate grid --nx 2 --ny 1 --kind quad -o "$gen/grid-quad-$v.msh" --msh-version "$v"
  $sl generate plate --kind mixed --resolution 1 -o "$gen/plate-mixed-$v.msh" --msh-version "$v"
  $sl generate plate --kind tri --order 2 --resolution 1 -o "$gen/plate-tri6-$v.msh" --msh-version "$v"
  $sl generate plate --kind quad --order 2 --resolution 1 -o "$gen/plate-quad8-$v.msh" --msh-version "$v"
done
for m in star-regular star-quad grid-tri grid-quad plate-mixed; do
  for ext in vtk obj off; do $sl convert "$gen/$m-2.2.msh" "$gen/$m.$ext"; done
done
for m in plate-tri6 plate-quad8; do $sl convert "$gen/$m-2.2.msh" "$gen/$m.vtk"; done
$sl convert "$gen/star-regular-2.2.msh" "$gen/star-regular.node"
# Issue 16's classes: a rand2D with one node lifted far off its plane (a mistyped exponent).
$sl generate rand2d --points 60 --per-side 5 --seed 7 -o "$gen/rand2d.obj"
awk '/^v /{n++; if (n==10) {$4="3e6"}} {print}' "$gen/rand2d.obj" > "$gen/rand2d-outlier.obj"
$sl convert "$gen/plate-tri6-2.2.msh" "$gen/plate-tri6.node"
# Medit: the linear meshes, and small volumes of every linear kind.
for m in star-regular star-quad grid-tri grid-quad plate-mixed; do $sl convert "$gen/$m-2.2.msh" "$gen/$m.mesh"; done
$sl generate mixed --cells 2 -o "$gen/mixed.mesh"
$sl generate hexgrid --cells 2 -o "$gen/hexgrid.mesh"
$sl generate cube --cells 1 -o "$gen/cube.mesh"

rm -rf "$seeds"
mkdir -p "$seeds"/{msh22,msh41,vtk,triangle,obj,off,medit,read_bytes}
# .msh bodies: the targets supply the $MeshFormat header themselves.
body() { awk 'NR>3' "$1"; }
for f in "$gen"/*-2.2.msh; do body "$f" > "$seeds/msh22/$(basename "$f" .msh)"; done
for f in "$gen"/*-4.1.msh; do body "$f" > "$seeds/msh41/$(basename "$f" .msh)"; done
for f in "$root"/tests/data/*.msh "$root"/tests/data/bad/*.msh; do
  case "$(sed -n 2p "$f")" in
    2*) body "$f" > "$seeds/msh22/fixture-$(basename "$f" .msh)" ;;
    4.1*) body "$f" > "$seeds/msh41/fixture-$(basename "$f" .msh)" ;;
  esac
done
for ext in vtk obj off; do
  cp "$gen"/*."$ext" "$seeds/$ext/"
  for f in "$root"/tests/data/*."$ext" "$root"/tests/data/bad/*."$ext"; do cp "$f" "$seeds/$ext/fixture-$(basename "$f")"; done
  # byte-order marks, extreme scales (tests/data/hardening)
  for f in "$root"/tests/data/hardening/*."$ext"; do cp "$f" "$seeds/$ext/hardening-$(basename "$f")"; done
done
cp "$gen/rand2d-outlier.obj" "$seeds/obj/rand2d-outlier.obj"
cp "$gen"/*.mesh "$seeds/medit/"
for f in "$root"/tests/data/*.mesh "$root"/tests/data/bad/*.mesh; do cp "$f" "$seeds/medit/fixture-$(basename "$f")"; done
# Triangle: .node, a NUL byte, .ele.
pair() { { cat "$1.node"; printf '\0'; cat "$1.ele"; } > "$2"; }
pair "$gen/star-regular" "$seeds/triangle/star-regular"
pair "$gen/plate-tri6" "$seeds/triangle/plate-tri6"
for f in "$root"/tests/data/*.node "$root"/tests/data/bad/*.node; do
  pair "${f%.node}" "$seeds/triangle/fixture-$(basename "$f" .node)"
done
pair "$root/tests/data/hardening/bom" "$seeds/triangle/hardening-bom"
# read_bytes: the first byte picks the name (0 .msh, 1 .vtk, 2 .obj, 3 .off, 4 .node, 7 .mesh).
tag() { { printf "\\x0$1"; cat "$2"; } > "$3"; }
tag 0 "$gen/grid-tri-2.2.msh" "$seeds/read_bytes/msh-grid-tri"
tag 0 "$gen/plate-tri6-4.1.msh" "$seeds/read_bytes/msh-plate-tri6"
tag 0 "$root/tests/data/bad/binary.msh" "$seeds/read_bytes/msh-binary"
tag 1 "$gen/plate-quad8.vtk" "$seeds/read_bytes/vtk-plate-quad8"
tag 1 "$root/tests/data/bad/binary.vtk" "$seeds/read_bytes/vtk-binary"
tag 2 "$root/tests/data/bad/not_utf8.obj" "$seeds/read_bytes/obj-not-utf8"
tag 3 "$gen/star-quad.off" "$seeds/read_bytes/off-star-quad"
tag 4 "$gen/star-regular.node" "$seeds/read_bytes/node-star"
tag 0 "$root/tests/data/hardening/bom.msh" "$seeds/read_bytes/msh-bom"
tag 1 "$root/tests/data/hardening/triangles_1e300.vtk" "$seeds/read_bytes/vtk-1e300"
tag 2 "$root/tests/data/hardening/bom.obj" "$seeds/read_bytes/obj-bom"
tag 2 "$gen/rand2d-outlier.obj" "$seeds/read_bytes/obj-rand2d-outlier"
tag 4 "$root/tests/data/hardening/bom.node" "$seeds/read_bytes/node-bom"
tag 7 "$gen/mixed.mesh" "$seeds/read_bytes/mesh-mixed"
echo "seeds written to $seeds: $(find "$seeds" -type f | wc -l) files, $(du -sh "$seeds" | cut -f1)"
