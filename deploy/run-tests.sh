#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: the Release suite, then the container
# image built with podman and run (deploy/test-container.sh), the engine, synth, io, mesh,
# pipeline and in-process server suites again under AddressSanitizer and
# UndefinedBehaviorSanitizer, the thread tests of the mesh suite under ThreadSanitizer, then
# the libFuzzer smoke of the readers (clang).
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${JOBS:-$(nproc)}"

deploy/install-deps.sh
# Each phase says how long it took: the suite must stay well under CI's budget on 2 cores.
phase_start=$SECONDS
phase_done() { echo "== $1 took $((SECONDS - phase_start)) s"; phase_start=$SECONDS; }

echo "== Release build and full suite"
# -Werror here only: the sanitizer and fuzz builds compile at other levels and with clang,
# where compilers warn about other things; the Release build is the one users run.
# Through ccache, which also writes every object it compiles or finds (reshare) to a store of
# this build's own, build/ccache-store: the container image's build (deploy/test-container.sh)
# reads it and compiles nothing that was compiled here. Its keys must match the image's: paths
# relative to the root (CCACHE_BASEDIR, the image compiles under /src), and none of the locale
# variables ccache hashes (the image's build sets none). The store is kept between runs (a
# build with nothing to compile leaves the image its objects); ccache never trims a file
# store, so its least recently used files go here once it passes 1 GB (a whole
# Release build's objects take 14 MB).
mkdir -p build/ccache-store
ccache --trim-dir build/ccache-store --trim-max-size 1G >/dev/null
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DMEMBRANE_WERROR=ON \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
env -u LANG -u LC_ALL -u LC_CTYPE -u LC_MESSAGES CCACHE_BASEDIR="$(pwd -P)" \
  CCACHE_SECONDARY_STORAGE="file://$(pwd -P)/build/ccache-store" CCACHE_RESHARE=true \
  cmake --build build -j "$JOBS"
ctest --test-dir build --output-on-failure -j "$JOBS" --timeout 900
phase_done "Release build and suite"

echo "== Container image: built with podman, run read-only, restarted (deploy/test-container.sh)"
deploy/test-container.sh build
phase_done "Container image build and run"

echo "== ASan/UBSan build: engine, synth, io, mesh, pipeline and server (in process) suites"
# -O1 -g1 (line tables): sanitizer reports keep file:line at a lower build cost than -O2 -g
# (measured on 2 cores: the whole suite 17.9 min against 18.4).
# ccache here too: a machine that keeps its cache between runs compiles only what changed.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DMEMBRANE_SANITIZE=ON \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  -DMEMBRANE_BENCH=OFF -DMEMBRANE_TEST_DIRS="engine;synth;io;mesh;pipeline;server"
# Only what these suites run: the client and the process-level server tests are not built a
# second time (the in-process suite covers the service, its job runner and the decoder child).
cmake --build build-asan -j "$JOBS" --target test_engine test_shrink test_real_scans test_synth \
  test_io test_mesh test_mesh_decimation test_render test_reconstructed_surfaces test_pipeline \
  test_server_service
# Left to the Release suite: tests that run on a real scan code that a test of a synthetic
# shape or of another scan already runs here, and whose point is the result, not the memory:
# the local snapshots and the thread counts on a real scan (the same comparisons on the
# synthetic torus and spheres run here), the decimation of the spot scan (the shapes' run
# here) and the real clouds' Draco variants (the shapes' Draco variants run here): 135 of the
# suites' 1000 test seconds under ASan, about a minute of wall on 2 cores. So are four
# comparisons whose cost is their size or their reference, not code that runs nowhere else
# here: the chains-only shrinks with and without local snapshots (every pass's snapshot
# against the dense one runs on the sparse torus and random grids here), the dense snapshot
# against the paper's slow list scan (every shrink here takes dense snapshots), the rejected
# closed forms restored on 1-4 threads (restored by planes in AppliesVoxelByVoxelOrByPlanes,
# the threads' word blocks in TorusIsTheSameForAnyThreadCount) and the sweeps' long runs on
# 1-4 threads (FlatBitsetThreads.RunsAreTheSameForAnyThreadCount's long runs here, the sweeps
# under ThreadSanitizer below): 179 test seconds under ASan (2026-12-07), 90 s of wall.
asan_release_only='LocalSnapshots\.RealScanShrinksTheSame$'
asan_release_only+='|ShrinkThreads\.RealScanIsTheSameForAnyThreadCount$'
asan_release_only+='|RealCloudDecimationTest\.SpotScanKeepsItsSurface$'
asan_release_only+='|^SharedData/RealCloudSurfaceTest\..*_drc( |$)'
asan_release_only+='|LocalSnapshots\.ChainsOnlyShrinkTheSame$'
asan_release_only+='|PlaceFinderTest\.DenseSnapshotIsThePaperListScan$'
asan_release_only+='|ShrinkThreads\.RejectedClosedFormsAreRestoredOnAnyThreadCount$'
asan_release_only+='|ClosedFormSweeps\.LongRunsReachTheLeastFixedPointOnAnyThreadCount$'
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j "$JOBS" --timeout 1800 \
  -E "$asan_release_only"
phase_done "ASan/UBSan build and suites"

echo "== ThreadSanitizer: the threaded word passes, surface fit and crossing search"
# Only the engine's and the mesh suite's thread tests: the shrink's word blocks and segments,
# the fit's slabs and the search's cells run side by side, and their independence is what
# keeps the mesh the same for any thread count.
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DMEMBRANE_TSAN=ON -DMEMBRANE_BENCH=OFF \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  -DMEMBRANE_TEST_DIRS="engine;mesh"
cmake --build build-tsan -j "$JOBS" --target test_engine test_mesh
TSAN_OPTIONS=halt_on_error=1 ctest --test-dir build-tsan --output-on-failure -j "$JOBS" \
  -R 'ParallelTasks|AnyThreadCount|CancelledMidwayOnSeveralThreads'
phase_done "ThreadSanitizer build and thread tests"

echo "== libFuzzer smoke of the readers (clang, ASan/UBSan)"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  -DMEMBRANE_FUZZ=ON -DMEMBRANE_BENCH=OFF -DMEMBRANE_TEST_DIRS="io"
cmake --build build-fuzz -j "$JOBS" --target fuzz_io_ply fuzz_io_obj fuzz_io_xyz fuzz_io_pcd fuzz_io_drc fuzz_io_stl fuzz_io_off
ctest --test-dir build-fuzz -R '^fuzz_io_' --output-on-failure -j "$JOBS"
phase_done "libFuzzer build and smoke"
