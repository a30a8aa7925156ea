#!/usr/bin/env bash
# Checks the include graph of core/ and server/ against the layer order below: every project
# include names its folder ("accel/bvh.h"), points to the same layer or one below, and no two
# modules (a header with its source) include each other, directly or round a longer loop.
#   tests/layers/check_layers.sh [ROOT]      prints the graph's summary; exits 1 on a violation
set -uo pipefail
root=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
# Bottom to top. File formats (io) sit below the renderer and know nothing of it; what combines
# formats with the renderer (scene loading, partial files, a film's EXR layers) is assembly's.
# The service sits on the whole library; the command line on the HTTP layer.
layers=(core/base core/shapes core/accel core/scene core/io core/render core/assembly core/denoise
        server/service server/http server/cli)

rank() {  # rank FOLDER: the layer's position, or nothing if FOLDER is not a layer
  local i
  for i in "${!layers[@]}"; do [ "${layers[$i]}" = "$1" ] && echo "$i" && return; done
}
failed=0
edges=$(mktemp)
trap 'rm -f "$edges"' EXIT
count=0
for i in "${!layers[@]}"; do
  dir=$root/${layers[$i]}
  [ -d "$dir" ] || { echo "missing layer folder ${layers[$i]}"; failed=1; continue; }
  for file in "$dir"/*.h "$dir"/*.cpp; do
    [ -e "$file" ] || continue
    from=${file#"$root"/}
    while IFS= read -r target; do
      count=$((count + 1))
      layer=${target%/*}
      case $target in
        */*) ;;
        *) echo "$from: #include \"$target\" names no folder"; failed=1; continue ;;
      esac
      for base in core server; do
        [ -e "$root/$base/$target" ] && layer=$base/$layer && break
      done
      to_rank=$(rank "$layer")
      if [ -z "$to_rank" ] || [ ! -e "$root/$layer/${target##*/}" ]; then
        echo "$from: #include \"$target\" is not in a layer"; failed=1; continue
      fi
      if [ "$to_rank" -gt "$i" ]; then
        echo "$from: #include \"$target\" goes up from ${layers[$i]} to $layer"; failed=1
      fi
      module=${from%.*}; to_module=$layer/${target##*/}; to_module=${to_module%.*}
      [ "$module" != "$to_module" ] && echo "$module $to_module" >> "$edges"
    done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$file")
  done
done
# tsort names the modules of any loop on stderr.
if ! loops=$(sort -u "$edges" | tsort 2>&1 >/dev/null) || [ -n "$loops" ]; then
  echo "include loop between modules:"; echo "$loops" | sed 's/^tsort: /  /'; failed=1
fi
# What a surface does with light is its BSDF's: outside the materials' own files (core/scene's
# material, bsdf, lambertian, mirror, glass and metallic_roughness) no code branches on a
# material type; it asks the BSDF's flags instead.
materials='core/scene/(material|bsdf|bsdf_flags|lambertian|mirror|glass|metallic_roughness)\.(h|cpp):'
branches=$(cd "$root" && grep -nE '(==|!=)[[:space:]]*MaterialType::|MaterialType::[a-z_]+[[:space:]]*(==|!=)|case[[:space:]]+MaterialType::' \
             -r core server --include='*.h' --include='*.cpp' | grep -vE "^($materials)" || true)
if [ -n "$branches" ]; then
  echo "branches on a material type outside the materials' files (ask the BSDF's flags):"
  echo "$branches" | sed 's/^/  /'; failed=1
fi
modules=$(awk '{print $1; print $2}' "$edges" | sort -u | wc -l)
echo "$count project includes in ${#layers[@]} layers, $(sort -u "$edges" | wc -l) module edges among $modules modules"
for l in "${layers[@]}"; do
  echo "  $l: $(ls "$root/$l" 2>/dev/null | grep -cE '\.(h|cpp)$') files"
done
if [ "$failed" = 0 ]; then echo "every include points down a layer; no loop"; fi
exit $failed
