#!/usr/bin/env bash
# Builds glint's image with podman (no Docker engine or registry needed) and checks it: renders
# a scene through a bind mount as the image's non-root user, splits a job over two containers
# and merges it, and answers /health from `serve`, which beyond loopback demands a bearer token
# for job routes and refuses to start without one. Run as root from anywhere; idempotent (the
# base image and build cache stay in podman's store). First run ~3 minutes on 2 cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=$root/.ci-container
image=localhost/glint:test
base=localhost/debian:bookworm-slim  # what `FROM debian:bookworm-slim` resolves to
mkdir -p "$work"
step() { echo "[test-image] $*" >&2; }

need=()
for p in podman runc debootstrap curl python3; do command -v "$p" >/dev/null || need+=("$p"); done
if ((${#need[@]})); then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=600 "${need[@]}" >/dev/null
fi

# This host's cgroups need runc (crun refuses them), and podman may not raise ulimits beyond its own.
hn=$(ulimit -Hn); hu=$(ulimit -Hu)
[[ $hn == unlimited || $hn -gt 1048576 ]] && hn=1048576
[[ $hu == unlimited || $hu -gt 32768 ]] && hu=32768
export CONTAINERS_CONF=$work/containers.conf
cat > "$CONTAINERS_CONF" <<CONF
[containers]
default_ulimits = ["nofile=$hn:$hn", "nproc=$hu:$hu"]
[engine]
runtime = "runc"
cgroup_manager = "cgroupfs"
CONF

if ! podman image exists "$base"; then
  mirror=${DEBIAN_MIRROR:-$( { cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list \
      /etc/apt/sources.list.d/*.sources 2>/dev/null || true; } | grep -v '^[[:space:]]*#' \
      | grep -oE 'https?://[^ ]+/debian/?( |$)' | sed -n 1p | tr -d ' ')}
  [[ -n $mirror ]] || { echo "no Debian mirror found; set DEBIAN_MIRROR" >&2; exit 1; }
  step "debootstrap bookworm from $mirror"
  rm -rf "$work/rootfs"
  debootstrap --variant=minbase bookworm "$work/rootfs" "$mirror" >/dev/null
  rm -rf "$work/rootfs"/var/cache/apt/archives/*.deb "$work/rootfs"/var/lib/apt/lists/*
  tar -C "$work/rootfs" -c . | podman import - "$base" >/dev/null
  rm -rf "$work/rootfs"
fi

step "podman build"
podman build -q -f "$root/docker/Dockerfile" -t "$image" "$root" >/dev/null
podman image inspect "$image" --format 'image size: {{.Size}} bytes' >&2

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
chmod a+rwx "$out"
cat > "$out/scene.json" <<'JSON'
{"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
 "film": {"width": 32, "height": 24, "spp": 16},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "emission": 1}]}
JSON
failures=0 passes=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok: $what"; passes=$((passes + 1)); else echo "FAILED: $what"; failures=$((failures + 1)); fi
}

podman run --rm -v "$out:/work" "$image" render /work/scene.json -o /work/out.png >/dev/null 2>&1
check "the image renders a bind-mounted scene" test -s "$out/out.png"
check "as the non-root user glint (uid 10001)" test "$(stat -c %u "$out/out.png")" -eq 10001
for i in 0 1; do
  range=$(podman run --rm --entrypoint glint-sample-range "$image" $i 2 16)
  podman run --rm -v "$out:/work" "$image" render /work/scene.json --samples "$range" --partial "/work/part$i" >/dev/null 2>&1
done
podman run --rm -v "$out:/work" "$image" merge /work/merged.png /work/part0 /work/part1 >/dev/null 2>&1
check "a job split over two containers merges into the whole render" cmp -s "$out/merged.png" "$out/out.png"

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
# Inside the image serve listens on 0.0.0.0 (GLINT_HOST), so it must refuse to start without a token.
refused=0
refusal=$(timeout 30 podman run --rm --network=host "$image" serve --port "$port" 2>&1) || refused=$?
check "serve refuses to listen beyond loopback without a token" test "$refused" -eq 1
check "and says why" grep -q "without a token" <<< "$refusal"
token=$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
container=$(podman run -d --rm --network=host -e GLINT_TOKEN="$token" "$image" serve --port "$port")
ok=1
for _ in $(seq 50); do curl -fs "127.0.0.1:$port/health" >/dev/null && { ok=0; break; }; sleep 0.2; done
check "serve answers /health from inside the container" test $ok -eq 0
check "the image serves the page" bash -c "curl -fs 127.0.0.1:$port/ | grep -q '<title>glint</title>'"
check "job routes need the token" test "$(curl -s -o /dev/null -w '%{http_code}' "127.0.0.1:$port/jobs")" = 401
check "and answer with it" test "$(curl -s -o /dev/null -w '%{http_code}' -H "Authorization: Bearer $token" "127.0.0.1:$port/jobs")" = 200
podman stop -t 10 "$container" >/dev/null
echo "image: $passes passed, $failures failed"
exit $((failures > 0))
