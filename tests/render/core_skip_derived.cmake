# render.virion.core_skip_derived: the same cutaway rendered from a package and from its copy without
# section core_skip must give the same hit ids (the runtime derives the levels the baker wrote).
# -DSTRIP= -DNANOVIEW= -DPACKAGE= -DWORK=
execute_process(COMMAND ${STRIP} ${PACKAGE} ${WORK}/virion-no-skip.nup core_skip RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "strip_section failed: ${rc}")
endif()
foreach(name virion virion-no-skip)
  if(name STREQUAL "virion")
    set(pkg ${PACKAGE})
  else()
    set(pkg ${WORK}/virion-no-skip.nup)
  endif()
  # Cut open by z <= 0, seen from +z: rays cross the grid's empty corners, then the lumen's solubles.
  execute_process(COMMAND ${CMAKE_COMMAND} -E env LP_NUM_THREADS=4 ${NANOVIEW} render ${pkg} -o ${WORK}/${name}-cut.png
                          --ids ${WORK}/${name}-cut.ids --size 96x72 --no-scene-effects --clip-plane 0,0,-1,0
                          --camera "position=0,0,1800;look_at=0,0,0;up=0,1,0;fov_degrees=40"
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render of ${pkg} failed: ${err}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/virion-cut.ids ${WORK}/virion-no-skip-cut.ids RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the hits differ with the derived skip levels")
endif()
