#!/usr/bin/env bash
# The container image, tested for real (run by deploy/run-tests.sh after the Release build):
#  1. a Debian bookworm base image made here with debootstrap and `podman import` (no
#     registry is reachable from CI);
#  2. deploy/Dockerfile built on it with podman;
#  3. the image run as Kubernetes runs it (deploy/k8s/statefulset.yaml): read-only root,
#     its own non-root user, no capabilities, no privilege escalation, a volume for
#     --store-dir, a token file mounted read-only; its HEALTHCHECK run;
#  4. a cloud reconstructed through it by the host's client (BUILD_DIR/client/membrane);
#  5. the container replaced by a new one on the same volume, and the job fetched again:
#     the same mesh, byte for byte;
#  6. the balancer's image (deploy/nginx/Dockerfile) run as deploy/k8s/balancer.yaml runs it:
#     read-only but for its two emptyDirs, as its own user; it answers gRPC calls and quits
#     on the manifest's preStop command.
# Usage: deploy/test-container.sh [BUILD_DIR]   (default: build)
#
# Cache: podman keeps its images in a storage of this test's own, under
# $MEMBRANE_CONTAINER_CACHE (default /var/cache/membrane-container, outside any clone): the base
# image (tagged by a key of how it is made) and the Dockerfile's stages, tagged so that the
# next run finds their layers (the packages' layer is keyed by the base and
# deploy/install-deps.sh alone). The compiler cache of the image build is a build cache mount
# of podman's (deploy/Dockerfile), kept there too (podman's TMPDIR). Removing the directory
# makes the next run cold: measured on a loaded 2-core machine, debootstrap 6 min, packages
# 3 min, compiling 10 min of CPU. The compile is skipped after deploy/run-tests.sh's Release
# build, which leaves its objects in BUILD_DIR/ccache-store: mounted read-only into the
# image's build as ccache's second store, with that build's -Werror, so that the same command
# lines find them there.
#
# Skips (exit 0, one line saying why) only where no container can run: not Linux, not root
# (debootstrap and this rootful podman need root: run it with sudo), or a kernel that
# refuses the namespaces of a container (this machine is itself an unprivileged container).
# Anything else that goes wrong fails, with the step and its log.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
client="$(pwd)/$build_dir/client/membrane"

say() { echo "test-container: $*"; }
skip() { say "SKIPPED: $*"; exit 0; }
fail() { say "FAILED: $*" >&2; exit 1; }
step_start=$SECONDS
step_done() { say "$1 ($((SECONDS - step_start)) s)"; step_start=$SECONDS; }

[ "$(uname -s)" = Linux ] || skip "containers need Linux (this is $(uname -s))"
[ "$(id -u)" -eq 0 ] || skip "needs root: debootstrap and rootful podman (run it with sudo)"
unshare --mount --pid --net --uts --ipc --fork true 2>/dev/null ||
  skip "the kernel refuses the namespaces a container needs (unshare --mount --pid --net" \
       "--uts --ipc failed: this machine is itself an unprivileged container)"
for tool in podman runc debootstrap; do
  command -v "$tool" >/dev/null || fail "$tool is missing (deploy/install-deps.sh container installs it)"
done
[ -x "$client" ] || fail "no client at $client: build it first (cmake --build $build_dir --target membrane)"

cache="${MEMBRANE_CONTAINER_CACHE:-/var/cache/membrane-container}"
mkdir -p "$cache"
# TMPDIR: where buildah keeps the build cache mounts (deploy/Dockerfile's ccache).
pod() {
  TMPDIR="$cache/tmp" podman --root "$cache/storage" --runroot "$cache/run" \
    --tmpdir "$cache/tmp" --runtime runc "$@"
}
# One run at a time per cache: runs share its storage and prune it.
exec 9>"$cache/lock"
flock 9
# What a run that was killed left behind (its containers, their volumes).
pod rm -a -f >/dev/null 2>&1 || true
pod volume prune -f >/dev/null 2>&1 || true

work="$(mktemp -d /var/tmp/membrane-container-test.XXXXXX)"
tag="$$"
# Kept after the run: the next run's build finds every layer of an unchanged source tree.
image="localhost/membrane:test"
balancer_image="localhost/membrane-balancer:test"
volume="membrane-jobs-$tag"
containers=()

