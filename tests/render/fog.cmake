# Renders views without effects and with fog, and checks each fogged frame against the plain one and
# its depths (check_fog: same hits, unchanged background, each hit pixel mixed towards the background
# by the fog of its view depth within the frame's depth range). Two views: the virion from 1000 Å at
# 60° (a depth range far wider than a tenth of the nearest depth), and a 5° patch of it from 2000 Å
# (a few Å deep at ~1500 Å: the range's least extent, a tenth of the nearest depth, decides).
function(check_view name camera fov)
  set(common ${PACKAGE} --size 64x64 --no-scene-effects)
  execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" -o ${WORK}/fog-${name}-plain.png --ids ${WORK}/fog-${name}-plain.ids
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "plain render failed: ${out}${err}")
  endif()
  # start, span (of the depth range), strength, the share of hit pixels that must be fogged by a tenth
  foreach(case ${ARGN})
    string(REPLACE "," ";" case "${case}")
    list(GET case 0 start)
    list(GET case 1 span)
    list(GET case 2 strength)
    list(GET case 3 share)
    set(fogged fog-${name}-${start})
    execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" --effect fog --fog-start ${start} --fog-span ${span}
                            --fog-strength ${strength} -o ${WORK}/${fogged}.png --ids ${WORK}/${fogged}.ids
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "fog render failed: ${out}${err}")
    endif()
    execute_process(COMMAND ${CHECK} ${WORK}/fog-${name}-plain.png ${WORK}/fog-${name}-plain.ids ${WORK}/${fogged}.png ${WORK}/${fogged}.ids
                            ${start} ${span} ${strength} ${share} ${fov}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    message(STATUS "${name}, fog from ${start} over ${span}: ${out}${err}")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "fog (${name}, from ${start} over ${span}) changed more than colour, or not as its depths say")
    endif()
  endforeach()
endfunction()

check_view(wide "position=0,0,1000;look_at=0,0,0;up=0,1,0;fov_degrees=60" 60 "0,1,0.6,0.3" "0.4,0.2,1,0.2")
# On the patch the fog may not take the whole ramp: nothing needs to be fogged by a tenth.
check_view(patch "position=0,0,2000;look_at=0,0,0;up=0,1,0;fov_degrees=5" 5 "0,1,1,0")
