#!/usr/bin/env bash
# Side-by-side timings of ray_loop builds: each round runs
# every BINARY:ENGINE once on each set, in turn, so that a burst of load falls on all of them; it
# prints each one's median over the rounds of ray_loop's fastest pass (3 passes a run), and for
# every build after the first, the median over the rounds of the first's speed over its own: a
# ratio of two runs seconds apart, which a slow spell of the machine moves less than a ratio of
# medians.
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
# The median of the numbers on stdin, one a line.
median() { grep . | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
for set in "${sets[@]}"; do
  declare -A times=()
  for _ in $(seq "$rounds"); do
    for spec in "$@"; do
      # shellcheck disable=SC2086  # "MESH KIND" splits into two arguments
      line=$(setarch -R "${spec%%:*}" "$shared" $set "${spec##*:}" "$query" 3)
      times[$spec]="${times[$spec]:-} $(sed -E 's/.*: ([0-9.]+) s a pass.*/\1/' <<< "$line")"
    done
  done
  first=$1
  for spec in "$@"; do
    line="$set $query $spec: median $(tr ' ' '\n' <<< "${times[$spec]}" | median) s (runs:${times[$spec]})"
    if [ "$spec" != "$first" ]; then
      ratio=$(paste <(tr ' ' '\n' <<< "${times[$first]}" | grep .) <(tr ' ' '\n' <<< "${times[$spec]}" | grep .) |
        awk '{print $2 / $1}' | median)
      line+="; ${first##*/} over ${spec##*/}, paired by round: $ratio"
    fi
    echo "$line"
  done
  unset times
done
