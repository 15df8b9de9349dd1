#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Regenerates docs/benchmarks.md: builds pcl_cocone_benchmark in BUILD_DIR (configured
# as a Release build without tests when it is not configured yet) and runs it.
#
#   benchmarks/run_benchmarks.sh BUILD_DIR [--quick] [other benchmark options]
#
# The full run takes about an hour on a 2-core machine; --quick (no 1M inputs, no
# peers at 100k points and more) a few minutes.
set -euo pipefail

if [[ $# -lt 1 || "$1" == -* ]]; then
  echo "usage: $0 BUILD_DIR [--quick] [pcl_cocone_benchmark options]" >&2
  exit 1
fi
source_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="$1"
shift

if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release \
    -DPCL_COCONE_BUILD_TESTS=OFF -DPCL_COCONE_BUILD_BENCHMARKS=ON
fi
cmake --build "$build_dir" --target pcl_cocone_benchmark -j "${JOBS:-2}"

binary="$(find "$build_dir" -name pcl_cocone_benchmark -type f -perm -u+x | head -n 1)"
if [[ -z "$binary" ]]; then
  echo "$0: pcl_cocone_benchmark was not built in $build_dir" >&2
  exit 1
fi

export PCL_COCONE_BENCH_INVOCATION="benchmarks/run_benchmarks.sh $build_dir${*:+ $*}"
exec "$binary" --markdown "$source_dir/docs/benchmarks.md" "$@"
