#include "render/settings.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/files.h"
#include "glints/methods.h"
#include "environment/ibl/ibl_modes.h"

namespace glimmer {

const std::vector<CommonParam>& commonParams() {
    static const std::vector<CommonParam> params = {
        {{"exposure", 0.0f, -16.0f, 16.0f, "exposure in stops before tone mapping; exposure=auto meters the frame (then these stops compensate)"}},
        {{"texture_anisotropy", 16.0f, 1.0f, 16.0f,
          "most anisotropic filtering of mipmapped material textures (1: trilinear; the window on a software "
          "renderer starts at 1)"}},
        {{"ambient", 1.0f, 0.0f, 16.0f, "scale of the constant sky/ambient radiance (when no environment map)"}},
        {{"light.intensity", 1.0f, 0.0f, 1000.0f, "multiplier on every light's intensity"}},
        {{"light.count", 0.0f, 0.0f, 64.0f,
          "number of lights: 0 keeps the scene's; more adds lights around the first one's direction", {}, true}},
        {{"light.turn", 0.0f, -360.0f, 360.0f,
          "turns every light about the world's +y axis through the origin, degrees (glint lifespan measurements)"}},
        {{"light.sun_diameter", 0.53f, 0.0f, 10.0f,
          "angular diameter (degrees) of every directional light: the solid angle its glints count against"}, true},
        {{"light.area_size", 1.0f, 0.1f, 10.0f,
          "scale of every area light's size (rect width and height, disk and sphere radius) at equal intensity"}},
        {{"light.area_intensity", 1.0f, 0.0f, 100.0f, "multiplier on every area light's intensity"}},
        {{"material.alpha", 0.3f, 0.001f, 1.0f, "NDF roughness alpha of every material"}, true},
        {{"material.metallic", 1.0f, 0.0f, 1.0f, "metalness of every material"}, true},
        {{"material.ndf", 0.0f, 0.0f, 1.0f, "microfacet distribution of every material", {"ggx", "beckmann"}}, true},
        {{"material.glinty", 1.0f, 0.0f, 1.0f, "whether every material uses the glint method (0 or 1)", {}, true},
         true},
        {{"material.density_scale", 1.0f, 0.0f, 1e6f, "glint density multiplier of every material", {}, false,
          true},
         true},
        // The glint material (one vocabulary for every method; README "Glint material"), set on every material.
        {{"material.glint_density", 2e6f, 0.0f, 1e14f, "glint facets per square metre of every material", {}, false,
          true},
         true},
        {{"material.glint_angular_size", 0.015f, 0.0005f, 0.5f,
          "gamma: half-angle (radians) of the cone around h in which one facet reflects, every material", {}, false,
          true},
         true},
        {{"material.glint_anisotropy", 1.0f, 1.0f, 64.0f, "stretch of the glints along the tangent, every material"},
         true},
        {{"material.glint_color_variation", 0.0f, 0.0f, 1.0f, "per-glint colour variation of every material"}, true},
        // KHR_materials_clearcoat on every material (0 = no coat; the lighting is then unchanged).
        {{"material.clearcoat", 0.0f, 0.0f, 1.0f, "clear coat layer intensity of every material (KHR_materials_clearcoat)"},
         true},
        {{"material.clearcoat_roughness", 0.0f, 0.0f, 1.0f,
          "clear coat perceptual roughness of every material (alpha = roughness^2)"}, true},
        {{"env.intensity", 1.0f, 0.0f, 100.0f, "multiplier on the environment's radiance (sky and image-based lighting)"}},
        {{"env.rotation", 0.0f, -360.0f, 360.0f,
          "rotation of the environment map about +y in degrees (the procedural sky's sun follows the light)"}},
        // The image pipeline (docs/image.md). Offscreen defaults keep a single frame identical to the plain
        // pipeline (aa=taa starts unjittered, bloom 0, manual exposure); the window switches TAA, bloom and
        // auto exposure on unless they are set.
        {{"aa", 0.0f, 0.0f, 2.0f, "anti-aliasing: off, taa (temporal, jittered) or ssaa (ssaa.factor^2 samples)",
          {"off", "taa", "ssaa"}}},
        {{"ssaa.factor", 4.0f, 2.0f, 8.0f, "aa=ssaa: render at N x the size and box-filter down", {}, true}},
        {{"taa.feedback", 0.1f, 0.02f, 1.0f, "aa=taa: weight of the current frame once the history has converged"}},
        {{"taa.glint_history", 1.0f, 0.0f, 1.0f,
          "aa=taa: 1 keeps glints in their own history (not clipped); 0 clips them with the rest (for comparison)",
          {}, true}},
        {{"taa.stable_glints", 1.0f, 0.0f, 1.0f,
          "aa=taa: 1 evaluates glints at the unjittered pixel centre (a still camera keeps each sparkle); 0 jittered",
          {}, true}},
        {{"lighting.split_glinty", 0.0f, 0.0f, 1.0f,
          "1 shades glinty and other pixels with separate programs (an early depth test picks each pixel's): "
          "pixels of non-glinty materials skip the method's code (the window's default)",
          {}, true}},
        {{"lighting.glint_footprint", 0.0f, 0.0f, 1.0f,
          "below render scale 1: glints filtered over the render pixel's footprint (render) or over the output "
          "pixel's, at each render pixel's centre (output: the sparkle an output pixel shows; the window's default)",
          {"render", "output"}}},
        {{"lod.pixel_error", 0.0f, 0.0f, 8.0f,
          "geometry level of detail: each mesh chunk drawn at the coarsest simplified level whose error stays within "
          "this many pixels of the render size; 0 draws full detail (the window's default on software renderers: 1)"}},
        {{"taa.upsample", 1.0f, 0.0f, 1.0f,
          "aa=taa below render scale 1: 1 resolves to the output size (TAAU); 0 resolves at the render size and the "
          "post passes run there, then a Catmull-Rom upscale (the window's default on software renderers)",
          {}, true}},
        {{"taa.glint_feedback", 0.25f, 0.02f, 1.0f,
          "aa=taa: weight of the current frame in the glint history once converged (higher keeps sparkle peaks)"}},
        {{"bloom.strength", 0.0f, 0.0f, 1.0f, "bloom: weight of the blurred image mixed into the HDR image"}},
        {{"bloom.radius", 1.0f, 0.25f, 4.0f, "bloom: tent radius of each upsample, in texels of its level"}},
        {{"exposure.auto", 0.0f, 0.0f, 1.0f,
          "1: exposure from the luminance histogram (exposure=auto); `exposure` then adds stops", {}, true}},
        {{"tonemap", 0.0f, 0.0f, 2.0f, "tone curve: aces (Narkowicz fit), neutral (Khronos PBR Neutral), agx",
          {"aces", "neutral", "agx"}}},
        // Reflection probes (render/probes/reflection_probes.h, docs/reflection_probes.md), read by the IBL modes that
        // say so (IblMode::readsProbes): prefiltered, ndf-is, glint-is, wang2020.
        {{"probes.enabled", 1.0f, 0.0f, 1.0f,
          "1: metallic objects reflect the scene around them (reflection probes, captured when the scene changes)",
          {}, true}},
        {{"probes.face_size", 128.0f, 16.0f, 512.0f, "face size of each reflection probe's cube map", {}, true}},
        {{"probes.max", 8.0f, 0.0f, 8.0f, "most reflection probes (one per metallic instance, in scene order)", {},
          true}},
        // Ambient occlusion of the environment / ambient term (docs/ambient_occlusion.md).
        {{"ao.enabled", 1.0f, 0.0f, 1.0f, "ambient occlusion of the environment / ambient term (0 or 1)", {}, true}},
        {{"ao.screen", 1.0f, 0.0f, 1.0f, "screen-space GTAO, the small scale (0 or 1)", {}, true}},
        {{"ao.sky", 1.0f, 0.0f, 1.0f, "baked sky visibility, the large scale (0 or 1)", {}, true}},
        {{"ao.radius", 1.0f, 0.05f, 10.0f, "GTAO search radius in metres"}},
        {{"ao.power", 1.0f, 0.0f, 4.0f, "intensity: the combined visibility is raised to this power"}},
        {{"ao.slices", 2.0f, 1.0f, 16.0f, "GTAO slices per pixel", {}, true}},
        {{"ao.steps", 4.0f, 1.0f, 32.0f, "GTAO horizon-search steps per side of a slice", {}, true}},
        {{"ao.falloff", 0.8f, 0.0f, 0.99f, "fraction of the radius after which occluders fade out"}},
        {{"ao.denoise", 1.0f, 0.0f, 1.0f, "4x4 depth-aware denoise of the GTAO term (0 or 1)", {}, true}},
        {{"ao.half_res", 0.0f, 0.0f, 1.0f,
          "GTAO and its resolve at every second pixel, interpolated by depth and plane (0: every pixel)"}},
        {{"ao.multibounce", 1.0f, 0.0f, 1.0f, "GTAO multi-bounce fit with the surface albedo (0 or 1)", {}, true}},
        {{"ao.sky_cell", 0.5f, 0.1f, 4.0f, "probe spacing of the sky-visibility bake in metres (grown for large scenes)"}},
        {{"ao.sky_rays", 64.0f, 8.0f, 1024.0f, "rays per probe of the sky-visibility bake (upper hemisphere)", {}, true}},
        // Shadows (render/shadows/shadow_maps.h, docs/shadows.md).
        {{"shadow.enabled", 1.0f, 0.0f, 1.0f, "shadow maps for the sun (cascades) and point lights (cube faces), 0 or 1",
          {}, true}},
        {{"shadow.map_size", 2048.0f, 256.0f, 4096.0f, "texels per side of each sun cascade", {}, true}},
        {{"shadow.cascades", 3.0f, 1.0f, 4.0f, "number of sun cascades over shadow.distance", {}, true}},
        {{"shadow.filter_radius", 1.5f, 0.0f, 4.0f, "PCF filter radius in texels (0: one bilinear compare)"}},
        {{"shadow.bias", 0.5f, 0.0f, 8.0f, "receiver depth bias towards the light, in texels"}},
        {{"shadow.normal_bias", 0.5f, 0.0f, 8.0f, "receiver offset along the normal, texels x sin(normal, light)"}},
        {{"shadow.slope_bias", 3.0f, 0.0f, 16.0f, "slope-scaled depth bias of the casters (glPolygonOffset factor)"}},
        {{"shadow.distance", 40.0f, 1.0f, 1000.0f, "view depth (m) the sun's cascades cover; beyond it no sun shadow"}},
        {{"shadow.point_map_size", 512.0f, 64.0f, 2048.0f,
          "texels per side of each cube face of a point light and of a spot light's view", {}, true}},
        {{"shadow.half_res", 0.0f, 0.0f, 1.0f,
          "filter the shadow maps at every second pixel, interpolated by depth and plane (0: every pixel)"}},
        {{"shadow.cache", 1.0f, 0.0f, 1.0f,
          "reuse shadow maps while geometry, light and the needed region are unchanged (0: render every frame)", {},
          true}},
    };
    return params;
}

const std::vector<ParamSpec>& lightEditParams() {
    static const std::vector<ParamSpec> params = {
        {"on", 1.0f, 0.0f, 1.0f, "1 lights with this light, 0 switches it off", {}, true},
        {"intensity", 1.0f, 0.01f, 100.0f, "multiplier on this light's intensity", {}, false, true},
        {"size", 1.0f, 0.1f, 10.0f,
         "scale of this light's size: rect width and height, disk and sphere radius, a punctual light's radius, "
         "the sun's angular diameter",
         {}, false, true},
        {"turn", 0.0f, -180.0f, 180.0f,
         "turns this light about the world's +y axis through its own centre, degrees: a directional light's "
         "direction, a spot's axis, a rect's or disk's facing"},
    };
    return params;
}

std::string lightEditKey(int lightNumber, const std::string& field) {
    return "light." + std::to_string(lightNumber) + "." + field;
}

int lightEditNumber(const std::string& key) {
    if (key.rfind("light.", 0) != 0) return 0;
    size_t end = key.find('.', 6);
    if (end == std::string::npos || end == 6 || end - 6 > 2) return 0;
    int number = 0;
    for (size_t i = 6; i < end; ++i) {
        if (key[i] < '0' || key[i] > '9') return 0;
        number = number * 10 + (key[i] - '0');
    }
    return number;
}

static const ParamSpec* findLightEdit(const std::string& key) {
    size_t dot = key.find('.', 6);
    for (const ParamSpec& spec : lightEditParams())
        if (key.compare(dot + 1, std::string::npos, spec.name) == 0) return &spec;
    return nullptr;
}

void clearLightEdits(RenderSettings& settings) {
    for (auto it = settings.common.begin(); it != settings.common.end();)
        it = lightEditNumber(it->first) > 0 ? settings.common.erase(it) : std::next(it);
}

static const CommonParam* findCommon(const std::string& name) {
    for (const CommonParam& p : commonParams())
        if (p.spec.name == name) return &p;
    return nullptr;
}

float RenderSettings::value(CommonParamKey key) const {
    const CommonParam* p = findCommon(key.name);
    if (!p) throw Error(std::string("internal: unknown common parameter ") + key.name);
    return paramOr(common, p->spec);
}

const ParamValues& RenderSettings::methodValues(const std::string& id) const {
    static const ParamValues empty;
    auto it = methods.find(id);
    return it == methods.end() ? empty : it->second;
}

const ParamValues& RenderSettings::iblModeValues(const std::string& id) const {
    static const ParamValues empty;
    auto it = iblValues.find(id);
    return it == iblValues.end() ? empty : it->second;
}

void RenderSettings::apply(const std::string& assignment) {
    size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("--set: expected KEY=VALUE, got '" + assignment + "'");
    std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
    if (key == "exposure") {
        // exposure=auto | EV: a number keeps its old meaning (manual stops); auto turns the histogram on.
        if (value == "auto") {
            common["exposure.auto"] = 1.0f;
            return;
        }
        common["exposure.auto"] = 0.0f;
    }
    if (const CommonParam* p = findCommon(key)) {
        common[key] = parseParamValue(p->spec, value, "--set", key);
        return;
    }
    if (int number = lightEditNumber(key); number > 0 || key.rfind("light.", 0) == 0) {
        const ParamSpec* spec = number > 0 ? findLightEdit(key) : nullptr;
        if (!spec || number > kMaxEditedLights) {
            std::string fields;
            for (const ParamSpec& s : lightEditParams()) fields += (fields.empty() ? "" : "|") + s.name;
            throw UsageError("--set: unknown parameter '" + key + "' (a light's own edit is light.<1.." +
                             std::to_string(kMaxEditedLights) + ">.<" + fields + ">; see glimmer render --list-params)");
        }
        common[key] = parseParamValue(*spec, value, "--set", key);
        return;
    }
    if (key.rfind("ibl.", 0) == 0) {
        const IblMode& mode = findIblMode(ibl);
        std::string name = key.substr(4);
        for (const ParamSpec& spec : mode.params)
            if (spec.name == name) {
                iblValues[ibl][name] = parseParamValue(spec, value, "--set", key);
                return;
            }
        throw UsageError("--set: unknown parameter '" + key + "' for --ibl " + ibl +
                         " (give --ibl before --set; see glimmer render --list-params)");
    }
    std::string methodId = method, name = key;
    if (size_t dot = key.find('.'); dot != std::string::npos) {
        methodId = key.substr(0, dot);
        name = key.substr(dot + 1);
        bool known = false;
        for (const GlintMethod& m : glintMethods()) known |= m.id == methodId;
        if (!known) throw UsageError("--set: unknown parameter '" + key + "' (see glimmer render --list-params)");
    }
    const GlintMethod& m = findGlintMethod(methodId);
    for (const ParamSpec& spec : m.params)
        if (spec.name == name) {
            methods[methodId][name] = parseParamValue(spec, value, "--set", key);
            return;
        }
    throw UsageError("--set: unknown parameter '" + key + "' for method " + methodId +
                     " (see glimmer render --list-params)");
}

// v turned about the world's +y axis by `degrees` (light.turn and a light's own turn).
static glm::vec3 turnedAboutY(glm::vec3 v, float degrees) {
    const float c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

// Each light's own edits (lightEditParams), then the switched-off lights leave the scene.
static void applyLightEdits(const RenderSettings& settings, Scene& scene) {
    std::vector<bool> off(scene.lights.size(), false);
    bool anyOff = false;
    for (const auto& [key, value] : settings.common) {
        int number = lightEditNumber(key);
        if (number <= 0) continue;
        if (size_t(number) > scene.lights.size())
            throw UsageError("--set " + key + ": scene " + scene.name + " has " + std::to_string(scene.lights.size()) +
                             " light" + (scene.lights.size() == 1 ? "" : "s"));
        Light& light = scene.lights[size_t(number - 1)];
        const std::string field = key.substr(key.find('.', 6) + 1);
        if (field == "on") {
            off[size_t(number - 1)] = value < 0.5f;
            anyOff |= value < 0.5f;
        } else if (field == "intensity") {
            light.intensity *= value;
        } else if (field == "size") {
            light.width *= value;
            light.height *= value;
            light.radius *= value;
            if (light.type == LightType::Directional) light.angularDiameter *= value;
        } else if (field == "turn" && value != 0.0f) {
            if (light.type == LightType::Directional) light.vector = turnedAboutY(light.vector, value);
            light.spotDirection = turnedAboutY(light.spotDirection, value);
            light.right = turnedAboutY(light.right, value);
        }
    }
    if (!anyOff) return;
    std::vector<Light> kept;
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (!off[i]) kept.push_back(scene.lights[i]);
    scene.lights = std::move(kept);
}

void applySceneOverrides(const RenderSettings& settings, Scene& scene) {
    for (Material& m : scene.materials) {
        if (settings.isSet(param::material_alpha)) m.alpha = settings.value(param::material_alpha);
        if (settings.isSet(param::material_metallic)) m.metallic = settings.value(param::material_metallic);
        if (settings.isSet(param::material_ndf)) m.ndf = static_cast<NdfType>(int(settings.value(param::material_ndf)));
        if (settings.isSet(param::material_glinty)) m.glinty = settings.value(param::material_glinty) > 0.5f;
        if (settings.isSet(param::material_density_scale))
            m.glintDensityScale = settings.value(param::material_density_scale);
        if (settings.isSet(param::material_glint_density)) m.glint.density = settings.value(param::material_glint_density);
        if (settings.isSet(param::material_glint_angular_size))
            m.glint.angularSize = settings.value(param::material_glint_angular_size);
        if (settings.isSet(param::material_glint_anisotropy)) m.glint.anisotropy = settings.value(param::material_glint_anisotropy);
        if (settings.isSet(param::material_glint_color_variation))
            m.glint.colorVariation = settings.value(param::material_glint_color_variation);
        if (settings.isSet(param::material_clearcoat)) m.clearcoat = settings.value(param::material_clearcoat);
        if (settings.isSet(param::material_clearcoat_roughness))
            m.clearcoatRoughness = settings.value(param::material_clearcoat_roughness);
    }
    float scale = settings.value(param::light_intensity);
    const float areaSize = settings.value(param::light_area_size), areaIntensity = settings.value(param::light_area_intensity);
    for (Light& light : scene.lights) {
        light.intensity *= scale;
        if (light.type == LightType::Directional && settings.isSet(param::light_sun_diameter))
            light.angularDiameter = glm::radians(settings.value(param::light_sun_diameter));
        if (light.isArea()) {
            light.intensity *= areaIntensity;
            light.width *= areaSize;
            light.height *= areaSize;
            light.radius *= areaSize;
        }
    }
    applyLightEdits(settings, scene);   // after light.sun_diameter, which a light's own size then scales
    int wanted = int(settings.value(param::light_count));
    if (wanted > 0 && !scene.lights.empty()) {
        // Extra lights circle the first one's direction at the same elevation, so every light shades the view.
        Light first = scene.lights.front();
        scene.lights.resize(1);
        for (int i = 1; i < wanted; ++i) {
            Light extra = first;
            float angle = 0.35f * float(i);
            glm::vec3 v = first.vector;
            extra.vector = first.type == LightType::Directional
                               ? glm::normalize(glm::vec3(v.x * std::cos(angle) - v.z * std::sin(angle), v.y,
                                                          v.x * std::sin(angle) + v.z * std::cos(angle)))
                               : v + glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
            scene.lights.push_back(extra);
        }
    }
    if (float turn = settings.value(param::light_turn); turn != 0.0f) {
        // After light.count, so added lights turn with the first. Directions and positions alike (a point light
        // circles the y axis), so h moves the same way everywhere.
        for (Light& light : scene.lights) {
            light.vector = turnedAboutY(light.vector, turn);
            light.spotDirection = turnedAboutY(light.spotDirection, turn);
            light.right = turnedAboutY(light.right, turn);   // an area light's width axis
        }
    }
}

std::string describeParams() {
    std::ostringstream out;
    auto line = [&](const std::string& key, const ParamSpec& spec, bool sceneDefault) {
        out << "  " << key;
        for (size_t i = key.size(); i < 28; ++i) out << ' ';
        out << " default " << (sceneDefault ? std::string("scene") : formatParamValue(spec, spec.defaultValue));
        if (spec.choices.empty())
            out << "  range [" << spec.minValue << ", " << spec.maxValue << "]";
        else {
            out << "  one of";
            for (const auto& c : spec.choices) out << ' ' << c;
        }
        out << "  " << spec.meaning << "\n";
    };
    out << "Common parameters (--set KEY=VALUE):\n";
    for (const CommonParam& p : commonParams()) line(p.spec.name, p.spec, p.sceneDefault);
    out << "\nOne light's own edits (--set light.<N>.<field>, N = 1.." << kMaxEditedLights
        << ": the scene's lights in order, as the window's panel numbers them):\n";
    for (const ParamSpec& spec : lightEditParams()) line("light.<N>." + spec.name, spec, false);
    for (const GlintMethod& m : glintMethods()) {
        out << "\nMethod " << m.id << (m.isUserMethod() ? " (user method, " + displayPath(m.sourceFile) + ")" : "") << ": "
            << m.title << " [" << m.citation << "]\n";
        if (m.params.empty()) out << "  (no parameters)\n";
        for (const ParamSpec& spec : m.params) {
            line(m.id + "." + spec.name, spec, false);
            for (const ParamMapping& mapping : m.materialMapping)
                if (mapping.param == spec.name)
                    out << "      per material: " << mappingFormula(mapping) << " (" << mapping.why
                        << "); --set overrides it on every material\n";
        }
        if (!m.sharedDataMaterial.empty())
            out << "  shared GPU data are built for the glinty material with the largest " << m.sharedDataMaterial << "\n";
    }
    for (const IblMode& m : iblModes()) {
        out << "\nIBL mode " << m.id << (m.accumulates ? " (accumulates --spp samples)" : "") << ": " << m.title
            << " [" << m.citation << "]\n";
        if (m.params.empty()) out << "  (no parameters)\n";
        for (const ParamSpec& spec : m.params) line("ibl." + spec.name, spec, false);
    }
    return out.str();
}

}  // namespace glimmer
