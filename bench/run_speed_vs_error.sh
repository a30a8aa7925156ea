#!/usr/bin/env bash
# Speed against error for every example scene: an SPP ladder per mode (glint, no-lt, no-nee,
# no-bvh, smallpt), RMSE against a reference glint renders itself (kept in bench/out/, not in git),
# then plots and tables into bench/results/ and bench/plots/. Run by hand on an idle machine:
#   bench/run_speed_vs_error.sh            (about 30 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja >/dev/null && cmake --build build --target speed_vs_error >/dev/null
csv=bench/results/speed_vs_error.csv
echo "scene,mode,spp,seconds,rmse,estimate" > "$csv"
run() {  # scene width height reference-spp max-spp
  build/bench/speed_vs_error "scenes/$1.json" --out "bench/out/$1" --width "$2" --height "$3" \
    --reference-spp "$4" --max-spp "$5" --threads 2 --max-seconds 60 | tee -a "$csv"
}
run cornell 256 192 4096 512
run mesh 256 192 2048 512
run caustic 256 192 8192 1024
run spheres 256 144 4096 512
# Debian's python3 has python3-matplotlib; a python3 earlier on PATH may not.
/usr/bin/python3 bench/plot_speed_vs_error.py "$csv"