# runc, not crun: crun cannot set RLIMIT_NOFILE on hosts whose hard limit is below podman's
# default, nor run on hybrid cgroup hierarchies. Limits are explicit for the same reason: this
# user may not raise them (no CAP_SYS_RESOURCE), and podman's defaults (1048576 files, 4194304
# processes) are above them. membraned needs a descriptor and a thread per open call
# (--max-calls, default 1000).
nofile="$(ulimit -Hn)"
[ "$nofile" = unlimited ] || [ "$nofile" -gt 65536 ] && nofile=65536
limits=(--ulimit "nofile=$nofile:$nofile" --ulimit "nproc=4096:4096")

cleanup() {
  local status=$?
  set +e
  if [ "$status" -ne 0 ]; then
    for c in "${containers[@]}"; do
      say "log of container $c:" >&2
      pod logs "$c" 2>&1 | tail -n 40 >&2
    done
  fi
  for c in "${containers[@]}"; do pod rm -f -t 5 "$c" >/dev/null 2>&1; done
  pod volume rm -f "$volume" >/dev/null 2>&1
  # The build stage (sources and objects) and the images the tags above moved from are left
  # untagged: pruned, so that the storage keeps only the tagged images and their layers.
  pod image prune -f >/dev/null 2>&1
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT

# Runs a step's command with its output in $work/NAME.log, shown only when it fails.
logged() {
  local name="$1"
  shift
  if ! "$@" >"$work/$name.log" 2>&1; then
    tail -n 60 "$work/$name.log" >&2
    fail "$name: $* failed (last lines above)"
  fi
}

# The Debian mirror this machine's apt uses (the only package source reachable from CI).
debian_mirror() {
  local uri
  uri="$(sed -n 's/^URIs:[[:space:]]*\([^[:space:]]*\/debian\/\{0,1\}\)$/\1/p' \
           /etc/apt/sources.list.d/*.sources 2>/dev/null | head -n 1)"
  [ -n "$uri" ] || uri="$(sed -n 's/^deb[[:space:]]\+\([^[:space:]]*\/debian\/\{0,1\}\)[[:space:]].*/\1/p' \
                            /etc/apt/sources.list 2>/dev/null | head -n 1)"
  echo "${MEMBRANE_DEBIAN_MIRROR:-${uri:-http://deb.debian.org/debian}}"
}

# --- 1. The base image --------------------------------------------------------------------
mirror="$(debian_mirror)"
security="${mirror%/debian*}/debian-security"
recipe="debootstrap --variant=minbase bookworm $mirror; updates; $security; recipe 1"
base="localhost/membrane-base:bookworm-$(printf '%s' "$recipe" | sha256sum | cut -c1-12)"
if pod image exists "$base"; then
  step_done "base image $base: cached"
else
  rootfs="$work/rootfs"
  logged debootstrap debootstrap --variant=minbase bookworm "$rootfs" "$mirror"
  rm -f "$rootfs/etc/apt/sources.list"
  cat >"$rootfs/etc/apt/sources.list.d/debian.sources" <<EOF
Types: deb
URIs: $mirror
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb
URIs: $security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  rm -rf "$rootfs"/var/cache/apt/archives/*.deb "$rootfs"/var/lib/apt/lists/*
  import_rootfs() { tar -C "$rootfs" -c . | pod import --change 'CMD ["/bin/bash"]' - "$base"; }
  logged import import_rootfs
  rm -rf "$rootfs"
  step_done "base image $base: made with debootstrap from $mirror"
fi

# --- 2. The image -------------------------------------------------------------------------
# The stages are built and tagged one by one: tagged, they and their layers survive the prune
# at the end, and each build finds them in podman's layer cache. A source tree the image does
# not see change (.dockerignore: tests, docs) compiles nothing.
# The Release build's objects, if it left them (else an empty directory stands in, so that the
# build's arguments, and with them its cached layers, stay the same).
store="$(pwd)/$build_dir/ccache-store"
if [ ! -d "$store" ]; then
  store="$work/no-store"
  mkdir "$store"
fi
build=(build --runtime runc "${limits[@]}" --format docker --pull=never --layers
       --build-arg "BASE=$base" --volume "$store:/ccache-store:ro"
       --build-arg "CCACHE_SECONDARY_STORAGE=file:///ccache-store|read-only"
       --build-arg MEMBRANE_WERROR=ON -f deploy/Dockerfile)
logged build-deps pod "${build[@]}" --target build-deps -t localhost/membrane-build-deps:cache .
step_done "build stage's packages (deploy/install-deps.sh build)"
logged runtime pod "${build[@]}" --target runtime -t localhost/membrane-runtime:cache .
step_done "runtime stage's packages"
logged build pod "${build[@]}" --target build -t localhost/membrane-build:cache .
logged image pod "${build[@]}" -t "$image" .
# ccache --show-stats: the first Hits line counts all, the one under "Remote storage:" those
# found in the Release build's store.
hits="$(grep -o 'Hits: *[0-9]* */ *[0-9]*' "$work/build.log" | head -n 1 | tr -s ' ' |
        sed 's/^Hits: //' || true)"
