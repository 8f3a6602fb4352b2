// User glint methods: one GLSL file implementing the interface of shaders/glints/README.md, whose header block (a
// GLSL comment, so the file stays valid GLSL) declares name, citation and parameters. The header becomes a
// GlintMethod of the method table (glints/methods.h), so --list-params, --set, the panel, P_<NAME> macros,
// --compare, bench and check-method treat it like a built-in. Format: docs/user_methods.md.
//
//   /* glimmer-method
//   name:      my_glints
//   citation:  where the idea comes from
//   param:     log_density = 16 in [0, 50]: natural log of the facet density per unit UV area
//   param:     blend = smooth in {linear, smooth}: an enumeration (stored as its index)
//   map:       log_density = ln(density_per_uv)   (the glint material's quantity, glint_mapping.h)
//   converge:  log_density=40
//   */
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "glints/methods.h"

namespace glimmer {

// Parses the header block of `text` into a GlintMethod (id, title, citation, parameters, convergence values,
// borrowed resources); shader file and source are left to the caller. Throws Error "<fileLabel>:<line>: message"
// naming the offending line.
GlintMethod parseUserMethodHeader(const std::string& text, const std::string& fileLabel);

// Reads and parses `path` (shaderFile and sourceFile set to its canonical path) without registering it.
GlintMethod readUserMethodFile(const std::filesystem::path& path);

// Reads `path` and registers (or, for a file loaded before, replaces) its method; returns the method's id.
std::string loadUserMethodFile(const std::filesystem::path& path);

// A method named on the command line: a table id, or "file:PATH" (loaded on first use). Returns the id; throws
// UsageError naming `flag` for an unknown id, Error for a bad file.
std::string resolveGlintMethod(const std::string& spec, const std::string& flag = "--method");

// The user method read from `file` (canonical path), or nullptr.
const GlintMethod* userMethodForFile(const std::filesystem::path& file);

// .glsl files of `folder` (sorted) whose first line opens a glimmer-method header: what the panel offers to load.
std::vector<std::filesystem::path> methodFilesIn(const std::filesystem::path& folder);

// Keeps a method's parameter values across a header change: drops the names that no longer exist and clamps the
// others into their new range (enumerations to their choices).
ParamValues carryParamValues(const ParamValues& values, const GlintMethod& method);

}  // namespace glimmer
