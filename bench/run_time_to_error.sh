#!/usr/bin/env bash
# Time to a given error, glint against its smallpt-equivalent mode and against two earlier
# versions (d505f08, before issue 5; c02a220, before the light-path connections), side by side
# in one run: their speed_vs_error is built from `git archive` in temporary folders, and the
# binaries' ladders alternate, sharing the reference images in bench/out/. Writes
# bench/results/time_to_error.csv, bench/plots/tte-*.svg and the table in bench/BENCHMARKS.md.
# Run by hand (about 20 minutes on 2 cores):
#   bench/run_time_to_error.sh [repeats]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-1}
cmake -S . -B build -G Ninja >/dev/null && cmake --build build --target speed_vs_error >/dev/null
old=$(mktemp -d /tmp/glint-previous.XXXXXX)
trap 'rm -rf "$old"' EXIT
for previous in d505f08 c02a220; do
  mkdir "$old/$previous"
  git archive "$previous" | tar -x -C "$old/$previous"
  cmake -S "$old/$previous" -B "$old/$previous/build" -G Ninja >/dev/null
  cmake --build "$old/$previous/build" --target speed_vs_error >/dev/null
done
csv=bench/results/time_to_error.csv
echo "version,repeat,scene,mode,spp,seconds,rmse,estimate" > "$csv"
ladder() {  # version binary repeat scene modes max-spp max-seconds (reference sizes as run_speed_vs_error.sh)
  local refspp=4096; [ "$4" = mesh ] && refspp=2048; [ "$4" = caustic ] && refspp=8192
  "$2" "scenes/$4.json" --out "bench/out/$4" --width 256 --height 192 --reference-spp $refspp \
    --max-spp "$6" --threads 2 --max-seconds "$7" --modes "$5" | sed "s/^/$1,$3,/" | tee -a "$csv"
}
for r in $(seq 1 "$repeats"); do
  for scene in cornell caustic mesh; do
    smallpt_spp=1024; smallpt_s=150; [ $scene = mesh ] && smallpt_spp=8 && smallpt_s=20
    ladder glint build/bench/speed_vs_error "$r" $scene glint,no-lt 1024 25
    ladder d505f08 "$old/d505f08/build/bench/speed_vs_error" "$r" $scene glint 1024 40
    ladder c02a220 "$old/c02a220/build/bench/speed_vs_error" "$r" $scene glint 1024 25
    ladder glint build/bench/speed_vs_error "$r" $scene smallpt $smallpt_spp $smallpt_s
  done
done
/usr/bin/python3 bench/plot_time_to_error.py "$csv"
