#!/usr/bin/env bash
# What AOVs cost: CPU time (user + sys, which load from other processes moves less than wall
# time) of `glint render` on each scene, run in turn by every LABEL=COMMAND in each round so a
# slow spell of the machine falls on all of them; prints each one's median over the rounds and,
# for every command after the first, the median over the rounds of its time over the first's.
#   bench/aov_cost.sh ROUNDS "WIDTH HEIGHT SPP" SCENE... -- LABEL=GLINT[:EXTRA OPTIONS]...
# e.g. bench/aov_cost.sh 5 "320 240 16" scenes/cornell.json scenes/mesh.json -- \
#        main=/tmp/glint-main exr=build/server/glint exr+aovs=build/server/glint:--aovs
set -euo pipefail
rounds=$1
read -r width height spp <<< "$2"
shift 2
scenes=()
while [ "$1" != "--" ]; do scenes+=("$1"); shift; done
shift
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for scene in "${scenes[@]}"; do
  : > "$out/runs"
  for round in $(seq "$rounds"); do
    for spec in "$@"; do
      label=${spec%%=*} command=${spec#*=}
      glint=${command%%:*} extra=""
      [ "$glint" != "$command" ] && extra=${command#*:}
      # shellcheck disable=SC2086  # EXTRA splits into options
      /usr/bin/time -f "%U %S" -o "$out/time" "$glint" render "$scene" -o "$out/image.png" --width "$width" \
        --height "$height" --spp "$spp" --threads 2 $extra > /dev/null 2>&1
      echo "$round $label $(awk '{print $1 + $2}' "$out/time")" >> "$out/runs"
    done
  done
  # Medians per label, and of each label's time over the first label's in the same round.
  /usr/bin/python3 - "$out/runs" "$(basename "$scene") ${width}x$height $spp spp" "${1%%=*}" <<'PY'
import statistics, sys
runs, name, first = sys.argv[1:]
times = {}
for line in open(runs):
    round_, label, seconds = line.split()
    times.setdefault(label, {})[round_] = float(seconds)
for label, by_round in times.items():
    text = "%s %s: median CPU %.3f s (runs: %s)" % (name, label, statistics.median(by_round.values()),
                                                   " ".join("%.2f" % v for v in by_round.values()))
    if label != first:
        ratio = statistics.median(by_round[r] / times[first][r] for r in by_round)
        text += "; over %s, paired by round: %.3f" % (first, ratio)
    print(text)
PY
done
