// Kneiphof & Klein 2025's environment glints in the frame (environment/environment_glints.h): prepare() runs after
// the probes are captured (render/probes/probes_pass.h) and, for a method that draws environment glints
// (GlintMethod::environmentGlints) under an IBL mode with `glint_levels`, rebuilds the environment's radiance levels
// and their prefiltered weights when the environment, the probes or the parameters changed (`env_glints.levels` in
// --stats), then publishes FrameResource::EnvironmentGlints (buffer: the levels; textures: the sky's and the
// probes' weights), or an image without a buffer when the frame draws none. It draws nothing itself.
#pragma once
#include <filesystem>

#include "environment/environment_glints.h"
#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class EnvironmentGlintsPass : public Pass {
public:
    explicit EnvironmentGlintsPass(const std::filesystem::path& shaderRoot) : glints_(shaderRoot) {}
    const char* name() const override { return "environment_glints"; }
    PassResources resources() const override {
        return {.reads = {FrameResource::ReflectionProbes}, .writes = {FrameResource::EnvironmentGlints}};
    }
    std::vector<gl::Program*> programs() override { return {}; }
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext&) const override { return false; }
    void execute(const FrameContext&) override {}
    const EnvironmentGlints& glints() const { return glints_; }

private:
    EnvironmentGlints glints_;
};

// What the lighting pass binds when the frame has no environment glints: a level block saying "no levels" and an
// empty cube-map array (one per lighting pass).
struct NoEnvironmentGlints {
    NoEnvironmentGlints();
    gl::Buffer block;
    gl::Texture empty;
};

// Binds EnvironmentGlints (common/bindings.glsl BINDING_ENV_GLINTS, UNIT_ENV_GLINT_WEIGHTS, UNIT_PROBE_GLINT_WEIGHTS),
// or `none` when the image has no buffer.
void bindEnvironmentGlints(const FrameImage& glints, const NoEnvironmentGlints& none);

}  // namespace glimmer
