# The preset asked for in scene.json (baked into PACKAGE, with the outline width overridden there) must
# draw the very frame the same preset and override give from the command line: the scene key, the bake,
# the package's effects record and the runtime's options all carry one preset.
set(camera "position=300,250,700;look_at=0,0,0;up=0,1,0;fov_degrees=40")
execute_process(COMMAND ${NANOVIEW} render ${PACKAGE} --size 64x48 "--camera=${camera}" -o ${WORK}/preset-scene.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render with the scene's preset failed: ${out}${err}")
endif()
execute_process(COMMAND ${NANOVIEW} render ${PACKAGE} --size 64x48 "--camera=${camera}" --no-scene-effects --preset illustrative
                        --outlines-width-pixels 2 -o ${WORK}/preset-option.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render with --preset failed: ${out}${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/preset-scene.png ${WORK}/preset-option.png RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "the scene's preset and --preset draw different frames")
endif()
# Not vacuous: the preset changes the frame.
execute_process(COMMAND ${NANOVIEW} render ${PACKAGE} --size 64x48 "--camera=${camera}" --no-scene-effects -o ${WORK}/preset-plain.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/preset-scene.png ${WORK}/preset-plain.png RESULT_VARIABLE same)
if(same EQUAL 0)
  message(FATAL_ERROR "the preset changed nothing")
endif()
