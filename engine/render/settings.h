// Everything that selects or tunes a render apart from the scene and camera: the glint method and its
// parameters, the common parameters (exposure, lights, material overrides) and the debug view.
#pragma once
#include <string>
#include <vector>

#include "core/params.h"
#include "scene/scene.h"

namespace glimmer {

struct GlintMethod;

// Parameters shared by every method. Entries marked sceneDefault take the scene's value unless set.
struct CommonParam {
    ParamSpec spec;
    bool sceneDefault = false;
};
const std::vector<CommonParam>& commonParams();

// A common parameter named in code: param::exposure, param::shadow_enabled... A misspelt name is a compile error,
// and a test (RenderSettings.EveryKeyNamesACommonParameter) checks that each key names an entry of commonParams().
struct CommonParamKey {
    const char* name;
};
namespace param {
inline constexpr CommonParamKey exposure{"exposure"};
inline constexpr CommonParamKey texture_anisotropy{"texture_anisotropy"};
inline constexpr CommonParamKey ambient{"ambient"};
inline constexpr CommonParamKey light_intensity{"light.intensity"};
inline constexpr CommonParamKey light_count{"light.count"};
inline constexpr CommonParamKey light_turn{"light.turn"};
inline constexpr CommonParamKey light_sun_diameter{"light.sun_diameter"};
inline constexpr CommonParamKey light_area_size{"light.area_size"};
inline constexpr CommonParamKey light_area_intensity{"light.area_intensity"};
inline constexpr CommonParamKey material_alpha{"material.alpha"};
inline constexpr CommonParamKey material_metallic{"material.metallic"};
inline constexpr CommonParamKey material_ndf{"material.ndf"};
inline constexpr CommonParamKey material_glinty{"material.glinty"};
inline constexpr CommonParamKey material_density_scale{"material.density_scale"};
inline constexpr CommonParamKey material_glint_density{"material.glint_density"};
inline constexpr CommonParamKey material_glint_angular_size{"material.glint_angular_size"};
inline constexpr CommonParamKey material_glint_anisotropy{"material.glint_anisotropy"};
inline constexpr CommonParamKey material_glint_color_variation{"material.glint_color_variation"};
inline constexpr CommonParamKey material_clearcoat{"material.clearcoat"};
inline constexpr CommonParamKey material_clearcoat_roughness{"material.clearcoat_roughness"};
inline constexpr CommonParamKey env_intensity{"env.intensity"};
inline constexpr CommonParamKey env_rotation{"env.rotation"};
inline constexpr CommonParamKey aa{"aa"};
inline constexpr CommonParamKey ssaa_factor{"ssaa.factor"};
inline constexpr CommonParamKey taa_feedback{"taa.feedback"};
inline constexpr CommonParamKey taa_glint_history{"taa.glint_history"};
inline constexpr CommonParamKey taa_stable_glints{"taa.stable_glints"};
inline constexpr CommonParamKey lighting_split_glinty{"lighting.split_glinty"};
inline constexpr CommonParamKey lighting_glint_footprint{"lighting.glint_footprint"};
inline constexpr CommonParamKey lod_pixel_error{"lod.pixel_error"};
inline constexpr CommonParamKey taa_upsample{"taa.upsample"};
inline constexpr CommonParamKey taa_glint_feedback{"taa.glint_feedback"};
inline constexpr CommonParamKey bloom_strength{"bloom.strength"};
inline constexpr CommonParamKey bloom_radius{"bloom.radius"};
inline constexpr CommonParamKey exposure_auto{"exposure.auto"};
inline constexpr CommonParamKey tonemap{"tonemap"};
inline constexpr CommonParamKey probes_enabled{"probes.enabled"};
inline constexpr CommonParamKey probes_face_size{"probes.face_size"};
inline constexpr CommonParamKey probes_max{"probes.max"};
inline constexpr CommonParamKey ao_enabled{"ao.enabled"};
inline constexpr CommonParamKey ao_screen{"ao.screen"};
inline constexpr CommonParamKey ao_sky{"ao.sky"};
inline constexpr CommonParamKey ao_radius{"ao.radius"};
inline constexpr CommonParamKey ao_power{"ao.power"};
inline constexpr CommonParamKey ao_slices{"ao.slices"};
inline constexpr CommonParamKey ao_steps{"ao.steps"};
inline constexpr CommonParamKey ao_falloff{"ao.falloff"};
inline constexpr CommonParamKey ao_denoise{"ao.denoise"};
inline constexpr CommonParamKey ao_half_res{"ao.half_res"};
inline constexpr CommonParamKey ao_multibounce{"ao.multibounce"};
inline constexpr CommonParamKey ao_sky_cell{"ao.sky_cell"};
inline constexpr CommonParamKey ao_sky_rays{"ao.sky_rays"};
inline constexpr CommonParamKey shadow_enabled{"shadow.enabled"};
inline constexpr CommonParamKey shadow_map_size{"shadow.map_size"};
inline constexpr CommonParamKey shadow_cascades{"shadow.cascades"};
inline constexpr CommonParamKey shadow_filter_radius{"shadow.filter_radius"};
inline constexpr CommonParamKey shadow_bias{"shadow.bias"};
inline constexpr CommonParamKey shadow_normal_bias{"shadow.normal_bias"};
inline constexpr CommonParamKey shadow_slope_bias{"shadow.slope_bias"};
inline constexpr CommonParamKey shadow_distance{"shadow.distance"};
inline constexpr CommonParamKey shadow_point_map_size{"shadow.point_map_size"};
inline constexpr CommonParamKey shadow_half_res{"shadow.half_res"};
inline constexpr CommonParamKey shadow_cache{"shadow.cache"};
inline constexpr CommonParamKey kAll[] = {exposure, texture_anisotropy, ambient, light_intensity, light_count, light_turn, light_sun_diameter, light_area_size, light_area_intensity, material_alpha, material_metallic, material_ndf, material_glinty, material_density_scale, material_glint_density, material_glint_angular_size, material_glint_anisotropy, material_glint_color_variation, material_clearcoat, material_clearcoat_roughness, env_intensity, env_rotation, aa, ssaa_factor, taa_feedback, taa_glint_history, taa_stable_glints, lighting_split_glinty, lighting_glint_footprint, lod_pixel_error, taa_upsample, taa_glint_feedback, bloom_strength, bloom_radius, exposure_auto, tonemap, probes_enabled, probes_face_size, probes_max, ao_enabled, ao_screen, ao_sky, ao_radius, ao_power, ao_slices, ao_steps, ao_falloff, ao_denoise, ao_half_res, ao_multibounce, ao_sky_cell, ao_sky_rays, shadow_enabled, shadow_map_size, shadow_cascades, shadow_filter_radius, shadow_bias, shadow_normal_bias, shadow_slope_bias, shadow_distance, shadow_point_map_size, shadow_half_res, shadow_cache};
}  // namespace param

struct RenderSettings {
    std::string method = "smooth";
    ParamValues common;                         // keys of commonParams()
    std::map<std::string, ParamValues> methods; // method id -> its parameter values
    int debugView = 0;                          // AovInfo::viewId
    std::string ibl = "prefiltered";            // environment-integration mode (environment/ibl/ibl_modes.h)
    std::map<std::string, ParamValues> iblValues;  // mode id -> its parameter values (--set ibl.<name>=V)

