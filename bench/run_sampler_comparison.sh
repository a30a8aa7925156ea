#!/usr/bin/env bash
# Time to error before and after a change to the sampler, on every scene in scenes/, side by
# side in one run: `speed_vs_error` of this version and of PREVIOUS (built from `git archive` in
# a temporary folder) alternate scene by scene, both measured against references that this
# version renders (kept in bench/out/sampler/, with their own error estimates, which
# plot_sampler_comparison.py takes out of the measured error). Writes
# bench/results/sampler_comparison.csv, bench/plots/sampler-*.svg and the table between the
# sampler_comparison markers of bench/BENCHMARKS.md. Run by hand (about 25 minutes on 2 cores):
#   bench/run_sampler_comparison.sh [PREVIOUS]
set -euo pipefail
cd "$(dirname "$0")/.."
previous=${1:-959f953}
width=128 height=96 reference_spp=8192 max_spp=4096
cmake -S . -B build -G Ninja >/dev/null && cmake --build build --target speed_vs_error >/dev/null
old=$(mktemp -d /tmp/glint-previous.XXXXXX)
trap 'rm -rf "$old"' EXIT
git archive "$previous" | tar -x -C "$old"
cmake -S "$old" -B "$old/build" -G Ninja >/dev/null
cmake --build "$old/build" --target speed_vs_error >/dev/null
csv=bench/results/sampler_comparison.csv
echo "version,scene,mode,spp,seconds,rmse,estimate" > "$csv"
for scene in cornell caustic mesh spheres; do
  for version in after before; do
    binary=build/bench/speed_vs_error
    [ $version = before ] && binary="$old/build/bench/speed_vs_error"
    "$binary" "scenes/$scene.json" --out "bench/out/sampler/$scene" --width $width --height $height \
      --reference-spp $reference_spp --max-spp $max_spp --max-seconds 600 --threads 2 --modes glint | sed "s/^/$version,/" | tee -a "$csv"
  done
done
/usr/bin/python3 bench/plot_sampler_comparison.py "$csv" bench/out/sampler "$previous" \
  "${width}x${height}-${reference_spp}spp"
