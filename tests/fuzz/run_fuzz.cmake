# Runs the glTF fuzz target for a bounded number of inputs (CTest: GltfLoader.Fuzz). Arguments:
# FUZZER (the binary), WORK (a scratch corpus folder, emptied first), DICT, and SEEDS (seed
# folders separated by '|'; absent ones are left out). Any finding fails the test, and
# libFuzzer leaves the crashing input in WORK as crash-*/leak-*/timeout-*/oom-*.
string(REPLACE "|" ";" seeds "${SEEDS}")
set(existing "")
foreach(dir IN LISTS seeds)
  if(IS_DIRECTORY "${dir}")
    list(APPEND existing "${dir}")
  else()
    message(STATUS "seed folder absent, left out: ${dir}")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus")
execute_process(
  COMMAND "${FUZZER}" -runs=${RUNS} -max_total_time=${SECONDS} -timeout=20 -rss_limit_mb=2048 -seed=1 -dict=${DICT}
          -artifact_prefix=${WORK}/ -print_final_stats=1 "${WORK}/corpus" ${existing}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the glTF fuzz target found a problem (exit ${result}); the input is in ${WORK}")
endif()
