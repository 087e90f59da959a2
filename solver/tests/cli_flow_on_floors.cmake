# A run whose flow solve once stalled: realisation 0 of the Monte Carlo Marcellus
# ensemble reaches t = 180 s with a 12-node network whose apertures all sit on their
# floors (the closing limit, w0), so the mass balance's Jacobian sees only the fluid's
# compressibility and the line-searched Newton iteration stalls at every step cut
# (docs/design_notes.md sections 21-23). With full Newton steps among the fallbacks the
# realisation runs its 60 steps, traced with --trace-iterations.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${HFDDA}" ensemble "${CASE}" --realisation 0 --out "${OUT}" --force --trace-iterations
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

# Traced (the results do not depend on it): every step ends on a committed attempt, the
# last one step 60's.
file(STRINGS "${OUT}/iterations.csv" committed REGEX ",attempt,[0-9]+,.*\"committed\"$")
list(LENGTH committed n_committed)
list(GET committed -1 last)
if(n_committed LESS 60 OR NOT last MATCHES "^60,")
  message(FATAL_ERROR "iterations.csv: ${n_committed} committed attempts, the last '${last}'")
endif()
# The trace is for one realisation.
execute_process(COMMAND "${HFDDA}" ensemble "${CASE}" --out "${OUT}_all" --trace-iterations
                RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 2 OR NOT err MATCHES "--trace-iterations goes with --realisation")
  message(FATAL_ERROR "--trace-iterations without --realisation: expected exit 2 and a reason, got ${code}: ${err}")
endif()
