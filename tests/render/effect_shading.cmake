# Renders one view without effects, with ambient occlusion, with shadows and with both, and checks
# each shaded frame against the plain one (check_effect_shading: same hits, only darker pixels).
set(camera "pos=700,500,900;at=0,0,0;up=0,1,0;fov=35")
set(common ${PACKAGE} --size 64x64 --no-scene-effects)
foreach(variant plain ao shadows both)
  set(extra)
  if(variant STREQUAL "ao" OR variant STREQUAL "both")
    list(APPEND extra --effect ao --ao-rays 8 --ao-radius 40)
  endif()
  if(variant STREQUAL "shadows" OR variant STREQUAL "both")
    list(APPEND extra --effect shadows)
  endif()
  execute_process(COMMAND ${NANOVIEW} render ${common} "--camera=${camera}" ${extra} -o ${WORK}/shading-${variant}.png --ids ${WORK}/shading-${variant}.ids
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render ${variant} failed: ${out}${err}")
  endif()
endforeach()
# Fractions of hit pixels that must get darker: AO darkens crevices between atoms; shadows every
# pixel facing away from the light or behind another molecule.
foreach(pair "ao;0.2" "shadows;0.1" "both;0.3")
  list(GET pair 0 variant)
  list(GET pair 1 fraction)
  execute_process(COMMAND ${CHECK} ${WORK}/shading-plain.png ${WORK}/shading-plain.ids ${WORK}/shading-${variant}.png
                          ${WORK}/shading-${variant}.ids ${fraction}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${variant}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${variant} changed more than shading or did not darken enough")
  endif()
endforeach()

# From afar (the blood scene's camera, FAR_PACKAGE), AO whose rays reach 8 pixels' footprint must darken
# the frame clearly more than the same AO measured in Å alone.
set(far_common ${FAR_PACKAGE} --size 96x72 --no-scene-effects)
foreach(variant plain angstrom pixels)
  set(extra)
  if(variant STREQUAL "angstrom")
    set(extra --effect ao --ao-rays 8 --ao-radius 40)
  elseif(variant STREQUAL "pixels")
    set(extra --effect ao --ao-rays 8 --ao-radius 40 --ao-radius-pixels 8)
  endif()
  execute_process(COMMAND ${NANOVIEW} render ${far_common} ${extra} -o ${WORK}/far-ao-${variant}.png --ids ${WORK}/far-ao-${variant}.ids
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render far ${variant} failed: ${out}${err}")
  endif()
endforeach()
execute_process(COMMAND ${CHECK} ${WORK}/far-ao-plain.png ${WORK}/far-ao-plain.ids ${WORK}/far-ao-pixels.png ${WORK}/far-ao-pixels.ids 0.3
                        ${WORK}/far-ao-angstrom.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "AO in pixels from afar: ${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "AO with a radius in pixels changed more than shading, or does not carry more than AO in Å from afar")
endif()
