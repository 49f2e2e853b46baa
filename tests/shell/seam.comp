#version 460
// seam.h must compile as GLSL (Vulkan 1.2): every function is called once.
#extension GL_GOOGLE_include_directive : require
#include "shared/seam.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Io { vec4 data[]; } io;

void main() {
  uint i = gl_GlobalInvocationID.x;
  float d = seam_point_segment_distance(io.data[i].xyz, io.data[i + 1u].xyz, io.data[i + 2u].xyz);
  bool drop = seam_drops(floatBitsToUint(io.data[i].w), io.data[i + 1u].xyz, io.data[i + 2u].xyz, io.data[i + 3u].xyz,
                         io.data[i + 4u].xyz, io.data[i + 4u].w);
  io.data[i] = vec4(d, drop ? 1.0f : 0.0f, 0.0f, 0.0f);
}
