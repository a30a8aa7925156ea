#!/usr/bin/env bash
# The denoised preview against the unbiased image on every scene in scenes/: relMSE and RMSE
# against a converged reference along a ladder of samples per pixel, the denoiser's CPU time,
# and its time at 1024×768. Writes bench/results/denoise.csv, bench/results/denoise_time.csv,
# bench/plots/denoise.svg, and PNGs of the 16 spp rung in bench/out/denoise/ to look at
# (three of them beside their references in bench/plots/denoise_16spp.png). The references,
# bench/out/denoise/SCENE/reference-128x96-4096spp.pfm and reference.png, are rendered by
# denoise_vs_error itself on its first run (seed 0x5EED) and kept: 4096 spp, so that the
# reference's own error is 1/256 of the unbiased image's at 16 spp and well below the denoised
# image's (a 1024 spp reference added 0.015 to every ratio). Each figure is the mean over eight
# seeds: one 16 spp render of a scene with fireflies can be off its expected relMSE by 1.5×.
# Run by hand (at 128×96, so that the references take minutes each on a busy 2-core machine):
#   bench/run_denoise.sh [max-spp]
set -euo pipefail
cd "$(dirname "$0")/.."
max_spp=${1:-256}
cmake -S . -B build -G Ninja >/dev/null && cmake --build build --target denoise_vs_error >/dev/null
out=bench/out/denoise
mkdir -p "$out" bench/results
csv=bench/results/denoise.csv
echo "scene,width,height,spp,render_cpu,rmse,relmse,rmse_denoised,relmse_denoised,denoise_cpu,denoise_wall" > "$csv"
for scene in cornell cornell_box caustic spheres mesh bunny_box sponza; do
  build/bench/denoise_vs_error "scenes/$scene.json" --out "$out/$scene" --width 128 --height 96 --reference-spp 4096 \
    --max-spp "$max_spp" --seeds 8 --threads 2 | tee -a "$csv"
done
# The denoiser's time at preview sizes: a film of 16 spp at 256×192 and 1024×768 (no reference).
time_csv=bench/results/denoise_time.csv
echo "scene,width,height,spp,render_cpu,rmse,relmse,rmse_denoised,relmse_denoised,denoise_cpu,denoise_wall" > "$time_csv"
for size in "256 192" "1024 768"; do
  set -- $size
  build/bench/denoise_vs_error scenes/cornell.json --out "$out/time-$1" --width "$1" --height "$2" \
    --reference-spp 4 --max-spp 16 --threads 2 | tee -a "$time_csv"
done
/usr/bin/python3 bench/plot_denoise.py "$csv"
