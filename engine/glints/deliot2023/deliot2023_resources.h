// GPU resources of Deliot & Belcour 2023: the random-number texture of Sec. 6.3, generated once at start-up and
// bound to texture unit 8 (u_deliotNoise in shaders/glints/deliot2023/deliot2023_binomial.glsl).
#pragma once
#include "common/bindings.glsl"
#include <memory>

#include "gl/handles.h"
#include "glints/methods.h"

namespace glimmer {

class Deliot2023Resources : public GlintMethodResources {
public:
    static constexpr int kNoiseUnit = UNIT_METHOD_FIRST;
    Deliot2023Resources();
    void bind() override;
    GLuint noiseTexture() const { return noise_.id(); }

private:
    gl::Texture noise_;
};

std::unique_ptr<GlintMethodResources> createDeliot2023Resources();

}  // namespace glimmer
