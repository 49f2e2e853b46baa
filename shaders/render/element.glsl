// The mLAS element, shared by the membrane and core levels: what their walks (membrane.glsl,
// core.glsl) hand trace_element (element_trace.glsl), declared before all three. The element's mLAS
// is a Wang square's (runtime/render/levels/membrane.cpp) or a Wang cube's (levels/core.cpp).
// From render.comp: nothing (types and a declaration only).

// One µLAS candidate is a prism (its membrane copies, tile by tile of the triangle's replication area)
// or a core grid (its soluble copies, box by box). Both are walked by one loop that yields elements —
// a replication slot or a core-grid box — and every element is traced by the one mLAS query of
// trace_element, which calls the one nLAS query of trace_molecule. Each ray-query loop thus appears
// once in the shader: a driver inlines every call, and a traversal loop is the bulk of the compiled
// code (issue #26: 11 to 22 inlined loops took 9–29 s to compile on lavapipe).
const uint kWalkSlotBoxes = 0u;  // a small replication area: each slot's box by a slab test
const uint kWalkRepLas = 1u;     // the slots the area's repLAS query meets
const uint kWalkAllSlots = 2u;   // every slot (no repLAS: bench knob)

// What a prism's slots share: the triangle, its chart, the ray's part inside the prism [t_lo, t_hi]
// (where every copy the prism owns lies) and the replication area.
struct ShellWalk {
  MembraneTriangle mt;
  TriangleChart chart;
  float t_lo;
  float t_hi;
  ivec2 origin;  // the area's first tile
  ivec2 extent;  // its slots, x by y
  uint mode;     // kWalkSlotBoxes, kWalkRepLas or kWalkAllSlots
  vec3 ot;       // the ray in the origin tile's space (slot boxes, repLAS)
  vec3 dt;
  uint squares;  // the triangle's distortion class: its first square mLAS, relative to frame.levels.x
  mat3 lift;             // the smooth surface's lift (chart_smooth_lift_coefficients); zero: not sheared
  mat3 lift_directions;  // chart_lift_directions
};

// Where the copies of one element can be hit: its mLAS (`entry` in `levels`) and its tile's first
// molecule instance, the ray in the tile's space on [q_lo, q_hi], and what the copies' placement needs.
struct ElementQuery {
  uint entry;
  uint first;
  vec3 ot;
  vec3 dt;
  float q_lo;
  float q_hi;
  vec2 g;        // membrane: the tile's UV origin
  vec3 box_min;  // core: the box's corner
  uint mask;     // core: the boundary box's keep-mask
};

// Defined in element_trace.glsl, after both levels' element queries it calls; declared here so the
// membrane and core walks, included before it, can call it.
bool trace_element(uint inst, uint ci, Compartment c, RenderCompartment rc, bool membrane, uint tl, ShellWalk w,
                   uint slot_or_box, ivec3 cell, vec3 o, vec3 d);
