// Base-colour textures generated in code for the project's own scenes (no image files needed). Each covers
// `periodMetres` of surface and tiles seamlessly; pair it with Material::uvTransform = scale(1 / period) on
// metre UVs. Deterministic (fixed seeds).
#pragma once
#include "scene/scene.h"

namespace glimmer {

// Sandstone ashlar: courses of blocks (0.5 m high, 1 m long, staggered) with mortar joints and per-block tint.
TextureData makeAshlarTexture(int size, float periodMetres);
// Plain weathered limestone: layered value noise, no joints (columns, arches, slabs).
TextureData makeStoneTexture(int size, float periodMetres);
// Floor of square tiles (`tileMetres` wide) alternating two marbles in a checkerboard, with grout lines.
TextureData makeFloorTileTexture(int size, float periodMetres, float tileMetres);

}  // namespace glimmer
