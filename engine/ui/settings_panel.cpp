#include "ui/settings_panel.h"

#include "glints/glint_mapping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/files.h"
#include "render/aov.h"
#include "environment/ibl/ibl_modes.h"
#include "ui/font.h"

namespace glimmer::ui {

PanelLayout panelLayout(int width, int height, int statsLines) {
    PanelLayout layout;
    layout.scale = height >= 600 ? 2 : 1;
    layout.margin = float(4 * layout.scale);
    layout.x = layout.y = layout.margin;
    float line = float((kCellHeight + 2) * layout.scale);
    float statsHeight = float(statsLines) * line + 2.0f * layout.margin;
    layout.maxHeight = float(height) - statsHeight - 2.0f * layout.margin;
    return layout;
}

ParamSpec moveSpeedSpec() {
    ParamSpec spec;
    spec.name = "move speed m/s";
    spec.defaultValue = 1.0f;
    spec.minValue = 0.01f;
    spec.maxValue = 100.0f;
    spec.logScale = true;
    return spec;
}

// Parameter prefixes shown together in one section, so the closed panel keeps few headers and fits at 1280x720.
static std::string sectionOfPrefix(const std::string& prefix) {
    if (prefix == "ssaa" || prefix == "taa" || prefix == "bloom" || prefix == "exposure" || prefix == "lod" ||
        prefix == "lighting")
        return "";
    if (prefix == "probes" || prefix == "ao") return "env";
    if (prefix == "shadow") return "light";   // prefixOf already files shadow.* under the lights; the title too
    return prefix;
}

std::string commonGroupTitle(const std::string& prefix) {
    const std::string section = sectionOfPrefix(prefix);
    if (section.empty()) return "Image, anti-aliasing, bloom";
    if (section == "light") return "Lights";
    if (section == "env") return "Environment, occlusion, probes";
    if (section == "material") return "Material overrides (all)";
    return section;
}

// Parameters of the sky-visibility bake: each change re-bakes the scene for seconds, so they are set with
// --set (or a scene file), not dragged; the panel then has room for the interactive ones at 1280x720.
// The GTAO sampling and filter switches likewise (slices, steps, falloff, denoise, multi-bounce), and the shadow
// maps' sizes and cache switch; the texture filtering cap, the geometry level of detail, the split lighting and
// the TAA upsampling switch (per-machine choices the window sets for its renderer). The shadow biases are the
// scene's (acne against peter-panning, tuned once per scene file): their rows made room for one light's own edits.
bool panelHidesParameter(const std::string& name) {
    static const char* const names[] = {"ao.sky_cell", "ao.sky_rays", "ao.slices",      "ao.steps",
                                        "ao.falloff",  "ao.denoise",  "ao.multibounce", "ssaa.factor",
                                        "taa.glint_history", "taa.stable_glints", "shadow.map_size",
                                        "shadow.point_map_size", "shadow.cache", "texture_anisotropy",
                                        "lod.pixel_error", "lighting.split_glinty", "taa.upsample",
                                        "lighting.glint_footprint",
                                        "shadow.bias", "shadow.normal_bias", "shadow.slope_bias"};
    for (const char* n : names)
        if (name == n) return true;
    return false;
}

// A method parameter fed by the material's base NDF (wang2020's `ndf`): the material overrides section edits
// that NDF (material.ndf) for every method at once, and a second control for it would push the last section
// header off a 720-line window (PanelFit). `--set <method>.ndf` still works.
static bool panelHidesMethodParameter(const GlintMethod& method, const std::string& name) {
    for (const ParamMapping& m : method.materialMapping)
        if (m.param == name && m.quantity == GlintQuantity::Ndf) return true;
    return false;
}

const char* methodParameterValueText(const GlintMethod& method, const RenderSettings& settings,
                                     const std::string& name) {
    auto values = settings.methods.find(method.id);
    if (values != settings.methods.end() && values->second.count(name)) return nullptr;
    for (const ParamMapping& m : method.materialMapping)
        if (m.param == name) return "material";
    return nullptr;
}

std::string panelMethodTitle(const std::string& title, int uiScale) {
    const float room = float((kPanelWidthChars * kCellWidth - 8) * uiScale);
    if (float(textWidth(title, uiScale)) <= room) return title;
    size_t bracket = title.find(" (");
    return bracket == std::string::npos ? title : title.substr(0, bracket);
}

std::vector<std::string> lightSelectorNames(const std::vector<Light>& lights) {
    std::vector<std::string> names;
    for (size_t i = 0; i < lights.size() && i < size_t(kMaxEditedLights); ++i) {
        const Light& l = lights[i];
        const char* kind = "";
        switch (l.type) {
            case LightType::Directional: kind = "sun"; break;
            case LightType::Point: kind = "point"; break;
            case LightType::Spot: kind = "spot"; break;
            case LightType::Rect: kind = "rect"; break;
            case LightType::Disk: kind = "disk"; break;
            case LightType::Sphere: kind = "sphere"; break;
        }
        char text[64];
        if (l.type == LightType::Directional)
            std::snprintf(text, sizeof text, "%zu %s", i + 1, kind);
        else
            std::snprintf(text, sizeof text, "%zu %s %.3g,%.3g,%.3g", i + 1, kind, double(l.vector.x),
                          double(l.vector.y), double(l.vector.z));
        names.push_back(text);
    }
    return names;
}

static std::string prefixOf(const std::string& name) {
    size_t dot = name.find('.');
    std::string prefix = dot == std::string::npos ? std::string() : name.substr(0, dot);
    // The shadow.* parameters share the lights' section: one more section header would push the last one off
    // a 720-line window (PanelFit).
    return prefix == "shadow" ? "light" : prefix;
}

PanelResult settingsPanel(Context& ui, RenderSettings& settings, WindowControls& window, float x, float y,
                          float maxHeight, const std::vector<GlintMethod>& methods) {
    PanelResult result;
    ui.beginPanel(kPanelId, x, y, kPanelWidthChars, maxHeight);
    ui.heading("GLIMMER  (H hides, arrows edit)");

    // Method selector and the method's own parameters, generated from its ParamSpec list.
    std::vector<std::string> ids;
    int methodIndex = 0;
    for (size_t i = 0; i < methods.size(); ++i) {
        ids.push_back(methods[i].id);
        if (methods[i].id == settings.method) methodIndex = int(i);
    }
    if (ui.section("Method (M)", true)) {
        if (!ids.empty() && ui.selector("method", ids, methodIndex)) {
            // The IBL mode follows the method's default while it is the previous method's (GlintMethod::defaultIbl):
            // selecting wang2020 turns on its environment glints, leaving it turns them off again.
            if (settings.ibl == defaultIblOf(findGlintMethod(settings.method)))
                settings.ibl = defaultIblOf(methods[size_t(methodIndex)]);
            settings.method = ids[size_t(methodIndex)];
            result.settingsChanged = result.methodChanged = true;
        }
        if (!methods.empty()) {
            const GlintMethod& method = methods[size_t(methodIndex)];
            // The description on one row where it fits, else its citation (the part before " (..."), wrapped only
            // if even that is too long: the method section must keep the panel's sections on a 1280x720 window
            // (PanelFit), and the whole description is the notice shown when the method is selected.
            ui.paragraph(panelMethodTitle(method.title, ui.scale()));
            // A user method: where it comes from (edits to the file reload it, header included).
            if (method.isUserMethod()) ui.paragraph("file " + displayPath(method.sourceFile));
            if (method.params.empty()) ui.label("(no parameters)");
            for (const ParamSpec& spec : method.params) {
                if (panelHidesMethodParameter(method, spec.name)) continue;
                float value = paramOr(settings.methodValues(method.id), spec);
                const char* valueText = methodParameterValueText(method, settings, spec.name);
                // A mapped parameter not set: it shows, and edits start from, the value the mapping gives the
                // reference material ("9.2 mat", the material named above), so the first step is a small change, not a jump to the default.
                std::string mappedText;
                if (valueText && window.mappedMaterial) {
                    value = materialParams(method, *window.mappedMaterial, settings.methodValues(method.id))
                                .at(spec.name);
                    char number[32];
                    std::snprintf(number, sizeof number, "%.3g", double(value));
                    int choice = int(std::lround(value));
                    mappedText = (!spec.choices.empty() && choice >= 0 && choice < int(spec.choices.size())
                                      ? spec.choices[size_t(choice)]
                                      : std::string(number)) +
                                 " mat";
                    valueText = mappedText.c_str();
                }
                Edit edit = ui.slider(spec.name, spec, value, valueText);
                if (edit == Edit::Changed) settings.methods[method.id][spec.name] = value;
                if (edit == Edit::Reset) settings.methods[method.id].erase(spec.name);
                result.settingsChanged |= edit != Edit::None;
            }
        }
        for (size_t i = 0; i < window.methodFileChoices.size(); ++i)
            if (ui.button("load " + window.methodFileChoices[i])) result.loadMethodFile = int(i);
    }

    if (ui.section("Scene, camera, window")) {
        if (!window.sceneNames.empty()) {
            int sceneIndex = std::clamp(window.sceneIndex, 0, int(window.sceneNames.size()) - 1);
            if (ui.selector("scene", window.sceneNames, sceneIndex)) result.sceneRequested = sceneIndex;
        }
        if (!window.cameraNames.empty()) {
            int cameraIndex = std::clamp(window.cameraIndex, 0, int(window.cameraNames.size()) - 1);
            if (ui.selector("camera (1-9)", window.cameraNames, cameraIndex)) result.cameraRequested = cameraIndex;
        }
        bool walking = window.walking;
        if (ui.checkbox("walk, collide (F: fly)", walking)) result.toggleWalking = true;
        ParamSpec speed = moveSpeedSpec();
        if (ui.slider(speed.name, speed, window.moveSpeed) == Edit::Reset) window.moveSpeed = speed.defaultValue;
        if (ui.button(window.walkthroughPlaying ? "stop path (P)" : (window.hasRecordedPath ? "play recorded path (P)" : "play walkthrough (P)")))
            result.toggleWalkthrough = true;
        if (ui.button(window.recording ? "stop recording (R)" : "record path (R)")) result.toggleRecording = true;
        result.vsyncChanged = ui.checkbox("vsync (V)", window.vsync);
        if (ui.button("reload shaders (F5)")) result.reloadShaders = true;
        if (ui.button("screenshot (F12)")) result.screenshot = true;
    }

    // Common parameters, grouped by prefix in the order the table first names each group; the debug view
    // belongs to the image group.
    std::vector<std::string> groups;
    for (const CommonParam& p : commonParams())
        if (std::find(groups.begin(), groups.end(), sectionOfPrefix(prefixOf(p.spec.name))) == groups.end())
            groups.push_back(sectionOfPrefix(prefixOf(p.spec.name)));
    for (const std::string& group : groups) {
        if (!ui.section(commonGroupTitle(group))) continue;
        if (group.empty()) {
            std::vector<std::string> views;
            int viewIndex = 0;
            for (const AovInfo& aov : aovTable()) {
                if (aov.viewId == settings.debugView) viewIndex = int(views.size());
                views.push_back(aov.name);
            }
            if (ui.selector("debug view", views, viewIndex)) {
                settings.debugView = aovTable()[size_t(viewIndex)].viewId;
                result.settingsChanged = true;
            }
        }
        if (group == "light" && !window.lightNames.empty()) {
            // One light at a time: the selector picks it, its rows edit light.<N>.<field> (scene order, from 1).
            window.lightIndex = std::clamp(window.lightIndex, 0, int(window.lightNames.size()) - 1);
            ui.selector("edit light", window.lightNames, window.lightIndex);
            for (const ParamSpec& spec : lightEditParams()) {
                const std::string key = lightEditKey(window.lightIndex + 1, spec.name);
                auto set = settings.common.find(key);
                float value = set == settings.common.end() ? spec.defaultValue : set->second;
                Edit edit = ui.slider(key, spec, value);
                if (edit == Edit::Changed) settings.common[key] = value;
                if (edit == Edit::Reset) settings.common.erase(key);
                result.settingsChanged |= edit != Edit::None;
            }
        }
        for (const CommonParam& p : commonParams()) {
            if (sectionOfPrefix(prefixOf(p.spec.name)) != group || panelHidesParameter(p.spec.name)) continue;
            bool fromScene = p.sceneDefault && !settings.isSet({p.spec.name.c_str()});
            float value = settings.value({p.spec.name.c_str()});
            Edit edit = ui.slider(p.spec.name, p.spec, value, fromScene ? "scene" : nullptr);
            if (edit == Edit::Changed) settings.common[p.spec.name] = value;
            if (edit == Edit::Reset) settings.common.erase(p.spec.name);
            result.settingsChanged |= edit != Edit::None;
        }
    }

    // Environment integration: the IBL mode selector and the mode's own parameters (environment/ibl/ibl_modes.h).
    if (ui.section("Environment integration (I)")) {
        std::vector<std::string> modes;
        int modeIndex = 0;
        for (const IblMode& mode : iblModes()) {
            if (mode.id == settings.ibl) modeIndex = int(modes.size());
            modes.push_back(mode.id);
        }
        if (ui.selector("ibl", modes, modeIndex)) {
            settings.ibl = modes[size_t(modeIndex)];
            result.settingsChanged = result.methodChanged = true;
        }
        const IblMode& mode = iblModes()[size_t(modeIndex)];
        for (const ParamSpec& spec : mode.params) {
            float value = paramOr(settings.iblModeValues(mode.id), spec);
            Edit edit = ui.slider("ibl." + spec.name, spec, value);
            if (edit == Edit::Changed) settings.iblValues[mode.id][spec.name] = value;
            if (edit == Edit::Reset) settings.iblValues[mode.id].erase(spec.name);
            result.settingsChanged |= edit != Edit::None;
        }
    }

    ui.endPanel();
    return result;
}

}  // namespace glimmer::ui
