// GPU resources of Chermain et al. 2020: the dictionary of multiscale marginal distributions (dictionary.h),
// loaded from the disk cache or generated once per process, uploaded as a mipmapped 1D array texture
// (shaders/glints/chermain2020/chermain2020_dictionary.glsl) and bound to texture unit UNIT_METHOD_FIRST.
#pragma once
#include <memory>

#include "common/bindings.glsl"
#include "gl/handles.h"
#include "glints/chermain2020/dictionary.h"
#include "glints/methods.h"

namespace glimmer {

class Chermain2020Resources : public GlintMethodResources {
public:
    static constexpr int kDictionaryUnit = UNIT_METHOD_FIRST;
    Chermain2020Resources();
    void bind() override;
    GLuint dictionaryTexture() const { return texture_.id(); }
    // The table the texture was made from (read once per process: every context shares it).
    static const chermain2020::LoadedDictionary& dictionary();

private:
    gl::Texture texture_;
};

// Uploads a dictionary as the shader's texture: RGBA16F, `resolution` texels, levels x marginals / 4 layers (four
// marginals per texel), the full mip chain (GL box filter), linear filtering, mirrored repeat.
gl::Texture uploadChermainDictionary(const chermain2020::Dictionary& dictionary);

std::unique_ptr<GlintMethodResources> createChermain2020Resources();

}  // namespace glimmer
