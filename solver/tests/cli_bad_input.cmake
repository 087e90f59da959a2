# `hfdda run` on a bad case file: exit code 2, a message naming file, line and key,
# and no output directory created (nothing half-written).
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${HFDDA}" run "${CASE}" --out "${OUT}" RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 2)
  message(FATAL_ERROR "expected exit code 2, got ${code}: ${err}")
endif()
if(NOT err MATCHES "bad_poisson.yaml:3: key 'materials\\[0\\].poissons_ratio'")
  message(FATAL_ERROR "error message does not name file:line and key: ${err}")
endif()
if(EXISTS "${OUT}")
  message(FATAL_ERROR "output directory was created for a bad case")
endif()
