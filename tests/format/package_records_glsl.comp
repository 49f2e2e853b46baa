// Compiles shaders/shared/package_records.h and instanced_records.h as GLSL: every record type in an
// std430 buffer.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/package_records.h"
#include "shared/instanced_records.h"

layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Molecules { MoleculeType molecules[]; };
layout(std430, binding = 1) readonly buffer Atoms { Atom atoms[]; };
layout(std430, binding = 2) readonly buffer Tiles2 { Tile2D tiles2d[]; };
layout(std430, binding = 3) readonly buffer Tiles3 { Tile3D tiles3d[]; };
layout(std430, binding = 4) readonly buffer Instances { MoleculeInstance instances[]; };
layout(std430, binding = 5) readonly buffer Recipes { Recipe recipes[]; };
layout(std430, binding = 6) readonly buffer Meshes { Mesh meshes[]; };
layout(std430, binding = 7) readonly buffer Triangles { Triangle triangles[]; };
layout(std430, binding = 8) readonly buffer Shells { TriangleShell shells[]; };
layout(std430, binding = 9) readonly buffer Compartments { Compartment compartments[]; };
layout(std430, binding = 10) readonly buffer Scene { SceneSettings scene[]; };
layout(std430, binding = 11) readonly buffer CInstances { CompartmentInstance compartment_instances[]; };
layout(std430, binding = 12) readonly buffer BoundaryBoxes { BoundaryBox boundary_boxes[]; };
layout(std430, binding = 13) writeonly buffer Out { uint sink[]; };
layout(std430, binding = 14) readonly buffer ICopies { InstancedCopy instanced_copies[]; };
layout(std430, binding = 15) readonly buffer ITypes { InstancedType instanced_types[]; };
layout(std430, binding = 16) readonly buffer IFrames { InstancedFrameRecord instanced_frames[]; };
layout(std430, binding = 17) readonly buffer Beads { Bead beads[]; };
layout(std430, binding = 18) readonly buffer BeadRanges { BeadRange bead_ranges[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  sink[i] = molecules[i].reserved1 + floatBitsToUint(atoms[i].centre_radius.w) + tiles2d[i].reserved1 +
            tiles3d[i].reserved1 + instances[i].reserved2 + recipes[i].reserved1 + meshes[i].triangle_count +
            triangles[i].v2 + shells[i].seam_edges + compartments[i].reserved0 + compartments[i].core_masks.w +
            scene[i].reserved2 + compartment_instances[i].reserved2 + boundary_boxes[i].first_word + NANO_NO_INDEX +
            instanced_copies[i].reserved + floatBitsToUint(instanced_types[i].colour.w) +
            floatBitsToUint(instanced_frames[i].light.w) + beads[i].reserved1 + bead_ranges[i].count;
}