stored="$(sed -n '/Remote storage:/,$s/.*Hits: *\([0-9]*\) .*/\1/p' "$work/build.log" |
          head -n 1 || true)"
[ -n "$hits" ] && compiled="compiler cache hits: $hits, ${stored:-0} from $store" ||
  compiled="every layer cached"
step_done "image $image built ($compiled)"

user="$(pod image inspect --format '{{.Config.User}}' "$image")"
case "$user" in
  0 | 0:* | root | root:* | "") fail "the image runs as '$user', not as a user of its own" ;;
esac

# --- 3. Run it as the StatefulSet does ----------------------------------------------------
token="$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')"
mkdir -p "$work/token"
printf '%s\n' "$token" >"$work/token/token"
chmod 0755 "$work/token"
chmod 0644 "$work/token/token"
pod volume create "$volume" >/dev/null

# Starts a container of the image on the jobs volume and sets $port to the host port of its
# gRPC listener, once membraned logged server_started.
start_server() {
  local name="membrane-test-$tag-$1"
  # --read-only-tmpfs=false: no writable /tmp either, as under readOnlyRootFilesystem.
  # --health-interval=disable: no timer (podman's need systemd; its complaints go to the
  # step's log); the check is run once below.
  logged "run-$1" pod run -d --name "$name" "${limits[@]}" \
    --read-only --read-only-tmpfs=false --cap-drop=ALL --security-opt=no-new-privileges \
    -v "$volume:/var/lib/membrane" -v "$work/token:/etc/membrane/token:ro" \
    -p 127.0.0.1::50051 --health-interval=disable \
    "$image" --replica=membraned-0 --store-dir=/var/lib/membrane/jobs --workers=1 \
    --job-threads=1 --grace-seconds=10 --token-file=/etc/membrane/token/token
  containers+=("$name")
  # Waits on the log line itself (the log ends, and grep with it, if membraned exits);
  # `timeout` bounds a server that neither starts nor exits.
  timeout 60 grep -q -m 1 'event=server_started' < <(pod logs -f "$name" 2>&1) ||
    fail "membraned in $name did not log server_started within 60 s"
  port="$(pod port "$name" 50051/tcp | sed -n 's/^127\.0\.0\.1:\([0-9]*\)$/\1/p')"
  [ -n "$port" ] || fail "no host port for $name's 50051"
  server="$name"
}

start_server 1
step_done "container $server started (read-only, no capabilities, port $port)"
uid="$(pod exec "$server" sh -c 'sed -n "s/^Uid:[[:space:]]*\([0-9]*\).*/\1/p" /proc/1/status')"
[ "$uid" != 0 ] && [ -n "$uid" ] || fail "membraned runs as uid '$uid' in the container"
if pod exec "$server" sh -c 'echo x >/usr/local/bin/written 2>/dev/null || echo x >/tmp/written' \
     2>/dev/null; then
  fail "the container's root filesystem is writable"
fi
logged healthcheck pod healthcheck run "$server"
say "membraned runs as uid $uid, cannot write its root filesystem; HEALTHCHECK passes"

# --- 4. Reconstruct through it from the host --------------------------------------------
"$client" synth torus -o "$work/torus.ply" --points 20000 --seed 1 >/dev/null
address="127.0.0.1:$port"
logged reconstruct "$client" reconstruct "$work/torus.ply" -o "$work/first.drc" \
  --server "$address" --token-file "$work/token/token" --timeout 120
