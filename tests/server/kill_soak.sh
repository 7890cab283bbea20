#!/bin/sh
# Soak of the SIGKILL fault test (tests/server/kill_fault_test.cc): membraned --store-dir killed
# at random moments CYCLES times (default 200) while clients follow their jobs by id; every
# accepted job must end SUCCEEDED with the mesh of an undisturbed run. Repeats ROUNDS times
# (default 1), each with a new seed, printed so that a failure can be replayed with
# MEMBRANE_KILL_SEED. Exits 1 at the first round that fails, with its output.
#   tests/server/kill_soak.sh [BUILD_DIR] [CYCLES] [ROUNDS]
set -eu
build=${1:-build}
cycles=${2:-200}
rounds=${3:-1}
binary="$build/tests/server/test_server_end_to_end"
if [ ! -x "$binary" ]; then
  echo "kill_soak.sh: $binary not found; build the target test_server_end_to_end" >&2
  exit 2
fi
output=$(mktemp)
trap 'rm -f "$output"' EXIT
round=1
while [ "$round" -le "$rounds" ]; do
  if ! MEMBRANE_KILL_CYCLES=$cycles "$binary" --gtest_filter='KillFaultTest.*' >"$output" 2>&1
  then
    cat "$output"
    echo "kill_soak.sh: round $round of $rounds failed" >&2
    exit 1
  fi
  echo "round $round of $rounds: $(grep -E 'kills:' "$output")"
  round=$((round + 1))
done
