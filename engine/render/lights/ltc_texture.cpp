#include "render/lights/ltc_texture.h"

#include <glad/gl.h>

#include "common/bindings.glsl"
#include "render/lights/ltc_tables.h"

namespace glimmer {

LtcTexture::LtcTexture() {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, 1, GL_RGBA32F, ltc::kTableSize, ltc::kTableSize, ltc::kLayers);
    glTextureSubImage3D(id, 0, 0, 0, 0, ltc::kTableSize, ltc::kTableSize, ltc::kLayers, GL_RGBA, GL_FLOAT,
                        ltc::kTableData);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    texture_ = gl::Texture(id);
}

void LtcTexture::bind() const { glBindTextureUnit(UNIT_LTC_TABLE, texture_.id()); }

}  // namespace glimmer
