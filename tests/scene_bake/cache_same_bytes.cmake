# The scene baked again through the bake cache that baked PACKAGE: the report says its shells came
# from the cache, and the package is byte for byte PACKAGE.
execute_process(COMMAND ${NANOBAKE} ${SCENE} -o ${WORK}/cached-again.nup --report ${WORK}/cached-again.json --jobs 2
                        --cache-dir ${CACHE} -q
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the bake through the cache failed (${rc}): ${out}${err}")
endif()
file(READ ${WORK}/cached-again.json report)
string(JSON compartments LENGTH "${report}" compartments)
math(EXPR last "${compartments} - 1")
foreach(c RANGE ${last})
  string(JSON name GET "${report}" compartments ${c} name)
  string(JSON cached ERROR_VARIABLE no_flag GET "${report}" compartments ${c} shells_from_cache)
  if(NOT cached STREQUAL "ON" AND NOT cached STREQUAL "true")
    message(FATAL_ERROR "compartment ${name}: its shells were computed again, not read from the cache (${cached}${no_flag})")
  endif()
endforeach()
file(SHA256 ${PACKAGE} computed)
file(SHA256 ${WORK}/cached-again.nup cached)
if(NOT computed STREQUAL cached)
  message(FATAL_ERROR "the package baked with its shells from the cache differs from the one that computed them")
endif()
message(STATUS "shells from the cache for ${compartments} compartment(s); package identical (${cached})")
