// Scene files: the small JSON format of content/*.json (documented in content/README.md). A file may start
// from a generated scene ("base"), add generated meshes and glTF models, and set materials (with glint
// parameters), lights, cameras, the walkthrough order and the environment.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace glimmer {

// Throws glimmer::Error naming the file (and the offending key) on missing, malformed or inconsistent input.
Scene loadSceneFile(const std::filesystem::path& path);

// Only the "methodFiles" of a scene file (paths resolved against its folder); empty when the file does not parse.
std::vector<std::string> readSceneMethodFiles(const std::filesystem::path& path);

}  // namespace glimmer
