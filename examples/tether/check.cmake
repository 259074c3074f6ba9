# ctest example_tether (tests/CMakeLists.txt, through tests/install_consumer/run.cmake):
# the example built against the installed ipstep runs its scene with the
# programs' flags and outputs, compares, and reports bad input as ipstep does.
function(run expected_rc must_contain)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL expected_rc)
    message(FATAL_ERROR "${ARGN}: exit code ${rc}, expected ${expected_rc}:\n${out}")
  endif()
  string(FIND "${out}" "${must_contain}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${ARGN}: output lacks '${must_contain}':\n${out}")
  endif()
endfunction()

set(scene --scene=${SOURCE}/tethered_square.json)
run(0 "tether: 25 terms" ${BUILD}/tether_ipstep ${scene} --steps=20 --integrator=newmark
    --stats=${WORK}/stats.csv --frames=${WORK}/frames --frame_every=10
    --positions=${WORK}/positions.csv)
if(NOT EXISTS ${WORK}/stats.csv OR NOT EXISTS ${WORK}/frames/run.pvd)
  message(FATAL_ERROR "tether_ipstep wrote no --stats or --frames output")
endif()
run(0 "| newmark | newton |" ${BUILD}/tether_compare ${scene} --steps=10
    --integrators=newmark --optimizers=newton,lbfgs)
run(0 "[0] " ${BUILD}/tether_bench --scenes=${SOURCE}/tethered_square.json --steps=4
    --integrators=newmark --optimizers=newton --repeats=1 --warmup=0 --output=${WORK}/sweep.csv)
file(STRINGS ${WORK}/sweep.csv rows)
list(LENGTH rows count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "tether_bench: expected a header and one row, got ${count} lines")
endif()
run(0 "Optimiser:" ${BUILD}/tether_ipstep --help)
file(READ ${SOURCE}/tethered_square.json text)
string(REPLACE "\"stiffness\": 20," "\"stiffness\": -1," text "${text}")
file(WRITE ${WORK}/bad.json "${text}")
run(2 "tether.stiffness" ${BUILD}/tether_ipstep --scene=${WORK}/bad.json)

# The Python module with the tether (where ipstep has its Python module): the
# same 20 steps as tether_ipstep's, to 1e-12 m, and the same bad-input line.
file(GLOB python_targets ${WORK}/prefix/lib*/cmake/ipstep/ipstepPythonTargets.cmake)
file(GLOB python_module ${BUILD}/ipstep_tether*.so)
if(python_targets AND NOT python_module)
  message(FATAL_ERROR "the installed ipstep has ipstep::python, but ipstep_tether was not built")
elseif(python_module)
  if(NOT PYTHON)
    message(FATAL_ERROR "ipstep_tether was built, but no interpreter was passed (-DPYTHON=)")
  endif()
  set(ENV{PYTHONPATH} ${BUILD})
  run(0 "same trajectory" ${PYTHON} ${SOURCE}/check_python.py ${SOURCE}/tethered_square.json
      ${WORK}/positions.csv ${WORK}/bad.json)
else()
  message(STATUS "ipstep_tether (Python) not built: the installed ipstep has no ipstep::python")
endif()
