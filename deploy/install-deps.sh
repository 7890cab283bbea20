#!/usr/bin/env bash
# Installs the Debian packages membrane needs, by set:
#   build      compile membrane, membraned and membrane-decode (the container's build stage)
#   test       the test suites of deploy/run-tests.sh, sanitizer and fuzzer builds included
#   bench      the benchmarks of tests/bench
#   container  deploy/test-container.sh: podman on runc, and debootstrap for its base image
# Usage: deploy/install-deps.sh [SET...]; no SET means every set. Idempotent: only missing
# packages are installed. Works as root and, for other users, through sudo.
set -euo pipefail

BUILD=(
  cmake ninja-build g++
  ccache                     # the image build keeps its cache between builds (deploy/Dockerfile)
  libabsl-dev
  libgrpc++-dev libgrpc-dev protobuf-compiler protobuf-compiler-grpc libprotobuf-dev
  libdraco-dev
  liblzf-dev                 # PCD DATA binary_compressed
  libcli11-dev
  prometheus-cpp-dev         # membraned --metrics-listen
  libcivetweb-dev            # membraned --http-listen (prometheus-cpp's HTTP server too)
  libpng-dev                 # mesh previews (membrane render, the web console)
)
TEST=(
  ccache                     # run-tests.sh's Release build, whose objects the image's build reads
  libgtest-dev libgmock-dev
  clang libclang-rt-14-dev   # libFuzzer targets and the sanitizer job
  openssl                    # the TLS test makes its own self-signed certificate
  nginx-light                # the balancer test runs deploy/nginx/nginx.conf
  python3-yaml python3-kubernetes  # the manifest test (tests/deploy): YAML, the API schema
  python3-jsonschema         # the statistics JSON against proto/membrane/v1/statistics.schema.json
  python3-grpcio python3-protobuf  # client/python, tested against a live membraned
  libjs-three                # the web console's 3D view (membraned serves its files)
  chromium chromium-driver   # the web console's test in a headless browser
)
BENCH=(
  libbenchmark-dev
  python3-open3d             # the peer measured beside us in tests/bench
  python3-scipy              # the eval tools' scorer (accuracy_table.py)
)
CONTAINER=(
  podman runc                # runc: crun cannot set this machine's rlimits (test-container.sh)
  debootstrap                # the base image is made locally: no registry is reachable
)

sets=("$@")
[ ${#sets[@]} -gt 0 ] || sets=(build test bench container)
PACKAGES=()
for s in "${sets[@]}"; do
  case "$s" in
    build) PACKAGES+=("${BUILD[@]}") ;;
    test) PACKAGES+=("${TEST[@]}") ;;
    bench) PACKAGES+=("${BENCH[@]}") ;;
    container) PACKAGES+=("${CONTAINER[@]}") ;;
    *) echo "install-deps: unknown set '$s' (build, test, bench, container)" >&2; exit 2 ;;
  esac
done

# Once each, though a package may be in two sets (ccache).
mapfile -t PACKAGES < <(printf '%s\n' "${PACKAGES[@]}" | awk '!seen[$0]++')
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages of ${sets[*]} present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
