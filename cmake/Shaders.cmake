# nano_add_shaders(TARGET name SOURCES a.comp b.comp)
# Compiles GLSL to SPIR-V with glslangValidator (Vulkan 1.2 target) and embeds each module in a
# static library as `extern const uint32_t nano_spv_<stem>[]` with `nano_spv_<stem>_words`,
# so the runtime never looks for shader files on disk.
function(nano_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES" ${ARGN})
  set(generated)
  # Every file a shader may #include is a dependency of every shader: shared/*.h and the .glsl files
  # in any folder under shaders/ (each level's render/<level>.glsl). CONFIGURE_DEPENDS globs again
  # at build time, so a new include file counts without re-running cmake by hand.
  file(GLOB_RECURSE includes CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/shaders/shared/*.h ${PROJECT_SOURCE_DIR}/shaders/*.glsl)
  foreach(entry IN LISTS ARG_SOURCES)
    # "path.comp" or "path.comp@DEFINE": a variant compiled with -DDEFINE, named path_define.comp.
    string(REPLACE "@" ";" parts ${entry})
    list(GET parts 0 src)
    set(defines)
    get_filename_component(abs ${src} ABSOLUTE)
    get_filename_component(name ${src} NAME)
    list(LENGTH parts n)
    if(n GREATER 1)
      list(GET parts 1 define)
      set(defines -D${define})
      get_filename_component(name_we ${src} NAME_WE)
      get_filename_component(ext ${src} LAST_EXT)
      string(TOLOWER ${define} variant)
      set(name ${name_we}_${variant}${ext})
    endif()
    string(MAKE_C_IDENTIFIER ${name} stem)
    set(spv ${CMAKE_CURRENT_BINARY_DIR}/${name}.spv)
    set(cpp ${CMAKE_CURRENT_BINARY_DIR}/${stem}_spv.cpp)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.2 -V ${defines} -I${PROJECT_SOURCE_DIR}/shaders -o ${spv} ${abs}
      DEPENDS ${abs} ${includes}
      COMMENT "glslang ${name}"
      VERBATIM)
    add_custom_command(
      OUTPUT ${cpp}
      COMMAND ${CMAKE_COMMAND} -DSPV=${spv} -DOUT=${cpp} -DSTEM=${stem} -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      DEPENDS ${spv} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      VERBATIM)
    list(APPEND generated ${cpp})
  endforeach()
  add_library(${ARG_TARGET} STATIC ${generated})
endfunction()
