// From the one glint material (scene/scene.h GlintMaterial, physical units) to each method's own parameters.
// A method's table entry lists ParamMapping rows; each says which physical quantity feeds which parameter and by
// which formula, so a method declared in data (a method file) can state its mapping the same way. `--set`
// values of a method parameter override the mapped value on every material.
#pragma once
#include <string>
#include <vector>

#include "core/params.h"
#include "scene/scene.h"

namespace glimmer {

struct GlintMethod;

// The physical quantities a mapping can read (names as in the glTF extension, content/README.md).
enum class GlintQuantity {
    Density,          // facets per unit UV area = GlintMaterial::density x Material::surfacePerUvArea
    AngularSize,      // gamma, radians
    Alpha,            // the material's NDF roughness alpha
    Anisotropy,
    ColorVariation,
    ColorR,
    ColorG,
    ColorB,
    Ndf,              // the material's base NDF as its NdfType index (0 GGX, 1 Beckmann): for an enumeration
};

// value = scale x q^power x alpha^alphaPower, then ln(value) when `log` (e.g. deliot2023's log density), minus
// half the square of parameter `minusHalfSquareOf` when set, then clamped into the parameter's range (so a material outside a method's range renders at its nearest value).
struct ParamMapping {
    std::string param;
    GlintQuantity quantity = GlintQuantity::Density;
    float scale = 1.0f;
    float power = 1.0f;
    float alphaPower = 0.0f;
    bool log = false;
    std::string why;   // the paper's definition the formula follows (for --list-params and the docs)
    // When set, the mapped value is the log-median of a log-normal whose sigma is this other parameter: value -=
    // sigma^2 / 2, so that the mean of exp(value) is the quantity (deliot2023's density randomization).
    std::string minusHalfSquareOf;
};

// Name of a quantity as written in formulas and method files ("density_per_uv", "angular_size", ...).
const char* glintQuantityName(GlintQuantity q);
// The quantity's value for a material.
float glintQuantity(const Material& m, GlintQuantity q);
// One mapping evaluated for a material (before the range clamp).
float mappedValue(const ParamMapping& mapping, const Material& m);
// "log_density = ln(density)" style text of a mapping.
std::string mappingFormula(const ParamMapping& mapping);

// Every parameter of `method` for material `m`: the --set override if given, else the mapped value (clamped to
// the parameter's range), else the parameter's default.
ParamValues materialParams(const GlintMethod& method, const Material& m, const ParamValues& overrides);

// The values the method's shared GPU data (tables, trees) are built from: those of the glinty material chosen by
// GlintMethod::sharedDataMaterial (see there), or the overrides alone when no material is glinty.
ParamValues sharedParams(const GlintMethod& method, const std::vector<Material>& materials, const ParamValues& overrides);

}  // namespace glimmer
