#!/usr/bin/env bash
# End-to-end checks of the glint command line: outputs, exit codes and error messages.
# Usage: cli_test.sh GLINT_BINARY SHARED_DIR SOURCE_DIR
set -uo pipefail
glint=$1
shared=$2
source=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=../../support/check.sh
source "$(dirname "$0")/../../support/check.sh"

cat > "$work/tiny.json" <<'JSON'
{"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
 "film": {"width": 8, "height": 6, "spp": 4},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "emission": 1}]}
JSON
"$glint" render "$work/tiny.json" -o "$work/out.png" --hdr "$work/out.pfm" --width 10 > "$work/stdout" 2> "$work/stderr"
check "render exits 0" test $? -eq 0
check "render writes a PNG" cmp -s -n 8 "$work/out.png" <(printf '\x89PNG\r\n\x1a\n')
check "render writes a 10x6 PFM" grep -qa "^10 6$" "$work/out.pfm"
check "render reports time, samples/s and error" grep -q "completed; 4 spp at 10x6 in .* samples/s, estimated RMSE .*, 0 samples dropped (rounds with a non-finite one)" "$work/stdout"
check "render prints progress lines off a terminal" grep -q "^progress 100%" "$work/stderr"
exr_magic() { cmp -s -n 4 "$1" <(printf '\x76\x2f\x31\x01'); }
"$glint" render "$work/tiny.json" --exr "$work/out.exr" > "$work/stdout" 2> /dev/null
check "render --exr alone exits 0" test $? -eq 0
check "render --exr writes an OpenEXR file" exr_magic "$work/out.exr"
check "render --exr names its file in the report" grep -q "^$work/out.exr: completed" "$work/stdout"

sed 's/"radius": 1/"radius": -1/' "$work/tiny.json" > "$work/bad.json"
"$glint" render "$work/bad.json" -o "$work/bad.png" 2> "$work/stderr"
check "a bad scene exits 1" test $? -eq 1
check "a bad scene names the JSON path" grep -q "bad.json: objects\[0\].radius: must be > 0" "$work/stderr"
check "a bad scene writes no image" test ! -e "$work/bad.png"

# Every numeric option has a range (server/cli/option_range.h): a value outside it, or no number,
# is one line naming the option and the range, with CLI11's exit code for a value that fails its
# check (105); never an abort (134: `--threads 100000` once failed to start its threads).
refused() {  # the line expected, then glint's arguments
  local expected=$1 status
  shift
  timeout 20 "$glint" "$@" > /dev/null 2> "$work/stderr"
  status=$?
  check "glint $* exits 105 (got $status)" test "$status" -eq 105
  check "glint $* says: $expected" grep -qxF -- "$expected" "$work/stderr"
}
threads="--threads: must be an integer in [0, 1024]"
refused "$threads" render "$work/tiny.json" -o "$work/x.png" --threads 100000
refused "$threads" serve --threads 100000
refused "$threads" trace-rays mesh.obj rays.rays --threads -1
refused "--spp: must be an integer in [1, 1048576]" render "$work/tiny.json" -o "$work/x.png" --spp 0
refused "--width: must be an integer in [1, 16384]" render "$work/tiny.json" -o "$work/x.png" --width 1e3
refused "--seed: must be an integer in [0, 9223372036854775807]" render "$work/tiny.json" -o "$work/x.png" --seed 18446744073709551615
refused "--checkpoint-interval: must be a number in [0, 3600]" render "$work/tiny.json" -o "$work/x.png" --checkpoint-interval nan
refused "--port: must be an integer in [1, 65535]" serve --port 70000
# The stop conditions are the film's: one check (check_settings) for a scene file, a request and
# these options, so the message is the scene's.
"$glint" render "$work/tiny.json" -o "$work/x.png" --time-limit inf 2> "$work/stderr"
check "--time-limit inf exits 1" test $? -eq 1
check "--time-limit inf is refused as film.time_limit" \
  grep -qF "tiny.json: film.time_limit: must be a finite number >= 0 (0: off)" "$work/stderr"
"$glint" render "$work/tiny.json" -o "$work/x.png" --region 2,0,9,6 2> "$work/stderr"
check "--region beyond the image exits 1" test $? -eq 1
check "--region beyond the image names the bounds" \
  grep -qF "film.region: [2, 0, 9, 6] must satisfy 0 <= x0 < x1 <= width (8) and 0 <= y0 < y1 <= height (6)" "$work/stderr"
