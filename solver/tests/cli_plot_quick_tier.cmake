# `hfdda plot` on a run of the quick verification tier that a user's own case resembles: a
# hydraulic fracture meeting a natural fracture read from a fracture map (Blanton's CT22,
# verification/blanton). The maps at t = 0 and 12 s and the histories are written, and
# the map's own account of what it drew shows the natural fracture (thin), open joints
# (thick) and, at 12 s, natural joints holding fluid while closed (light).
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${HFDDA}" plot "${RUN}" --times 0,12 --out "${OUT}"
                RESULT_VARIABLE code OUTPUT_VARIABLE listed ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "plot: exit ${code}: ${err}")
endif()
foreach(png IN ITEMS "${OUT}/fracture_map_t0.png" "${OUT}/fracture_map_t12.png" "${OUT}/histories.png")
  if(NOT EXISTS "${png}")
    message(FATAL_ERROR "plot: ${png} not written; printed: ${listed}")
  endif()
  file(SIZE "${png}" size)
  if(size LESS 1000)
    message(FATAL_ERROR "plot: ${png} has only ${size} bytes")
  endif()
endforeach()
if(NOT listed MATCHES "t = 12 s: [0-9]+ joints drawn: ([0-9]+) natural \\(thin\\), ([0-9]+) open \\(thick\\), ([0-9]+) closed with fluid")
  message(FATAL_ERROR "plot: no account of the 12 s map in: ${listed}")
endif()
if(CMAKE_MATCH_1 EQUAL 0 OR CMAKE_MATCH_2 EQUAL 0 OR CMAKE_MATCH_3 EQUAL 0)
  message(FATAL_ERROR "plot: the 12 s map should show natural, open and invaded joints: ${listed}")
endif()
