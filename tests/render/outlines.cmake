# Renders one view without effects and with outlines (two widths and creases, a colour that no shaded
# pixel has), then checks each outlined frame against its own ids image (check_outlines).
# A close-up of the envelope, where a lipid spans several pixels (from afar every pixel is another copy).
set(camera "position=0,0,750;look_at=0,0,0;up=0,1,0;fov_degrees=12")
set(common ${PACKAGE} --size 96x72 --no-scene-effects)
execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" -o ${WORK}/outlines-plain.png --ids ${WORK}/outlines-plain.ids
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plain render failed: ${out}${err}")
endif()
# width, crease (Å), colour as the option takes it, the RGBA8 word it packs to (R in the low byte)
foreach(case "1;5;0,0,0;ff000000" "3;2.5;1,0,1;ffff00ff")
  list(GET case 0 width)
  list(GET case 1 crease)
  list(GET case 2 colour)
  list(GET case 3 word)
  execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" --effect outlines --outlines-width-pixels ${width}
                          --outlines-crease-depth ${crease} --outlines-colour ${colour}
                          -o ${WORK}/outlines-${width}.png --ids ${WORK}/outlines-${width}.ids
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "outlined render failed: ${out}${err}")
  endif()
  execute_process(COMMAND ${CHECK} ${WORK}/outlines-plain.png ${WORK}/outlines-plain.ids ${WORK}/outlines-${width}.png
                          ${WORK}/outlines-${width}.ids ${width} ${crease} ${word}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "width ${width}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "outlines of width ${width} are not exactly the ids image's discontinuities")
  endif()
endforeach()
