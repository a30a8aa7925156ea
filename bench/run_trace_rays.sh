#!/usr/bin/env bash
# glint trace-rays on every shared ray set: closest-hit and any-hit, 1 and 2 threads, median of
# 5 runs each; a markdown table on stdout. Run by hand:  bench/run_trace_rays.sh > bench/results/trace_rays.md
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja >/dev/null && cmake --build build --target glint >/dev/null
shared=../shared
echo "| ray set | triangles | build ms | bytes/triangle: nodes / with triangles | query | Mrays/s 1 thread | Mrays/s 2 threads | hits |"
echo "|---|---|---|---|---|---|---|---|"
for mesh in bunny sponza_dabrovic cornell_box; do
  for kind in primary diffuse; do
    for query in closest-hit any-hit; do
      flag=""; [ "$query" = any-hit ] && flag="--any-hit"
      one=$(build/server/glint trace-rays "$shared/scenes/meshes/$mesh.obj" "$shared/rays/${mesh}_$kind.rays" --threads 1 --repeat 5 $flag)
      two=$(build/server/glint trace-rays "$shared/scenes/meshes/$mesh.obj" "$shared/rays/${mesh}_$kind.rays" --threads 2 --repeat 5 $flag)
      tris=$(sed -n 's/^triangles \([0-9]*\).*/\1/p' <<< "$one")
      build=$(sed -n 's/.*build \([0-9.]*\) ms.*/\1/p' <<< "$one")
      bytes=$(sed -n 's/.* \([0-9.]*\) BVH node bytes\/triangle *\([0-9.]*\) with.*/\1 \/ \2/p' <<< "$one")
      m1=$(sed -n 's/.* \([0-9.]*\) Mrays\/s/\1/p' <<< "$one")
      m2=$(sed -n 's/.* \([0-9.]*\) Mrays\/s/\1/p' <<< "$two")
      hits=$(sed -n 's/.*hits \([0-9]*\) .*/\1/p' <<< "$one")
      echo "| ${mesh}_$kind | $tris | $build | $bytes | $query | $m1 | $m2 | $hits |"
    done
  done
done
