#!/usr/bin/env bash
# Shows that a change moved code and nothing else: every scene in scenes/ renders to the same
# PNG and PFM bytes with this tree's glint and with REV's, at small sizes and fixed seeds, and
# `glint trace-rays` writes the same hit files on every shared ray set (closest and any hit).
#   bench/check_identical.sh REV        e.g. bench/check_identical.sh 3ab8039
# Prints one line per comparison and exits non-zero if any differs. OLD_GLINT and NEW_GLINT in the
# environment name binaries already built, for REV and for this tree, instead of building them;
# SHARED the folder of the shared meshes and ray sets (default: ../shared beside the tree).
set -euo pipefail
rev=${1:?usage: bench/check_identical.sh REV}
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SHARED:-$root/../shared}
[ -d "$shared/rays" ] || { echo "no ray sets in $shared/rays: set SHARED" >&2; exit 2; }
work=$(mktemp -d)
trap 'git -C "$root" worktree remove --force "$work/src" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT

build() {  # build SRC DIR: the glint binary of the tree at SRC into DIR
  cmake -S "$1" -B "$2" -G Ninja -DGLINT_BUILD_TESTS=OFF -DGLINT_BUILD_BENCH=OFF >/dev/null
  cmake --build "$2" --target glint >/dev/null
}
old=${OLD_GLINT:-}
new=${NEW_GLINT:-}
if [ -z "$old" ]; then
  git -C "$root" worktree add --detach "$work/src" "$rev" >/dev/null 2>&1
  build "$work/src" "$work/old" &
fi
[ -n "$new" ] || build "$root" "$work/new"
wait
old=${old:-$(find "$work/old" -name glint -type f -perm -u+x | head -1)}
new=${new:-$(find "$work/new" -name glint -type f -perm -u+x | head -1)}

failed=0
same() {  # same LABEL FILE_A FILE_B
  if cmp -s "$2" "$3"; then echo "identical  $1"; else echo "DIFFERENT  $1"; failed=1; fi
}
for scene in "$root"/scenes/*.json; do
  name=$(basename "$scene" .json)
  # A scene REV cannot load (it uses what this tree adds) has nothing to compare with.
  if ! "$old" render "$scene" --width 4 --height 4 --spp 1 --threads 1 -o "$work/probe.png" >/dev/null 2>&1; then
    echo "new        $name (REV cannot load it)"
    continue
  fi
  for args in "--width 64 --height 48 --spp 16 --seed 1" "--width 37 --height 23 --spp 8 --seed 7 --encoding srgb"; do
    for bin in old new; do
      "${!bin}" render "$scene" $args --threads 2 -o "$work/$name.$bin.png" --hdr "$work/$name.$bin.pfm" >/dev/null 2>&1
    done
    same "$name ($args) png" "$work/$name.old.png" "$work/$name.new.png"
    same "$name ($args) pfm" "$work/$name.old.pfm" "$work/$name.new.pfm"
  done
  for bin in old new; do  # a part of a split job: the partial file, fingerprint included
    "${!bin}" render "$scene" --width 40 --height 30 --spp 32 --samples 8:24 --seed 3 --threads 2 \
      -o "$work/$name.$bin.part.png" --partial "$work/$name.$bin.partial" >/dev/null 2>&1
  done
  same "$name (samples 8:24) partial" "$work/$name.old.partial" "$work/$name.new.partial"
done
for rays in "$shared"/rays/*.rays; do
  set_name=$(basename "$rays" .rays)
  mesh=$shared/scenes/meshes/${set_name%_*}.obj
  for flag in "" --any-hit; do
    for bin in old new; do
      "${!bin}" trace-rays "$mesh" "$rays" $flag --threads 2 -o "$work/$set_name.$bin.hits" >/dev/null
    done
    same "trace-rays $set_name ${flag:-closest-hit}" "$work/$set_name.old.hits" "$work/$set_name.new.hits"
  done
done
exit $failed
