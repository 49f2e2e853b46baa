# Renders views without effects and with outlines, then checks each outlined frame against its own ids
# image (check_outlines: every pixel's colour is the plain one mixed towards the outline colour by the
# strength the rule of docs/effects.md gives).
# 1. A close-up of the envelope, where a lipid spans many pixels: two widths, creases and fades, a
#    colour no shaded pixel has.
# 2. The virion's scene camera at 320×240 (FAR_PACKAGE), where a lipid is a pixel or two: outlines may
#    change at most 35 % of the hit pixels, and every spike must still be outlined.
function(render_pair package camera size name)
  execute_process(COMMAND ${NANOVIEW} render ${package} --size ${size} --no-scene-effects "--camera=${camera}" ${ARGN}
                          -o ${WORK}/${name}.png --ids ${WORK}/${name}.ids
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render ${name} failed: ${out}${err}")
  endif()
endfunction()

function(check_frame package plain name width crease fade word fov)
  execute_process(COMMAND ${CHECK} ${package} ${WORK}/${plain}.png ${WORK}/${plain}.ids ${WORK}/${name}.png ${WORK}/${name}.ids
                          ${width} ${crease} ${fade} ${word} ${fov} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${name}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "outlines ${name} are not what the rule makes of the ids image, or fail its measures")
  endif()
endfunction()

set(close "position=0,0,750;look_at=0,0,0;up=0,1,0;fov_degrees=12")
render_pair(${PACKAGE} "${close}" 96x72 outlines-plain)
# width, crease (Å), fade (px), colour as the option takes it, the RGBA8 word it packs to (R in the low byte)
foreach(case "1;5;12;0,0,0;ff000000" "3;2.5;0;1,0,1;ffff00ff" "2;5;200;0,0,0;ff000000")
  list(GET case 0 width)
  list(GET case 1 crease)
  list(GET case 2 fade)
  list(GET case 3 colour)
  list(GET case 4 word)
  render_pair(${PACKAGE} "${close}" 96x72 outlines-${width} --effect outlines --outlines-width-pixels ${width}
              --outlines-crease-depth ${crease} --outlines-fade-pixels ${fade} --outlines-colour ${colour})
  check_frame(${PACKAGE} outlines-plain outlines-${width} ${width} ${crease} ${fade} ${word} 12)
endforeach()

set(far "position=900,700,1300;look_at=0,0,0;up=0,1,0;fov_degrees=40")
render_pair(${FAR_PACKAGE} "${far}" 320x240 outlines-far-plain)
render_pair(${FAR_PACKAGE} "${far}" 320x240 outlines-far --effect outlines)
check_frame(${FAR_PACKAGE} outlines-far-plain outlines-far 1 5 12 ff000000 40 0.35 spike 20)