logged check "$client" check "$work/first.drc"
job="$("$client" jobs list --server "$address" --token-file "$work/token/token" |
       awk '$2 == "SUCCEEDED" {print $1}')"
[ "$(printf '%s\n' "$job" | grep -c .)" = 1 ] || fail "expected one SUCCEEDED job, listed: '$job'"
step_done "job $job reconstructed through the container ($(wc -c <"$work/first.drc") bytes)"

# --- 5. A new container on the same volume serves it again ------------------------------
logged stop pod stop -t 20 "$server"
pod logs "$server" 2>&1 | grep -q 'event=server_stopped' ||
  fail "membraned in $server did not stop gracefully on SIGTERM"
start_server 2
logged watch "$client" jobs watch "$job" -o "$work/again.drc" --server "127.0.0.1:$port" \
  --token-file "$work/token/token" --timeout 60
cmp "$work/first.drc" "$work/again.drc" ||
  fail "the mesh fetched after the restart differs from the first"
step_done "container $server on the same volume served job $job again: same mesh bytes"

# --- 6. The balancer's image, as deploy/k8s/balancer.yaml runs it ------------------------
logged balancer-build pod build --runtime runc "${limits[@]}" --format docker --pull=never \
  --layers --build-arg "BASE=$base" -f deploy/nginx/Dockerfile -t "$balancer_image" .
balancer="membrane-test-$tag-balancer"
# Writable: only the manifest's two emptyDirs (`U`: the user's, as fsGroup makes them).
# The cluster's DNS (nginx resolves its resolver's name at start) is this machine's resolver,
# which knows no cluster names: every call is then one nginx cannot place, which it must
# answer with a gRPC status of its own. A resolver on loopback is not reachable from the
# container: nginx then gives up on the name after its resolver_timeout (30 s).
dns="$(sed -n 's/^nameserver[[:space:]]\+\([0-9.]*\)[[:space:]]*$/\1/p' /etc/resolv.conf |
       grep -v '^127\.' | head -n 1 || true)"
logged run-balancer pod run -d --name "$balancer" "${limits[@]}" \
  --read-only --read-only-tmpfs=false --cap-drop=ALL --security-opt=no-new-privileges \
  --tmpfs /tmp:mode=1777 --tmpfs /var/lib/nginx:U \
  --add-host "kube-dns.kube-system.svc.cluster.local:${dns:-127.0.0.1}" -p 127.0.0.1::50051 \
  --entrypoint '["nginx", "-g", "daemon off; error_log stderr notice;"]' \
  "$balancer_image"
containers+=("$balancer")
# The image's command with one more log, at notice level: "start worker processes" comes
# once nginx listens, and is the event waited for.
timeout 60 grep -q -m 1 'start worker process' < <(pod logs -f "$balancer" 2>&1) ||
  fail "nginx in $balancer did not start its workers within 60 s"
balancer_port="$(pod port "$balancer" 50051/tcp | sed -n 's/^127\.0\.0\.1:\([0-9]*\)$/\1/p')"
[ -n "$balancer_port" ] || fail "no host port for $balancer's 50051"
set +e
answer="$("$client" health --server "127.0.0.1:$balancer_port" --timeout 45 2>&1)"
set -e
case "$answer" in
  *"no membraned replica is reachable"*) ;;
  *) fail "the balancer's answer was not its own gRPC status: $answer" ;;
esac
uid="$(pod exec "$balancer" sh -c 'sed -n "s/^Uid:[[:space:]]*\([0-9]*\).*/\1/p" /proc/1/status')"
[ "$uid" != 0 ] && [ -n "$uid" ] || fail "nginx runs as uid '$uid' in the container"
# The manifest's preStop: a graceful quit, which finds nginx through its pid file in /tmp.
logged balancer-quit pod exec "$balancer" nginx -s quit
[ "$(pod wait "$balancer")" = 0 ] || fail "nginx did not quit cleanly on 'nginx -s quit'"
step_done "balancer image: nginx read-only as uid $uid answers calls ($answer), quits on preStop"
say "passed"
