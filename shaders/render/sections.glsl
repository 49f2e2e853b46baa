// The package's sections as runtime/render/levels/sections.cpp binds them, looked up where several
// levels need them: the Wang tile a recipe puts at a cell (membrane squares, core and medium cubes).
// From render.comp: recipes, recipe_indices.

uint recipe_cell(uint recipe, ivec3 cell) {
  Recipe r = recipes[recipe];
  ivec3 dims = ivec3(r.dims.xyz);
  ivec3 w = ((cell % dims) + dims) % dims;  // recipes wrap in every direction
  return recipe_indices[r.first_index + uint(w.x) + r.dims.x * (uint(w.y) + r.dims.y * uint(w.z))];
}
