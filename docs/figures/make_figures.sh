#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Regenerates every figure of docs/figures/ (listed in docs/figures.md) with the
# project's tools, from the scans in the data folder. It builds nothing: pass the build
# folder that holds the tools, e.g.
#
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
#   cmake --build build --target pcl_cocone_reconstruction pcl_voronoi_decimation \
#     pcl_boundary_sample_estimation pcl_cocone_render
#   docs/figures/make_figures.sh build
#
# The data folder is $PCL_COCONE_DATA_DIR, by default ../shared/data next to the
# checkout; the scans are read where they are, never copied. Intermediate clouds and
# meshes go to a temporary folder that is removed at the end. Without a DISPLAY the
# script runs itself again under xvfb-run -a (the renderer needs an X server); every
# command is printed before it runs.
set -eu

usage() {
  echo "usage: $0 BUILD_DIR   (data from \$PCL_COCONE_DATA_DIR, default ../shared/data)" >&2
  exit 1
}
die() {
  echo "$(basename "$0"): $*" >&2
  exit 1
}

[ $# -eq 1 ] || usage
case "$1" in -h | --help) usage ;; esac

figures=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$figures/../.." && pwd)
[ -d "$1" ] || die "no build folder $1"
build=$(cd "$1" && pwd)
data=${PCL_COCONE_DATA_DIR:-$root/../shared/data}
[ -d "$data" ] || die "no data folder $data (set PCL_COCONE_DATA_DIR)"
data=$(cd "$data" && pwd)

reconstruction=$build/tools/pcl_cocone_reconstruction
decimation=$build/tools/pcl_voronoi_decimation
boundary=$build/tools/pcl_boundary_sample_estimation
render=$build/apps/render/pcl_cocone_render
for tool in "$reconstruction" "$decimation" "$boundary" "$render"; do
  [ -x "$tool" ] || die "$tool is missing: build it first (see the top of $0)"
done
for scan in bun_zipper_35947.ply bun000_rawscan_40256.ply; do
  [ -f "$data/$scan" ] || die "$data/$scan is missing"
done

# One X server for every picture: the script itself runs under xvfb-run.
if [ -z "${DISPLAY:-}" ]; then
  [ -z "${PCL_COCONE_FIGURES_XVFB:-}" ] || die "xvfb-run gave no DISPLAY"
  command -v xvfb-run > /dev/null || die "no DISPLAY and no xvfb-run (apt-get install xvfb)"
  PCL_COCONE_FIGURES_XVFB=1 exec xvfb-run -a "$0" "$@"
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/pcl_cocone_figures.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' INT TERM

# Prints a command (paths shortened to $BUILD, $DATA, $WORK, docs/...) and runs it.
run() {
  echo "\$ $*" | sed -e "s|$build|\$BUILD|g" -e "s|$data|\$DATA|g" \
    -e "s|$work|\$WORK|g" -e "s|$root/||g"
  "$@" > "$work/log" 2>&1 || { cat "$work/log" >&2; die "failed: $*"; }
  grep -E "^(kept|vertices used|[0-9]+ boundary samples)" "$work/log" | sed 's/^/  /' || true
}

# 1. The Stanford bunny (35947 samples) reconstructed with COCONE and boundary
#    detection, shaded.
run "$reconstruction" "$data/bun_zipper_35947.ply" "$work/bunny.ply"
run "$render" "$work/bunny.ply" "$figures/bunny_reconstruction.png"

# 2. The paper's figure 9: the bunny decimated at rho 0.25, 0.35 and 0.4, each
#    decimated cloud reconstructed; edges drawn to show the sampling density.
for rho in 0.25 0.35 0.4; do
  name=$(echo "$rho" | sed -e 's/^0\.//' -e 's/^\(.\)$/\10/')
  run "$decimation" "$data/bun_zipper_35947.ply" "$work/bunny_rho$name.pcd" -rho "$rho"
  run "$reconstruction" "$work/bunny_rho$name.pcd" "$work/bunny_rho$name.ply"
  run "$render" "$work/bunny_rho$name.ply" "$figures/bunny_decimated_rho0$name.png" \
    -wireframe -width 400 -height 300
done

# 3. Boundary samples (red) of a raw single-view range scan of the bunny, over its
#    reconstruction: the scan's borders and occlusion edges (the paper's figures 4, 10).
run "$boundary" "$data/bun000_rawscan_40256.ply" "$work/bun000_boundary.pcd"
run "$reconstruction" "$data/bun000_rawscan_40256.ply" "$work/bun000.ply"
run "$render" "$work/bun000.ply" "$figures/bunny_scan_boundary.png" \
  -boundary "$work/bun000_boundary.pcd" -azimuth -35 -elevation 10 -point_size 3.5

# 4. A generated open surface: 4000 samples of the saddle z = 0.5 (x^2 - y^2) over the
#    unit disc (a sunflower lattice, no randomness), its rim found by BOUNDARY.
awk 'BEGIN {
  n = 4000; golden = 3.14159265358979 * (3 - sqrt(5))
  for (i = 0; i < n; i++) {
    r = sqrt((i + 0.5) / n); t = i * golden; x = r * cos(t); y = r * sin(t)
    printf "%.7f %.7f %.7f\n", x, y, 0.5 * (x * x - y * y)
  }
}' > "$work/saddle.xyz"
echo "\$ awk ... > \$WORK/saddle.xyz   (see $0)"
run "$boundary" "$work/saddle.xyz" "$work/saddle_boundary.pcd"
run "$reconstruction" "$work/saddle.xyz" "$work/saddle.ply"
run "$render" "$work/saddle.ply" "$figures/saddle_boundary.png" \
  -boundary "$work/saddle_boundary.pcd" -elevation -60 -azimuth 30

# The README shows them as they are: keep each small.
status=0
for png in "$figures"/*.png; do
  size=$(wc -c < "$png")
  echo "$(basename "$png"): $size bytes"
  if [ "$size" -ge 153600 ]; then
    echo "  larger than 150 KB: use a smaller -width/-height" >&2
    status=1
  fi
done
exit $status
