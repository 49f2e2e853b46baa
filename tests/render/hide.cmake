# render --hide, checked by check_hidden against the same view without it (see check_hidden.cpp).
# Two views of a blood scene: its cut-away (CUTAWAY_CAMERA and CUTAWAY_CLIP: a red cell's haemoglobin
# in the plasma) hiding the red cells and albumin; and CELLS_CAMERA without the plasma hiding the
# membranes' lipids and the red cells' aquaporin.
foreach(view cutaway cells)
  if(view STREQUAL "cutaway")
    set(names rbc albumin)
    set(base --clip-plane ${CUTAWAY_CLIP})
    set(camera "${CUTAWAY_CAMERA}")
  else()
    set(names POPC POPE aquaporin)
    set(base --hide medium)
    set(camera "${CELLS_CAMERA}")
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
