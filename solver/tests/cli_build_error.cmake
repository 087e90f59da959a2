# `hfdda run` on a case that reads but whose model cannot be built (a fracture off the
# grid lines): exit code 2 and the message; the output directories the run created
# for it are removed again, a directory that existed before is kept.
file(REMOVE_RECURSE "${OUT}")
function(expect_build_error out_dir)
  execute_process(COMMAND "${HFDDA}" run "${CASE}" --out "${out_dir}" --quiet RESULT_VARIABLE code ERROR_VARIABLE err)
  if(NOT code EQUAL 2 OR NOT err MATCHES "off_grid_fracture.yaml:7: key 'fractures\\[0\\]': .*does not follow mesh edges")
    message(FATAL_ERROR "--out ${out_dir}: expected exit code 2 and the model-build error, got ${code}: ${err}")
  endif()
endfunction()

# Three levels created by the run: all removed.
expect_build_error("${OUT}/a/b")
if(EXISTS "${OUT}")
  message(FATAL_ERROR "the output directory the run created was left behind: ${OUT}")
endif()

# An existing directory, empty or not: kept as it was; the level below it that the run
# created is removed.
file(MAKE_DIRECTORY "${OUT}/empty")
file(WRITE "${OUT}/notes/notes.txt" "kept")
expect_build_error("${OUT}/empty")
expect_build_error("${OUT}/notes")
expect_build_error("${OUT}/empty/new/")
if(NOT IS_DIRECTORY "${OUT}/empty" OR NOT EXISTS "${OUT}/notes/notes.txt")
  message(FATAL_ERROR "a directory that existed before the run was removed or emptied")
endif()
if(EXISTS "${OUT}/empty/new")
  message(FATAL_ERROR "the directory the run created under an existing one was left behind")
endif()
file(REMOVE_RECURSE "${OUT}")
