# Compiles package_records_glsl.comp and checks glslang's std430 reflection (offset of each
# record's last member and array stride) against the C++ layout pinned in package_records.h and
# instanced_records.h.
execute_process(COMMAND ${GLSLANG} -q --target-env vulkan1.2 -V -I${SHADERS} -o ${OUT} ${SOURCE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "glslang failed:\n${out}${err}")
endif()
foreach(expect
    "molecules.reserved1: offset 92,[^\n]*topLevelArrayStride 96"
    "atoms.centre_radius: offset 0,[^\n]*topLevelArrayStride 16"
    "tiles2d.reserved1: offset 44,[^\n]*topLevelArrayStride 48"
    "tiles3d.reserved1: offset 60,[^\n]*topLevelArrayStride 64"
    "instances.reserved2: offset 76,[^\n]*topLevelArrayStride 80"
    "recipes.reserved1: offset 28,[^\n]*topLevelArrayStride 32"
    "meshes.triangle_count: offset 44,[^\n]*topLevelArrayStride 48"
    "triangles.v2: offset 8,[^\n]*topLevelArrayStride 12"
    "shells.seam_edges: offset 28,[^\n]*topLevelArrayStride 32"
    "compartments.reserved0: offset 92,[^\n]*topLevelArrayStride 112"
    "compartments.core_masks: offset 96,[^\n]*topLevelArrayStride 112"
    "scene.reserved2: offset 60,[^\n]*topLevelArrayStride 64"
    "compartment_instances.reserved2: offset 60,[^\n]*topLevelArrayStride 64"
    "boundary_boxes.first_word: offset 4,[^\n]*topLevelArrayStride 8"
    "instanced_copies.reserved: offset 12,[^\n]*topLevelArrayStride 16"
    "instanced_types.colour: offset 16,[^\n]*topLevelArrayStride 32"
    "instanced_frames.light: offset 96,[^\n]*topLevelArrayStride 112"
    "beads.reserved1: offset 28,[^\n]*topLevelArrayStride 32"
    "bead_ranges.count: offset 4,[^\n]*topLevelArrayStride 8")
  if(NOT out MATCHES "${expect}")
    message(FATAL_ERROR "std430 layout differs from C++: no match for '${expect}' in\n${out}")
  endif()
endforeach()
