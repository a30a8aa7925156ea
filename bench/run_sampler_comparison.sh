#!/usr/bin/env bash
# Time to error before and after a change to the sampler, on every scene in scenes/, side by
# side in one run, against references that this version renders (kept in bench/out/sampler/,
# with their own error estimates, which plot_sampler_comparison.py takes out of the measured
# error). Two stages:
#   ladders  `speed_vs_error` of this version and of PREVIOUS (built from `git archive` in a
#            temporary folder) alternate scene by scene, 4 to 4096 spp: time to the high target
#            (this version's error at 4096 spp);
#   seeds    `glint render` of both versions at 64 spp with seeds 1-24, alternating: the mean
#            squared error there and the time it took, for the low target, where one seed's
#            error is too noisy to compare (fireflies).
# Writes bench/results/sampler_comparison.csv and sampler_seeds.csv, bench/plots/sampler-*.svg
# and the tables between the sampler_comparison markers of bench/BENCHMARKS.md. Run by hand
# (about 35 minutes on 2 cores):
#   bench/run_sampler_comparison.sh [PREVIOUS [ladders|seeds|all]]
set -euo pipefail
cd "$(dirname "$0")/.."
previous=${1:-959f953} stage=${2:-all}
width=128 height=96 reference_spp=8192 max_spp=4096 seeds=24
scenes="cornell caustic mesh spheres"
cmake -S . -B build -G Ninja >/dev/null && cmake --build build --target speed_vs_error glint >/dev/null
old=$(mktemp -d /tmp/glint-previous.XXXXXX)
trap 'rm -rf "$old"' EXIT
git archive "$previous" | tar -x -C "$old"
cmake -S "$old" -B "$old/build" -G Ninja >/dev/null
cmake --build "$old/build" --target speed_vs_error glint >/dev/null
binary() {  # version tool
  if [ "$1" = before ]; then echo "$old/build/$2"; else echo "build/$2"; fi
}
if [ "$stage" != seeds ]; then
  csv=bench/results/sampler_comparison.csv
  echo "version,scene,mode,spp,seconds,rmse,estimate" > "$csv"
  for scene in $scenes; do
    for version in after before; do
      "$(binary $version bench/speed_vs_error)" "scenes/$scene.json" --out "bench/out/sampler/$scene" \
        --width $width --height $height --reference-spp $reference_spp --max-spp $max_spp --max-seconds 600 \
        --threads 2 --modes glint | sed "s/^/$version,/" | tee -a "$csv"
    done
  done
fi
if [ "$stage" != ladders ]; then
  csv=bench/results/sampler_seeds.csv
  echo "version,scene,seed,seconds,image" > "$csv"
  images=bench/out/sampler/seeds
  mkdir -p "$images"
  for scene in $scenes; do
    for seed in $(seq 1 $seeds); do
      for version in after before; do
        image="$images/$scene-$version-$seed.pfm"
        start=$EPOCHREALTIME
        "$(binary $version server/glint)" render "scenes/$scene.json" --width $width --height $height --spp 64 \
          --seed "$seed" --threads 2 -o "$images/last.png" --hdr "$image" >/dev/null
        seconds=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.4f", b - a }')
        echo "$version,$scene,$seed,$seconds,$image" | tee -a "$csv"
      done
    done
  done
fi
/usr/bin/python3 bench/plot_sampler_comparison.py bench/results/sampler_comparison.csv bench/results/sampler_seeds.csv \
  bench/out/sampler "$previous" "${width}x${height}-${reference_spp}spp"
