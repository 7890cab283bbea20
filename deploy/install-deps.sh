#!/usr/bin/env bash
# Installs the Debian packages membrane needs to build, test and benchmark. Idempotent: only
# missing packages are installed. Works as root and, for other users, through sudo.
set -euo pipefail

PACKAGES=(
  cmake ninja-build g++ pkg-config
  libabsl-dev
  libgrpc++-dev libgrpc-dev protobuf-compiler protobuf-compiler-grpc libprotobuf-dev
  libdraco-dev
  libcli11-dev
  prometheus-cpp-dev         # membraned --metrics-listen
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev   # libFuzzer targets and the sanitizer job
  python3-open3d             # the peer measured beside us in tests/bench
  openssl                    # the TLS test makes its own self-signed certificate
  nginx-light                # the balancer test runs deploy/nginx/nginx.conf
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
