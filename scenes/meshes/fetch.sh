#!/usr/bin/env bash
# Puts the public meshes that scenes/*.json name, and that this repository does not carry, into
# scenes/meshes/ (see scenes/meshes/README.md for their sources and licences). Each is taken from
# a local mirror when there is one ($GLINT_MESHES, by default ../shared/scenes/meshes beside the
# clone), else downloaded from its public source, and kept only if its SHA-256 matches.
# `.ci/install-deps` runs it; running it again does nothing once the files are there.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
mirror=${GLINT_MESHES:-$here/../../../shared/scenes/meshes}

# name sha256 url [member of the zip at url]
meshes=(
  "cornell_box.obj 190c47edc9f01af3be0818386e4aca562497010bcf24aab571684b39e4a8397d
   https://raw.githubusercontent.com/wallisc/Real-time-Path-Tracer/f96467f75be5df12b96b6bf67b7c6a24bf23ea3e/CornellBox-Original.obj"
  "bunny.obj 1eb35d1e21ce99e5ce911353b6be278990713448dd9e8f5c9387f9de39b32205
   https://raw.githubusercontent.com/alecjacobson/common-3d-test-models/29339feae9a77dbd839d0a83f8349c2e7f978c8f/data/stanford-bunny.obj"
  "sponza_dabrovic.obj 5b4f8bc4f847aef7f0bd20bc3647f1d72843188c0a650d52ac8e0700c2e5f092
   https://raw.githubusercontent.com/YangYuchu/cg/c16837cf16cc4afaafa920c609cd0291044ffb0a/sponza.zip sponza.obj"
)

matches() { [ -f "$1" ] && [ "$(sha256sum "$1" | cut -d' ' -f1)" = "$2" ]; }

get() {  # name sha url [member]
  local target=$here/$1 tmp=$here/.$1.tmp
  matches "$target" "$2" && return 0
  if [ -f "$mirror/$1" ]; then
    cp "$mirror/$1" "$tmp"
  elif [ -n "${4:-}" ]; then
    curl -fsSL "$3" -o "$tmp.zip" && unzip -p "$tmp.zip" "$4" > "$tmp"; rm -f "$tmp.zip"
  else
    curl -fsSL "$3" -o "$tmp"
  fi
  if ! matches "$tmp" "$2"; then
    rm -f "$tmp"
    echo "fetch.sh: could not get $1 (from $mirror or $3)" >&2
    return 1
  fi
  mv "$tmp" "$target"
  echo "fetch.sh: scenes/meshes/$1"
}

status=0
for entry in "${meshes[@]}"; do
  # shellcheck disable=SC2086  # the entry is split into its fields on purpose
  get $entry || status=1
done
exit $status
