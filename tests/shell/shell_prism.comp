#version 460
// shell_prism.h must compile as GLSL (Vulkan 1.2): every function is called once.
#extension GL_GOOGLE_include_directive : require
#include "shared/shell_prism.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Io { vec4 data[]; } io;

void main() {
  uint i = gl_GlobalInvocationID.x;
  ShellOffsets a = ShellOffsets(io.data[i].x, io.data[i].y, io.data[i].z);
  ShellOffsets b = ShellOffsets(io.data[i].w, 1.0f, 2.0f);
  ShellOffsets m = shell_offsets_max(a, b);
  Prism pr = shell_prism_make(io.data[i + 1u].xyz, io.data[i + 2u].xyz, io.data[i + 3u].xyz, vec3(0, 0, 1),
                              vec3(0, 0, 1), vec3(0, 0, 1), m);
  vec3 acc = shell_miter_offset(pr.v[0], pr.v[1], pr.v[2], m.side);
  for (int k = 0; k < 6; ++k) acc += pr.v[k];
  io.data[i] = vec4(acc, m.h_plus);
}
