# Renders one view without effects and with fog, and checks the fogged frame against the plain one and
# its depths (check_fog: same hits, unchanged background, each hit pixel mixed towards the background
# by the fog of its depth within the frame's depth range).
set(camera "position=0,0,1000;look_at=0,0,0;up=0,1,0;fov_degrees=60")
set(common ${PACKAGE} --size 64x64 --no-scene-effects)
execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" -o ${WORK}/fog-plain.png --ids ${WORK}/fog-plain.ids
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plain render failed: ${out}${err}")
endif()
# start, span (of the depth range), strength, the share of hit pixels that must be fogged by a tenth
foreach(case "0;1;0.6;0.3" "0.4;0.2;1;0.2")
  list(GET case 0 start)
  list(GET case 1 span)
  list(GET case 2 strength)
  list(GET case 3 share)
  execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" --effect fog --fog-start ${start} --fog-span ${span} --fog-strength ${strength}
                          -o ${WORK}/fog-${start}.png --ids ${WORK}/fog-${start}.ids
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fog render failed: ${out}${err}")
  endif()
  execute_process(COMMAND ${CHECK} ${WORK}/fog-plain.png ${WORK}/fog-plain.ids ${WORK}/fog-${start}.png ${WORK}/fog-${start}.ids
                          ${start} ${span} ${strength} ${share} 60
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "fog from ${start} over ${span}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fog from ${start} over ${span} changed more than colour, or not as its depths say")
  endif()
endforeach()
