# render --hide, checked by check_hidden against the same view without it (see check_hidden.cpp).
# Two views of blood: its cut-away (a red cell's haemoglobin in the plasma) hiding the red cells and
# albumin; and the scene's camera without the plasma hiding the membranes' lipids and the red cells' aquaporin.
set(cutaway_camera "position=41159,42886,60000;look_at=41159,42886,0;up=0,1,0;fov_degrees=40")
foreach(view cutaway cells)
  if(view STREQUAL "cutaway")
    set(names rbc albumin)
    set(base --clip-plane 0,0,-1,5300)
    set(camera "${cutaway_camera}")
  else()
    set(names POPC POPE cholesterol sphingomyelin aquaporin)  # the lipid kinds this 48² view shows
    set(base --hide medium)
    set(camera "fov_degrees=40")  # the scene's camera, a little wider
  endif()
  set(hides)
  foreach(name IN LISTS names)
    list(APPEND hides --hide ${name})
  endforeach()
  foreach(frame shown hidden)
    set(extra)
    if(frame STREQUAL "hidden")
      set(extra ${hides})
    endif()
    execute_process(COMMAND ${NANOVIEW} render ${PACKAGE} --size 48x48 "--camera=${camera}" ${base} ${extra}
                            -o ${WORK}/hide-${view}-${frame}.png --ids ${WORK}/hide-${view}-${frame}.ids
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "render ${view} ${frame} failed: ${out}${err}")
    endif()
  endforeach()
  execute_process(COMMAND ${CHECK} ${PACKAGE} ${WORK}/hide-${view}-shown.ids ${WORK}/hide-${view}-hidden.ids ${names}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${view}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${view}: --hide ${names} left something in, hid nothing, or changed what it should not")
  endif()
endforeach()
