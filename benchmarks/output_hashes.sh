#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Hashes what the three tools write for every file of the shared data: the meshes of
# pcl_cocone_reconstruction, the flags of pcl_boundary_sample_estimation and the points
# kept by pcl_voronoi_decimation at rho 0.3 and 0.4. Run it before and after a change
# that must not change behaviour, and compare the two lists (diff).
#
#   benchmarks/output_hashes.sh TOOL_DIR [DATA_DIR] > hashes.txt
#
# TOOL_DIR holds the three tools (e.g. build/tools); DATA_DIR defaults to
# ../shared/data beside the source folder. A tool that fails prints "failed" in place
# of the hash, so a list still compares line by line.
set -uo pipefail

tool_dir=${1:?usage: output_hashes.sh TOOL_DIR [DATA_DIR]}
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
data_dir=${2:-$source_dir/../shared/data}
[[ -d $data_dir ]] || { echo "output_hashes: no data folder $data_dir" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

hash_of() { # tool output args...
  local tool=$1 output=$2
  shift 2
  if "$tool_dir/$tool" "$@" "$output" >/dev/null 2>&1; then
    sha256sum "$output" | cut -d' ' -f1
  else
    echo failed
  fi
  rm -f "$output"
}

for input in "$data_dir"/*; do
  name=$(basename "$input")
  [[ $name == README.md ]] && continue
  echo "$(hash_of pcl_cocone_reconstruction "$work/mesh.ply" "$input") reconstruction $name"
  echo "$(hash_of pcl_boundary_sample_estimation "$work/flags.pcd" "$input") boundary $name"
  for rho in 0.3 0.4; do
    echo "$(hash_of pcl_voronoi_decimation "$work/kept.pcd" "$input" -rho $rho) decimation-$rho $name"
  done
done
