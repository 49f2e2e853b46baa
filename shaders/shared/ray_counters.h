// Work counters per pixel (`nanoview bench --counters`): what a pixel's rays cost at each level of
// the traversal, counted by render.comp and instanced.comp only when their counters specialization
// constant is on (a frame without it has no counter code at all). One row of NANO_RAY_COUNTER_COUNT
// words per pixel, summed over every ray the pixel traces (primary, shadow, AO).
#ifndef NANO_RAY_COUNTERS_H
#define NANO_RAY_COUNTERS_H

#include "glsl_cpp.h"

NANO_BEGIN

NANO_CONST uint NANO_RC_ULAS_QUERIES = 0u;      // top-level queries started (µLAS; explicit: its TLAS)
NANO_CONST uint NANO_RC_ULAS_CANDIDATES = 1u;   // top-level candidates met (prism and core boxes; explicit: atom boxes)
NANO_CONST uint NANO_RC_PRISM_TESTS = 2u;       // shell prisms reached (exact test, or AABB only)
NANO_CONST uint NANO_RC_PRISMS_ENTERED = 3u;    // prisms whose test passed
NANO_CONST uint NANO_RC_REPLAS_QUERIES = 4u;    // replication-area queries started
NANO_CONST uint NANO_RC_SLOTS_TRIED = 5u;       // replication slots tried (repLAS candidates, or every slot)
NANO_CONST uint NANO_RC_MLAS_QUERIES = 6u;      // molecule-level queries started (membrane tiles and core cubes)
NANO_CONST uint NANO_RC_MLAS_CANDIDATES = 7u;   // molecule candidates met
NANO_CONST uint NANO_RC_OWNERSHIP_REJECTS = 8u; // membrane candidates another triangle owns, or the seam rule drops
NANO_CONST uint NANO_RC_LISTED_REJECTS = 9u;    // membrane candidates the baker's drop list removes
NANO_CONST uint NANO_RC_NLAS_QUERIES = 10u;     // atom-level queries started
NANO_CONST uint NANO_RC_NLAS_CANDIDATES = 11u;  // atom candidates met
NANO_CONST uint NANO_RC_SPHERE_TESTS = 12u;     // exact ray–sphere tests
NANO_CONST uint NANO_RC_CORE_STEPS = 13u;       // core-grid DDA steps
NANO_CONST uint NANO_RC_CORE_BOXES = 14u;       // core boxes traced (inside the grid, not yet traced)
NANO_CONST uint NANO_RC_MASK_REJECTS = 15u;     // soluble candidates a boundary box's keep mask removes
NANO_CONST uint NANO_RC_FLAT_QUERIES = 16u;     // queries of the flat level (copies of flattened compartment instances)
NANO_CONST uint NANO_RC_FLAT_CANDIDATES = 17u;  // atom candidates the flat level met
NANO_CONST uint NANO_RC_MEDIUM_STEPS = 18u;        // medium DDA steps (its region's boxes)
NANO_CONST uint NANO_RC_MEDIUM_KEEP_QUERIES = 19u;  // keep-rule queries of the exclusion structure (copies whose sphere the ray meets)
NANO_CONST uint NANO_RC_MEDIUM_REJECTS = 20u;       // medium candidates an instance's exclusion field removes
NANO_CONST uint NANO_RAY_COUNTER_COUNT = 21u;

NANO_END

#endif