"$glint" render "$work/tiny.json" -o "$work/whole.png" --hdr "$work/whole.pfm" > /dev/null 2>&1
"$glint" render "$work/tiny.json" -o "$work/window.png" --hdr "$work/window.pfm" --region 2,1,7,5 > /dev/null 2>&1
check "--region writes the window: a 5x4 PFM" grep -qa "^5 4$" "$work/window.pfm"
refused "--max-jobs: must be an integer in [1, 256]" serve --max-jobs 100000
refused "--max-queued: must be an integer in [1, 1024]" serve --max-queued 0
refused "--max-denoising: must be an integer in [1, 64]" serve --max-denoising 0
refused "--store-limit: must be an integer in [1, 9223372036854775807]" serve --store-limit -1
refused "--farm-parts: must be an integer in [1, 10000]" serve --farm-parts 0
refused "--repeat: must be an integer in [1, 1000]" trace-rays mesh.obj rays.rays --repeat 0
# A thread the system refuses within the range (here: no address space left for its stack) ends
# the command with one line and exit 1 once the threads started are stopped, never an abort. Not
# under AddressSanitizer, whose shadow memory needs terabytes of address space to start at all.
# (ldd to a file first: under pipefail, `ldd | grep -q` fails whenever grep quits before ldd
# has written everything and ldd dies of SIGPIPE.)
ldd "$glint" > "$work/ldd"
if ! grep -q libasan "$work/ldd"; then
  (ulimit -v 400000; "$glint" render "$work/tiny.json" -o "$work/x.png" --threads 1024) > /dev/null 2> "$work/stderr"
  check "a render whose threads the system refuses exits 1" test $? -eq 1
  check "and says which thread failed" grep -q "^glint: cannot start render thread [0-9]* of 1024: " "$work/stderr"
fi
"$glint" render --help > "$work/stdout"
check "--help shows an option's range" grep -q -- "--threads UINT:\[0, 1024\]" "$work/stdout"
"$glint" render "$work/missing.json" -o "$work/x.png" 2> "$work/stderr"
check "a missing scene file exits 1" grep -q "cannot open" "$work/stderr"

# Batch mode: several files and a folder; a bad scene fails alone.
mkdir -p "$work/batch"
cp "$work/tiny.json" "$work/batch/a.json"
sed 's/"spp": 4/"spp": 8/' "$work/tiny.json" > "$work/batch/b.json"
"$glint" render "$work/batch" "$work/bad.json" -o "$work/out" --hdr "$work/hdr" --exr "$work/exr" > "$work/stdout" 2> "$work/stderr"
check "a batch with a bad scene exits 1" test $? -eq 1
check "a batch renders the good scenes" test -s "$work/out/a.png" -a -s "$work/out/b.png" -a -s "$work/hdr/b.pfm"
check "a batch writes an EXR per scene into the --exr folder" exr_magic "$work/exr/a.exr"
check "a batch ends with a summary" grep -q "^3 scenes: 2 rendered, 1 failed$" "$work/stdout"
check "a batch prints one line per scene" test "$(grep -c "completed;" "$work/stdout")" -eq 2

# --denoise: OUT.denoised.png beside OUT, which stays the unbiased image; in a batch, beside each.
small=(render "$source/scenes/cornell.json" --width 32 --height 24 --spp 16 --threads 1)
"$glint" "${small[@]}" -o "$work/plain.png" > /dev/null 2>&1
"$glint" "${small[@]}" -o "$work/dn.png" --denoise > /dev/null 2>&1
check "--denoise writes OUT.denoised.png" cmp -s -n 8 "$work/dn.denoised.png" <(printf '\x89PNG\r\n\x1a\n')
check "--denoise leaves OUT the unbiased image" cmp -s "$work/dn.png" "$work/plain.png"
check "the denoised image differs from it" test -n "$(cmp "$work/dn.png" "$work/dn.denoised.png")"
"$glint" render "$work/batch" -o "$work/dnbatch" --denoise > /dev/null 2>&1
check "--denoise in a batch writes one beside each PNG" test -s "$work/dnbatch/a.denoised.png" -a -s "$work/dnbatch/b.denoised.png"
"$glint" render "$work/tiny.json" --partial "$work/p" --denoise 2> "$work/stderr"
check "--denoise without -o exits 2" test $? -eq 2
check "and says why" grep -q "^glint: --denoise writes OUT.denoised.png beside the PNG: give -o$" "$work/stderr"

# One job split over three processes running at once, merged: the whole render's image.
ranges=$(for i in 0 1 2; do "$source/docker/sample-range" $i 3 40; done | tr '\n' ' ')
check "sample-range tiles 40 spp in 3 parts of whole rounds" test "$ranges" = "0:12 12:24 24:40 "
for r in $ranges; do
  "$glint" render "$work/tiny.json" --samples "$r" --partial "$work/part-$r" --spp 999 2>/dev/null >/dev/null &
