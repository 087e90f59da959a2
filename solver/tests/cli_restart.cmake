# A run stopped mid-way (SIGNAL=KILL: killed outright; SIGNAL=TERM: asked to stop) and
# continued with --restart gives the history.csv of a run never stopped, but for the
# wall-time columns. SIGKILL must leave whole lines in history.csv; SIGTERM must end
# with exit code 3 and a checkpoint, and say at once that the stop was taken.
set(full "${OUT}_${SIGNAL}_full")
set(out "${OUT}_${SIGNAL}")
file(REMOVE_RECURSE "${full}" "${out}")
execute_process(COMMAND "${HFDDA}" run "${CASE}" --out "${full}" --quiet RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "uninterrupted run: exit ${code}: ${err}")
endif()

# Start the run, wait until 5 steps are in history.csv (checkpoints every 2 steps), signal it.
set(script "\"$0\" run \"$1\" --out \"$2\" --quiet --checkpoint-every 2 & pid=$!
i=0
while [ $i -lt 3000 ]; do
  if [ -f \"$2/history.csv\" ] && [ $(wc -l < \"$2/history.csv\") -ge 6 ]; then break; fi
  sleep 0.01; i=$((i+1))
done
kill -${SIGNAL} $pid
wait $pid")
execute_process(COMMAND sh -c "${script}" "${HFDDA}" "${CASE}" "${out}" RESULT_VARIABLE code ERROR_VARIABLE err)
if(EXISTS "${out}/summary.json" AND NOT SIGNAL STREQUAL "TERM")
  message(FATAL_ERROR "the run ended before it was killed; the test needs a longer case")
endif()
if(SIGNAL STREQUAL "TERM")
  if(NOT code EQUAL 3 OR NOT err MATCHES "checkpoint .*--restart")
    message(FATAL_ERROR "SIGTERM: expected exit code 3 and a restart hint, got ${code}: ${err}")
  endif()
  # Told at once that the signal was taken, and how to stop without waiting for the step.
  if(NOT err MATCHES "stop requested: the current step is abandoned at its next iteration.*signal again to stop at once")
    message(FATAL_ERROR "SIGTERM: no notice that the stop was requested: ${err}")
  endif()
  file(READ "${out}/summary.json" summary)
  if(NOT summary MATCHES "\"status\": \"interrupted\"")
    message(FATAL_ERROR "summary.json does not record the interruption")
  endif()
elseif(NOT code EQUAL 137)
  message(FATAL_ERROR "SIGKILL: expected the shell's 137, got ${code}: ${err}")
endif()
if(NOT EXISTS "${out}/checkpoint.bin")
  message(FATAL_ERROR "no checkpoint after the interruption")
endif()

# Every line of the interrupted history.csv is whole.
file(STRINGS "${out}/history.csv" lines)
list(GET lines 0 header)
string(REPLACE "," ";" names "${header}")
list(LENGTH names n_columns)
foreach(line IN LISTS lines)
  string(REPLACE "," ";" fields "${line}")
  list(LENGTH fields n)
  if(NOT n EQUAL n_columns)
    message(FATAL_ERROR "partial line in history.csv after the interruption: '${line}'")
  endif()
endforeach()

execute_process(COMMAND "${HFDDA}" run "${CASE}" --out "${out}" --quiet --restart RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "restart: exit ${code}: ${err}")
endif()

# history.csv of both runs without the wall-time columns.
list(FIND names step_wall_s wall_a)
list(FIND names elapsed_wall_s wall_b)
function(history_without_wall file result)
  file(STRINGS "${file}" rows)
  set(text "")
  foreach(row IN LISTS rows)
    string(REPLACE "," ";" fields "${row}")
    list(REMOVE_AT fields ${wall_a} ${wall_b})
    string(APPEND text "${fields}\n")
  endforeach()
  set(${result} "${text}" PARENT_SCOPE)
endfunction()
history_without_wall("${full}/history.csv" expected)
history_without_wall("${out}/history.csv" actual)
if(NOT expected STREQUAL actual)
  message(FATAL_ERROR "history.csv after the restart differs from the uninterrupted run:\n${expected}\n---\n${actual}")
endif()
foreach(f joints/joints_final.csv blocks.pvd joints.pvd vtu/blocks_000012.vtu)
  file(READ "${full}/${f}" a)
  file(READ "${out}/${f}" b)
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "${f} after the restart differs from the uninterrupted run")
  endif()
endforeach()
file(REMOVE_RECURSE "${full}" "${out}")
