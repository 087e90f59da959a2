# `hfdda ensemble` on a tiny ensemble: the likelihood maps are the same, byte for byte,
# on one process, on 2 and 4 MPI ranks (when mpirun is there), over two shards merged,
# and after a resume that re-runs a deleted realisation; every realisation has a record;
# a directory holding another ensemble (here: another shard) is refused with exit 2.
file(REMOVE_RECURSE "${OUT}")
set(maps likelihood_joints.csv likelihood_grid.csv likelihood_convergence.csv likelihood_joints_000.vtu
         likelihood_grid_002.vtu likelihood_joints.pvd likelihood_grid.pvd)

function(run_ensemble dir)
  execute_process(COMMAND ${ARGN} "${HFDDA}" ensemble "${CASE}" --out "${dir}" --no-figures ${EXTRA}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "ensemble into ${dir}: exit ${code}: ${out} ${err}")
  endif()
  set(last_err "${err}" PARENT_SCOPE)
endfunction()

function(expect_same_maps reference other)
  foreach(name IN LISTS maps)
    if(NOT EXISTS "${other}/${name}")
      message(FATAL_ERROR "${other}/${name} not written")
    endif()
    file(SHA256 "${reference}/${name}" a)
    file(SHA256 "${other}/${name}" b)
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "${name} differs between ${reference} and ${other}")
    endif()
  endforeach()
endfunction()

# One process.
run_ensemble("${OUT}/serial")
file(GLOB records "${OUT}/serial/realisations/r*.json")
list(LENGTH records n_records)
file(READ "${OUT}/serial/ensemble_summary.json" summary)
string(JSON completed GET "${summary}" completed)
string(JSON requested GET "${summary}" realisations_requested)
if(NOT n_records EQUAL requested OR NOT completed EQUAL requested OR requested LESS 4)
  message(FATAL_ERROR "${n_records} records, ${completed} completed of ${requested}: ${summary}")
endif()
file(READ "${OUT}/serial/likelihood_joints.csv" joints_csv)
if(NOT joints_csv MATCHES "\n120,[0-9]+,")
  message(FATAL_ERROR "likelihood_joints.csv has no row at the first map time (120 s)")
endif()

# MPI ranks, sharing this machine's cores (one thread each).
if(MPIEXEC)
  set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)
  set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
  # Containers often forbid the cross-memory attach OpenMPI's shared-memory transport tries.
  set(ENV{OMPI_MCA_btl_vader_single_copy_mechanism} none)
  # OpenMPI keeps memory to the end of the process: not ours to report under the sanitizers.
  set(ENV{ASAN_OPTIONS} "detect_leaks=0")
  foreach(ranks 2 4)
    run_ensemble("${OUT}/ranks${ranks}" "${MPIEXEC}" --oversubscribe -n ${ranks})
    expect_same_maps("${OUT}/serial" "${OUT}/ranks${ranks}")
  endforeach()
else()
  message(STATUS "mpirun not found: rank invariance not checked")
endif()

# Two shards, merged.
set(EXTRA --shard 0/2)
run_ensemble("${OUT}/shard0")
set(EXTRA --shard 1/2)
run_ensemble("${OUT}/shard1")
set(EXTRA "")
execute_process(COMMAND "${HFDDA}" ensemble merge --out "${OUT}/merged" "${OUT}/shard0" "${OUT}/shard1" --no-figures
                RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "merge: exit ${code}: ${err}")
endif()
expect_same_maps("${OUT}/serial" "${OUT}/merged")

# Resume: a deleted realisation is run again, the others are skipped.
file(COPY "${OUT}/serial/" DESTINATION "${OUT}/resumed")
file(REMOVE "${OUT}/resumed/realisations/r000002.json")
file(GLOB old_maps "${OUT}/resumed/likelihood_*")
file(REMOVE ${old_maps})
run_ensemble("${OUT}/resumed")
if(NOT last_err MATCHES " 1 of [0-9]+ realisations to run")
  message(FATAL_ERROR "resume did not run exactly the missing realisation: ${last_err}")
endif()
expect_same_maps("${OUT}/serial" "${OUT}/resumed")

# Another ensemble in the same directory is refused.
execute_process(COMMAND "${HFDDA}" ensemble "${CASE}" --out "${OUT}/shard0" --no-figures --shard 1/2
                RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 2 OR NOT err MATCHES "holds another ensemble")
  message(FATAL_ERROR "a directory of another shard was not refused: exit ${code}: ${err}")
endif()

# --force empties the directory but keeps the case file when it lies there (the harness
# writes a variant's case.yaml into the directory it runs the ensemble in; ensemble.json
# names it, and `--realisation I` needs it to repeat a realisation).
file(MAKE_DIRECTORY "${OUT}/own")
configure_file("${CASE}" "${OUT}/own/case.yaml" COPYONLY)
file(WRITE "${OUT}/own/stale.txt" "left by an earlier run")
execute_process(COMMAND "${HFDDA}" ensemble "${OUT}/own/case.yaml" --out "${OUT}/own" --no-figures --force
                RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR NOT EXISTS "${OUT}/own/case.yaml" OR EXISTS "${OUT}/own/stale.txt")
  message(FATAL_ERROR "--force with the case file in DIR: exit ${code}; case kept, stale file removed? ${err}")
endif()
expect_same_maps("${OUT}/serial" "${OUT}/own")
