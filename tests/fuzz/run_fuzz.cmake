# Runs a fuzz target for a bounded number of inputs (CTest: GltfLoader.Fuzz, BuiltinScenes.Fuzz,
# MethodOptions.Fuzz). Arguments: FUZZER (the binary), WORK (a scratch corpus folder, emptied
# first), DICT, SEEDS (seed folders separated by '|'; absent ones are left out), RUNS and SECONDS
# (it stops at whichever comes first), TIMEOUT (seconds an input may take) and RSS_MB (memory).
# Any finding fails the test, and libFuzzer leaves the input in WORK as crash-*/leak-*/
# timeout-*/oom-*.
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
  COMMAND "${FUZZER}" -runs=${RUNS} -max_total_time=${SECONDS} -timeout=${TIMEOUT} -rss_limit_mb=${RSS_MB} -seed=1 -dict=${DICT}
          -artifact_prefix=${WORK}/ -print_final_stats=1 "${WORK}/corpus" ${existing}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${FUZZER} found a problem (exit ${result}); the input is in ${WORK}")
endif()
