#include "glints/glint_mapping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "glints/methods.h"

namespace glimmer {

const char* glintQuantityName(GlintQuantity q) {
    switch (q) {
        case GlintQuantity::Density: return "density_per_uv";
        case GlintQuantity::AngularSize: return "angular_size";
        case GlintQuantity::Alpha: return "alpha";
        case GlintQuantity::Anisotropy: return "anisotropy";
        case GlintQuantity::ColorVariation: return "color_variation";
        case GlintQuantity::ColorR: return "color.r";
        case GlintQuantity::ColorG: return "color.g";
        case GlintQuantity::ColorB: return "color.b";
        case GlintQuantity::Ndf: return "ndf";
    }
    return "?";
}

float glintQuantity(const Material& m, GlintQuantity q) {
    switch (q) {
        case GlintQuantity::Density: return m.glint.density * m.surfacePerUvArea;
        case GlintQuantity::AngularSize: return m.glint.angularSize;
        case GlintQuantity::Alpha: return m.alpha;
        case GlintQuantity::Anisotropy: return m.glint.anisotropy;
        case GlintQuantity::ColorVariation: return m.glint.colorVariation;
        case GlintQuantity::ColorR: return m.glint.color.x;
        case GlintQuantity::ColorG: return m.glint.color.y;
        case GlintQuantity::ColorB: return m.glint.color.z;
        case GlintQuantity::Ndf: return float(int(m.ndf));
    }
    return 0.0f;
}

float mappedValue(const ParamMapping& mapping, const Material& m) {
    double q = glintQuantity(m, mapping.quantity);
    double v = double(mapping.scale) * std::pow(q, double(mapping.power)) *
               std::pow(double(std::max(m.alpha, 1e-4f)), double(mapping.alphaPower));
    if (mapping.log) v = std::log(std::max(v, 1e-30));
    return float(v);
}

static std::string number(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", double(v));
    return text;
}

std::string mappingFormula(const ParamMapping& mapping) {
    // A constant (power 0, no alpha): the mapping switches a knob to a fixed value whatever the material.
    if (mapping.power == 0.0f && mapping.alphaPower == 0.0f && !mapping.log && mapping.minusHalfSquareOf.empty())
        return mapping.param + " = " + number(mapping.scale);
    std::string term = glintQuantityName(mapping.quantity);
    if (mapping.power != 1.0f) term = "(" + term + ")^" + number(mapping.power);
    if (mapping.scale != 1.0f) term = number(mapping.scale) + " " + term;
    if (mapping.alphaPower != 0.0f) term += " alpha^" + number(mapping.alphaPower);
    if (mapping.log) term = "ln(" + term + ")";
    if (!mapping.minusHalfSquareOf.empty()) term += " - " + mapping.minusHalfSquareOf + "^2/2";
    return mapping.param + " = " + term;
}

ParamValues materialParams(const GlintMethod& method, const Material& m, const ParamValues& overrides) {
    ParamValues values;
    for (const ParamSpec& spec : method.params) {
        if (auto it = overrides.find(spec.name); it != overrides.end()) {
            values[spec.name] = it->second;
            continue;
        }
        float v = spec.defaultValue;
        for (const ParamMapping& mapping : method.materialMapping)
            if (mapping.param == spec.name) {
                float mapped = mappedValue(mapping, m);
                v = std::isfinite(mapped) ? std::clamp(mapped, spec.minValue, spec.maxValue) : spec.defaultValue;
            }
        values[spec.name] = v;
    }
    // Log-normal offsets read the other parameter's final value (override, mapped or default).
    for (const ParamMapping& mapping : method.materialMapping) {
        if (mapping.minusHalfSquareOf.empty() || overrides.count(mapping.param)) continue;
        auto sigma = values.find(mapping.minusHalfSquareOf);
        if (sigma == values.end()) continue;
        for (const ParamSpec& spec : method.params)
            if (spec.name == mapping.param) {
                float mapped = mappedValue(mapping, m) - 0.5f * sigma->second * sigma->second;
                values[spec.name] = std::isfinite(mapped) ? std::clamp(mapped, spec.minValue, spec.maxValue) : spec.defaultValue;
            }
    }
    return values;
}

ParamValues sharedParams(const GlintMethod& method, const std::vector<Material>& materials, const ParamValues& overrides) {
    const Material* chosen = nullptr;
    float best = 0.0f;
    for (const Material& m : materials) {
        if (!m.glinty) continue;
        if (method.sharedDataMaterial.empty()) {
            chosen = &m;
            break;
        }
        float v = materialParams(method, m, overrides)[method.sharedDataMaterial];
        if (!chosen || v > best) chosen = &m, best = v;
    }
    return chosen ? materialParams(method, *chosen, overrides) : overrides;
}

}  // namespace glimmer
