# ctest bench_smoke: runs a tiny sweep of ipstep_bench in two shards, merges
# them and checks the merged CSV (row count, no configuration errors). Timings
# are never checked.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(sweep --scenes=oscillator,cloth --grid_sizes=6 --integrators=backward_euler,newmark,symplectic_euler
          --optimizers=newton,lbfgs,projected_newton --dt_factors=1,0.5 --steps=4
          --repeats=1 --warmup=0 --max_run_seconds=10)
foreach(shard 0 1)
  execute_process(COMMAND ${BENCH} ${sweep} --shard=${shard}/2 --output=${WORK_DIR}/shard${shard}.csv
                  RESULT_VARIABLE rc ERROR_VARIABLE log)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "shard ${shard} failed (${rc}):\n${log}")
  endif()
  # The second shard reads the references the first computed (bench/references/).
  if(shard EQUAL 1 AND NOT log MATCHES "0 reference runs computed")
    message(FATAL_ERROR "shard 1 should read its references from the cache:\n${log}")
  endif()
endforeach()
# The merged file's folder does not exist yet: --output creates it.
execute_process(COMMAND ${BENCH} --merge=${WORK_DIR}/shard*.csv --output=${WORK_DIR}/merged/all.csv
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "merge failed (${rc}):\n${log}")
endif()
file(STRINGS ${WORK_DIR}/merged/all.csv lines)
# A missing shard and a shard given twice are refused (exit 2), naming the shard.
file(COPY_FILE ${WORK_DIR}/shard0.csv ${WORK_DIR}/copy_of_shard0.csv)
foreach(case "missing;${WORK_DIR}/shard0.csv;shard 1/2"
             "duplicated;${WORK_DIR}/shard0.csv,${WORK_DIR}/shard1.csv,${WORK_DIR}/copy_of_shard0.csv;shard 0/2 is in two files")
  list(GET case 0 name)
  list(GET case 1 inputs)
  list(GET case 2 expected)
  execute_process(COMMAND ${BENCH} --merge=${inputs} --output=${WORK_DIR}/${name}.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "a merge with a ${name} shard should exit with 2, got ${rc}:\n${log}")
  endif()
  string(FIND "${log}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "a merge with a ${name} shard should say '${expected}':\n${log}")
  endif()
endforeach()
list(LENGTH lines count)
# 2 scenes x (2 variational integrators x 3 optimisers + symplectic Euler) x 2 dt = 28 rows.
if(NOT count EQUAL 29)
  message(FATAL_ERROR "expected a header and 28 rows, got ${count} lines")
endif()
foreach(line IN LISTS lines)
  if(line MATCHES ",error: ")
    message(FATAL_ERROR "a configuration failed to run: ${line}")
  endif()
endforeach()
# Bad input is exit code 2.
execute_process(COMMAND ${BENCH} --optimizers=newton+bogus=1 --output=${WORK_DIR}/bad.csv
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "a bad optimizer spec should exit with 2, got ${rc}")
endif()
