#!/usr/bin/env bash
# Adaptive sampling against plain sampling on every scene in scenes/, in CPU time (user + sys;
# the machine is shared), at 128×96: per scene a plain ladder (16 to 128 spp) and adaptive renders
# at each threshold (at most 256 spp a pixel), alternating per repeat; RMSEs against a reference
# of two plain 512-spp renders, its noise taken out (bench/adaptive_vs_plain.cpp). Writes bench/results/adaptive.csv, bench/plots/adaptive.svg and
# the table in bench/BENCHMARKS.md. Run by hand (about 15 minutes on 2 busy cores):
#   bench/run_adaptive.sh [thresholds] [repeats]
set -euo pipefail
cd "$(dirname "$0")/.."
thresholds=${1:-0.2,0.1}
repeats=${2:-2}
cmake --build build --target adaptive_vs_plain >/dev/null
csv=bench/results/adaptive.csv
echo "scene,mode,threshold,spp,repeat,cpu,rmse,rmse_pairs,mean_spp" > "$csv"
for scene in cornell spheres mesh caustic cornell_box bunny_box sponza; do
  build/bench/adaptive_vs_plain "scenes/$scene.json" --width 128 --height 96 --reference-spp 512 --max-spp 128 --adaptive-spp 256 \
    --thresholds "$thresholds" --repeats "$repeats" --threads 2 | tee -a "$csv"
done
/usr/bin/python3 bench/plot_adaptive.py "$csv"