done
wait
"$glint" render "$work/tiny.json" -o "$work/whole.png" --hdr "$work/whole.pfm" --spp 40 2>/dev/null >/dev/null
"$glint" merge "$work/merged.png" --hdr "$work/merged.pfm" "$work"/part-* > "$work/stdout"
check "merge reports the samples it joined" grep -q "3 parts, samples \[0, 40)" "$work/stdout"
check "the merged PNG equals the whole render's" cmp -s "$work/merged.png" "$work/whole.png"
check "the merged PFM equals the whole render's" cmp -s "$work/merged.pfm" "$work/whole.pfm"
"$glint" merge "$work/gap.png" "$work/part-0:12" "$work/part-24:40" 2> "$work/stderr"
check "merge refuses a gap" grep -q "samples \[12, 24) are missing" "$work/stderr"
"$glint" merge "$work/merged.png" --exr "$work/merged.exr" "$work"/part-* > /dev/null
check "merge --exr writes an OpenEXR file" exr_magic "$work/merged.exr"
"$glint" render "$work/tiny.json" --samples 12:24 --aovs --partial "$work/aovs-12:24" > /dev/null 2>&1
"$glint" merge "$work/mixed.png" "$work/part-0:12" "$work/aovs-12:24" "$work/part-24:40" 2> "$work/stderr"
check "merge refuses a part with AOVs among parts without" grep -q "part \[12, 24) is from another scene or settings" "$work/stderr"
for parts in 1 2 3 5 7 10; do
  covered=0 ok=1
  for i in $(seq 0 $((parts - 1))); do
    r=$("$source/docker/sample-range" "$i" "$parts" 37)
    [ "${r%%:*}" -eq "$covered" ] || ok=0
    covered=${r##*:}
  done
  check "sample-range: $parts parts tile 37 spp (rounded to 40) without gaps" test "$ok" -eq 1 -a "$covered" -eq 40
done

if [ -f "$shared/rays/cornell_box_primary.rays" ]; then
  "$glint" trace-rays "$shared/scenes/meshes/cornell_box.obj" "$shared/rays/cornell_box_primary.rays" \
    -o "$work/hits.hits" --repeat 1 > "$work/stdout"
  check "trace-rays finds the documented ~90% hits (58,716 of 65,536)" grep -q "hits 58716 " "$work/stdout"
  check "trace-rays writes 16 + 8·N bytes" test "$(stat -c %s "$work/hits.hits")" -eq $((16 + 8 * 65536))
fi

# --checkpoint: a render stopped part-way continues from its last checkpoint to the bytes of an
# uninterrupted one, and a completed render removes the file.
cornell=(render "$source/scenes/cornell.json" --width 64 --height 48 --samples 0:320 --threads 1)
"$glint" "${cornell[@]}" --partial "$work/straight.partial" > /dev/null 2>&1
"$glint" "${cornell[@]}" --partial "$work/stopped.partial" --checkpoint "$work/ck" --checkpoint-interval 0 \
  > /dev/null 2>&1 &
pid=$!
for _ in $(seq 400); do [ -e "$work/ck" ] && break; sleep 0.05; done
kill -INT "$pid"
wait "$pid"
check "a render stopped part-way exits 130" test $? -eq 130
check "and keeps its checkpoint" test -s "$work/ck"
"$glint" "${cornell[@]}" --partial "$work/continued.partial" --checkpoint "$work/ck" > "$work/stdout" 2> /dev/null
check "a render finding a checkpoint continues from it" grep -q "ck: continuing from sample [1-9]" "$work/stdout"
check "the continued render's partial equals the uninterrupted one's" cmp -s "$work/continued.partial" "$work/straight.partial"
check "a completed render removes its checkpoint" test ! -e "$work/ck"
"$glint" "${cornell[@]}" --partial "$work/x.partial" --checkpoint "$work/continued.partial" --seed 9 > /dev/null 2> "$work/stderr"
check "a checkpoint of other settings is refused, naming it" \
  grep -q "continued.partial cannot be continued: it is from another scene or settings" "$work/stderr"
"$glint" "${cornell[@]}" --partial "$work/x.partial" --checkpoint "$work/continued.partial" --aovs > /dev/null 2> "$work/stderr"
check "a checkpoint without AOVs does not continue a render with them" \
  grep -q "continued.partial cannot be continued: it is from another scene or settings" "$work/stderr"

# glint asks glibc for transparent huge pages by running itself again with GLIBC_TUNABLES set
# (cli/huge_pages.h), unless the user set that variable. A server stays up long enough to look at
# the environment it runs with.
environment_of_server() {  # GLIBC_TUNABLES for the server, or unset; prints its environment
  local port pid environment=""
  port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  env "$@" "$glint" serve --port "$port" --threads 1 > /dev/null 2>&1 &
  pid=$!
  for _ in $(seq 50); do  # until it listens: the re-execution happens before that
    python3 -c "import socket, sys; socket.create_connection(('127.0.0.1', $port), 0.2)" 2> /dev/null && break
    sleep 0.1
  done
  environment=$(tr '\0' '\n' < "/proc/$pid/environ")
  kill "$pid"; wait "$pid" 2> /dev/null
  printf '%s\n' "$environment"
}
check "glint runs with glibc's huge pages" bash -c "grep -qx 'GLIBC_TUNABLES=glibc.malloc.hugetlb=1' <<< '$(environment_of_server -u GLIBC_TUNABLES)'"
check "a GLIBC_TUNABLES the user set is left alone" bash -c "grep -qx 'GLIBC_TUNABLES=glibc.malloc.check=0' <<< '$(environment_of_server GLIBC_TUNABLES=glibc.malloc.check=0)'"

check_summary cli