    float value(CommonParamKey key) const;  // value or default of a common parameter
    bool isSet(CommonParamKey key) const { return common.count(key.name) != 0; }
    const ParamValues& methodValues(const std::string& id) const;
    const ParamValues& iblModeValues(const std::string& id) const;

    // Applies one --set KEY=VALUE. KEY is a common parameter, "<method>.<param>", "ibl.<param>" (a parameter of
    // the current IBL mode), or a bare parameter of the current method. Throws UsageError naming --set and the key.
    void apply(const std::string& assignment);
};

// One light's own edits (the panel's "edit light" rows; --set light.<N>.<field>, N counting the scene's lights
// from 1 in scene order): kept in RenderSettings::common under those keys and applied by applySceneOverrides
// before the all-lights parameters (light.intensity, light.area_*, light.count, light.turn).
const std::vector<ParamSpec>& lightEditParams();
constexpr int kMaxEditedLights = 64;
std::string lightEditKey(int lightNumber, const std::string& field);
// The light number of a "light.<N>.<field>" key (0 when the key is not one).
int lightEditNumber(const std::string& key);
// Removes every light's own edits (the window does when it loads another scene: the numbers name other lights).
void clearLightEdits(RenderSettings& settings);

// Returns the scene with material and light overrides of `settings` applied. A light edit naming a light the scene
// lacks throws UsageError naming the key.
void applySceneOverrides(const RenderSettings& settings, Scene& scene);

// Text for `glimmer render --list-params`.
std::string describeParams();

}  // namespace glimmer
