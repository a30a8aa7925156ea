#!/usr/bin/env bash
# docker/slurm/ on a real Slurm cluster of four nodes started here (cluster.sh): (a) a job split
# into four parts over the four nodes merges to the whole render's image, byte for byte; (b) a
# node killed while its part runs: Slurm requeues the part and the image is still identical;
# (c) a part that fails ends the job with a message naming the part, and nothing is left queued.
# Usage: slurm_test.sh GLINT_BINARY SOURCE_DIR   (as root, with Debian's slurmctld slurmd
# slurm-client munge installed)
set -uo pipefail
glint=$(realpath "$1")
source_dir=$(realpath "$2")
submit=$source_dir/docker/slurm/submit
work=$(mktemp -d /tmp/glint-slurm-test.XXXXXX)
chmod 755 "$work"  # munged runs as the munge user, in a folder under it
# shellcheck source=cluster.sh
source "$(dirname "$0")/cluster.sh"
trap 'cluster_stop "$work/cluster"; rm -rf "$work"' EXIT
# shellcheck source=../support/check.sh
source "$(dirname "$0")/../support/check.sh"
cluster_start "$work/cluster" || { echo "FAILED: the cluster did not start"; cat "$work"/cluster/*.log; exit 1; }
echo "cluster up: $(sinfo -h -o '%D nodes %T')"

# The Cornell box of spheres, small: each part takes a few seconds on one core.
size=(--width 64 --height 48)
"$glint" render "$source_dir/scenes/cornell.json" -o "$work/whole.png" --hdr "$work/whole.pfm" --spp 64 "${size[@]}" \
  > /dev/null 2>&1
nodes_of() { sed -n 's/^part [0-9]*: samples .* on \(node[0-9]*\),.*/\1/p' "$1"/part-*.log | sort -u | tr '\n' ' '; }

# (a) Four parts over the four nodes.
timeout 120 "$submit" "$source_dir/scenes/cornell.json" -o "$work/a.png" --parts 4 --spp 64 --glint "$glint" \
  --wait -- "${size[@]}" > "$work/a.out" 2>&1
check "(a) a job of four parts finishes" test $? -eq 0
check "(a) its parts ran on the four nodes" test "$(nodes_of "$work/a.parts")" = "node1 node2 node3 node4 "
check "(a) the merged PNG equals the whole render's" cmp -s "$work/a.png" "$work/whole.png"
check "(a) the merged PFM equals the whole render's" cmp -s "$work/a.pfm" "$work/whole.pfm"

# (b) Parts of a few seconds each (256 spp); the node running part 1 is killed while it renders;
# Slurm finds the node down (SlurmdTimeout) and requeues the part, which runs again elsewhere
# after cred_expire and continues from the checkpoint the first attempt left.
"$glint" render "$source_dir/scenes/cornell.json" -o "$work/whole-b.png" --hdr "$work/whole-b.pfm" --spp 1024 \
  "${size[@]}" > /dev/null 2>&1
"$submit" "$source_dir/scenes/cornell.json" -o "$work/b.png" --parts 4 --spp 1024 --glint "$glint" \
  --wait -- "${size[@]}" --checkpoint-interval 0.2 > "$work/b.out" 2>&1 &
submitter=$!
victim=""
for _ in $(seq 200); do
  victim=$(sed -n 's/^part 1: samples .* on \(node[0-9]*\), attempt 1,.*/\1/p' "$work/b.parts/part-1.log" 2> /dev/null)
  [ -n "$victim" ] && break
  sleep 0.1
done
check "(b) part 1 started" test -n "$victim"
for _ in $(seq 100); do [ -e "$work/b.parts/part-1.checkpoint" ] && break; sleep 0.05; done  # into its render
check "(b) part 1 is still running when its node is killed" test ! -e "$work/b.parts/part-1.partial"
[ -n "$victim" ] && cluster_kill_node "$work/cluster" "$victim"
( sleep 150; kill "$submitter" 2> /dev/null ) &
watchdog=$!
wait "$submitter"
check "(b) the job finishes after a node died under it" test $? -eq 0
kill "$watchdog" 2> /dev/null
check "(b) part 1 ran twice" grep -q "^part 1: samples .* attempt 2," "$work/b.parts/part-1.log"
check "(b) its second attempt continued from the first's checkpoint" \
  grep -q "part-1.checkpoint: continuing from sample [1-9]" "$work/b.parts/part-1.log"
check "(b) the merged PNG still equals the whole render's" cmp -s "$work/b.png" "$work/whole-b.png"
check "(b) the merged PFM still equals the whole render's" cmp -s "$work/b.pfm" "$work/whole-b.pfm"
[ -n "$victim" ] && slurmd -f "$SLURM_CONF" -N "$victim"  # back in service (ReturnToService=2)

# (c) Part 2 gets a scene that does not load (a glint that swaps in a broken copy for task 2).
sed 's/"radius": 1e5/"radius": -1/' "$source_dir/scenes/cornell.json" > "$work/broken.json"
cat > "$work/glint-part2-broken" <<WRAP
#!/usr/bin/env bash
if [ "\$SLURM_ARRAY_TASK_ID" = 2 ] && [ "\$1" = render ]; then set -- render "$work/broken.json" "\${@:3}"; fi
exec "$glint" "\$@"
WRAP
chmod +x "$work/glint-part2-broken"
timeout 120 "$submit" "$source_dir/scenes/cornell.json" -o "$work/c.png" --parts 4 --spp 64 \
  --glint "$work/glint-part2-broken" --wait -- "${size[@]}" > "$work/c.out" 2>&1
check "(c) a failed part fails the job (exit 1)" test $? -eq 1
check "(c) the message names the part and glint's error" \
  bash -c "grep -q '^part 2 (samples 32:48, on node[0-9]) failed with exit code 1:' '$work/c.out' && grep -q 'radius: must be > 0' '$work/c.out'"
check "(c) no image is written" test ! -e "$work/c.png"
for _ in $(seq 50); do [ -z "$(squeue -h)" ] && break; sleep 0.2; done
check "(c) nothing is left queued or running" test -z "$(squeue -h)"

if [ "$failures" -gt 0 ]; then
  for f in "$work"/*.out "$work"/*.parts/*.log; do echo "== $f"; cat "$f"; done
fi
check_summary slurm
