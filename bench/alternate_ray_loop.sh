#!/usr/bin/env bash
# Side-by-side timings of ray_loop builds (bench/BENCHMARKS.md, ninth round on): each round runs
# every BINARY:ENGINE once on each set, in turn, so that a burst of load falls on all of them; it
# prints each one's median over the rounds of ray_loop's fastest pass (3 passes a run).
#   bench/alternate_ray_loop.sh QUERY ROUNDS "MESH KIND"... -- BINARY:ENGINE...
# QUERY: closest | any; ENGINE: glint | glint-split | medium | high (see ray_loop.cpp). Copy the
# builds to compare out of build/bench first; SHARED (default ../shared) holds the meshes and rays.
set -euo pipefail
shared=${SHARED:-$(dirname "$0")/../../shared}
query=$1 rounds=$2
shift 2
sets=()
while [ "$1" != "--" ]; do sets+=("$1"); shift; done
shift
for set in "${sets[@]}"; do
  declare -A times=()
  for _ in $(seq "$rounds"); do
    for spec in "$@"; do
      # shellcheck disable=SC2086  # "MESH KIND" splits into two arguments
      line=$(setarch -R "${spec%%:*}" "$shared" $set "${spec##*:}" "$query" 3)
      times[$spec]="${times[$spec]:-} $(sed -E 's/.*: ([0-9.]+) s a pass.*/\1/' <<< "$line")"
    done
  done
  for spec in "$@"; do
    median=$(tr ' ' '\n' <<< "${times[$spec]}" | grep . | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}')
    echo "$set $query $spec: median $median s (runs:${times[$spec]})"
  done
  unset times
done
