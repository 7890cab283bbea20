# Runs one libFuzzer binary briefly from a fresh scratch corpus plus the committed seeds, so
# every smoke run starts from the same state (with -seed fixed, the same inputs) and never
# writes into the source tree.
#   cmake -DFUZZER=<binary> -DWORK=<scratch dir> -DSEEDS=<seed dir> -DARTIFACTS=<prefix> -P run_fuzz_smoke.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(
  COMMAND ${FUZZER} -seed=1 -runs=20000 -max_total_time=20 -rss_limit_mb=2048 -timeout=10
          -artifact_prefix=${ARTIFACTS} ${WORK} ${SEEDS}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${result}); the crashing input is under ${ARTIFACTS}")
endif()
