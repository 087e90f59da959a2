# A run whose flow solve once stalled: realisation 0 of the Monte Carlo Marcellus
# ensemble reaches t = 180 s with a 12-node network whose apertures all sit on their
# floors (the closing limit, w0), so the mass balance's Jacobian sees only the fluid's
# compressibility and the line-searched Newton iteration stalls at every step cut
# (docs/design_notes.md sections 21-23). With full Newton steps among the fallbacks the
# realisation runs its 60 steps.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${HFDDA}" ensemble "${CASE}" --realisation 0 --out "${OUT}" --force
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "realisation 0 did not complete (exit ${code}): ${err}")
endif()
file(READ "${OUT}/summary.json" summary)
string(JSON status GET "${summary}" status)
string(JSON steps GET "${summary}" steps)
if(NOT status STREQUAL "completed" OR NOT steps EQUAL 60)
  message(FATAL_ERROR "realisation 0: status ${status} after ${steps} of 60 steps")
endif()
