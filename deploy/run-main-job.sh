#!/usr/bin/env bash
# The main job: installs what is missing, builds, generates a sample cloud (a tilted torus,
# 100,000 points, density varying 30:1), starts membraned on a free loopback port,
# reconstructs a closed mesh through it with the client, checks the mesh and stops the server
# (also when a step fails: trap on exit).
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${JOBS:-$(nproc)}"

deploy/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$JOBS" --target membrane membraned membrane-decode

out=build/sample
mkdir -p "$out"
build/client/membrane synth torus -o "$out/torus.ply" --points 100000 --density-ratio 30 --seed 1

# Port 0: the kernel picks a free port; membraned logs it in its server_started line.
server_log="$out/membraned.log"
build/server/membraned --listen=127.0.0.1:0 2>"$server_log" &
server_pid=$!
trap 'kill -TERM "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true' EXIT
port=""
for _ in $(seq 100); do
  port="$(sed -n 's/.*event=server_started.* port=\([0-9]*\).*/\1/p' "$server_log")"
  [ -n "$port" ] && break
  kill -0 "$server_pid" 2>/dev/null || { cat "$server_log" >&2; exit 1; }
  sleep 0.1
done
[ -n "$port" ] || { echo "main job: membraned did not start" >&2; cat "$server_log" >&2; exit 1; }
server="127.0.0.1:$port"
build/client/membrane health --server "$server"

build/client/membrane reconstruct "$out/torus.ply" -o "$out/torus-mesh.ply" --server "$server" \
  --stats-json "$out/torus-stats.json"
build/client/membrane check "$out/torus-mesh.ply"
echo "main job: mesh in $out/torus-mesh.ply, statistics in $out/torus-stats.json (via $server)"
