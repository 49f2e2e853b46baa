#pragma once
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// Replaces the mesh's normals by angle-weighted vertex normals (Thürmer & Wüthrich): each
// triangle contributes its unit normal weighted by its interior angle at the vertex, so the
// result does not depend on how a region is split into triangles. One normal per position;
// normal_triangles becomes a copy of triangles. Degenerate triangles contribute nothing; a
// vertex with no usable triangle gets +z so that no NaN ever reaches the shell builder.
void compute_angle_weighted_normals(ProxyMesh& mesh);

}  // namespace nano::mesh

namespace nano::mesh {

// How fast the interpolated normal field n(x) = normalize(Σ λ_i n_i) turns across the surface: the
// largest, over triangles with a usable shape, of ‖∂(Σ λ_i n_i)/∂x‖ (the 3×2 gradient of the linear
// interpolant in the triangle's plane, largest singular value) divided by the smallest length that
// interpolant can take there (≥ min over corner pairs of |n_i + n_j| / 2, the normalisation only
// speeds the turn up by that factor). Radians per Å; 1/R on a fine sphere of radius R. A copy at
// height h above the surface sees lateral offsets scaled by at most 1 ± h·rate.
double normal_turn_rate(const ProxyMesh& mesh);
// The same over triangle t alone; 0 when the triangle gives no bound (degenerate, opposite normals).
double triangle_turn_rate(const ProxyMesh& mesh, std::size_t t);

// tan of the largest angle between a corner normal and its triangle's face normal, over triangles
// with a usable shape (an interpolated normal lies within that angle of the face normal). Copies
// stand along the interpolated normal while their centres spread over the flat triangle, so seen
// from a copy a neighbour p Å away sits up to tan·p Å above or below it.
double largest_normal_tilt(const ProxyMesh& mesh);

// The same for copies placed on the smooth surface of shape factor `smooth` (chart_smooth_position,
// Phong tessellation of the corner normals) instead of the flat triangle: tan of the largest angle
// between the interpolated normal and that surface's own normal, sampled on a barycentric grid of
// every triangle with a usable shape (corners, edges and inside). smooth = 0 gives the flat tilt.
double largest_smooth_normal_tilt(const ProxyMesh& mesh, double smooth);
// The same over triangle t alone (0 for a degenerate triangle).
double triangle_smooth_normal_tilt(const ProxyMesh& mesh, std::size_t t, double smooth);

// How far a flat triangle strays from the smooth surface its corner normals describe, largest over
// triangles: ρ²·rate/2 with ρ the largest corner distance from the centroid and rate the
// triangle's normal turn rate (a sphere's facet sags ρ²/(2R) below it). Two copies' rises from the
// tilt differ by at most about this much however far apart they are (Å).
double largest_facet_sag(const ProxyMesh& mesh);
// The same for triangle t alone.
double triangle_facet_sag(const ProxyMesh& mesh, std::size_t t);

// Area of the surface the mesh's triangles sweep when each corner moves `distance` Å along its
// corner normal (the direction the shells stand copies along): where a leaflet lying that far out
// (negative: in) from the mesh really spreads. ((R + d) / R)² of the mesh's area on a sphere of
// radius R whose corner normals are radial (to 1e-8 here). The mesh's own area without normals.
double offset_surface_area(const ProxyMesh& mesh, double distance);

}  // namespace nano::mesh
