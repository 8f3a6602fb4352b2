// A digest of everything in a scene that shows in an image of it: meshes, textures, materials, instances, lights,
// the sky colour and the environment's name (not cameras, names or file paths). Disk caches of data rendered from
// the scene (the reflection probes: render/probes/reflection_probes.h) key on it, so an edited scene file or model
// never reads a stale cache.
#pragma once
#include <string>

#include "scene/scene.h"

namespace glimmer {

// 16 hex digits (core/cache_file.h ContentHasher). About 30 ms for the atrium's 97k triangles.
std::string sceneContentHash(const Scene& scene);

}  // namespace glimmer
