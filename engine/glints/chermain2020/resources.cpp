#include "glints/chermain2020/resources.h"

#include <vector>

#include "core/cache_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/log.h"

namespace glimmer {

const chermain2020::LoadedDictionary& Chermain2020Resources::dictionary() {
    static const chermain2020::LoadedDictionary loaded =
        chermain2020::loadOrGenerateDictionary(chermain2020::DictionarySpec{}, cache::defaultCacheDir());
    return loaded;
}

gl::Texture uploadChermainDictionary(const chermain2020::Dictionary& dict) {
    const chermain2020::DictionarySpec& spec = dict.spec;
    const int width = spec.resolution, groups = spec.marginals / 4, layers = spec.levels * groups;
    GLint maxLayers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (layers > maxLayers)
        throw Error("chermain2020: the dictionary needs " + std::to_string(layers) + " texture layers, the GL offers " +
                    std::to_string(maxLayers));
    int mips = 1;
    while ((width >> mips) >= 1) ++mips;   // down to one texel
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_1D_ARRAY, 1, &id);
    gl::Texture texture(id);
    glTextureStorage2D(id, mips, GL_RGBA16F, width, layers);
    // Level 0: texel j of layer (level, group) holds marginals 4 group .. 4 group + 3 in RGBA. The mips are box
    // averages computed here in float from the table (a pair average keeps h sum v, the normalization).
    std::vector<float> rgba(size_t(width) * layers * 4);
    for (int level = 0; level < spec.levels; ++level)
        for (int g = 0; g < groups; ++g)
            for (int c = 0; c < 4; ++c) {
                const float* v = dict.marginal(level, 4 * g + c);
                float* row = rgba.data() + size_t(level * groups + g) * width * 4;
                for (int j = 0; j < width; ++j) row[size_t(j) * 4 + c] = v[j];
            }
    int w = width;
    for (int mip = 0; mip < mips; ++mip) {
        glTextureSubImage2D(id, mip, 0, 0, w, layers, GL_RGBA, GL_FLOAT, rgba.data());
        if (w == 1) break;
        int half = w / 2;
        std::vector<float> next(size_t(half) * layers * 4);
        for (int layer = 0; layer < layers; ++layer)
            for (int j = 0; j < half; ++j)
                for (int c = 0; c < 4; ++c)
                    next[(size_t(layer) * half + j) * 4 + c] = 0.5f * (rgba[(size_t(layer) * w + 2 * j) * 4 + c] +
                                                                        rgba[(size_t(layer) * w + 2 * j + 1) * 4 + c]);
        rgba.swap(next);
        w = half;
    }
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_MIRRORED_REPEAT);
    return texture;
}

Chermain2020Resources::Chermain2020Resources() {
    const chermain2020::LoadedDictionary& loaded = dictionary();
    Stopwatch clock;
    texture_ = uploadChermainDictionary(loaded.dictionary);
    log::debug("chermain2020: dictionary texture uploaded in ", clock.elapsedMs(), " ms (",
               loaded.fromCache ? "from the cache" : "generated", ")");
}

void Chermain2020Resources::bind() { glBindTextureUnit(kDictionaryUnit, texture_.id()); }

std::unique_ptr<GlintMethodResources> createChermain2020Resources() {
    return std::make_unique<Chermain2020Resources>();
}

}  // namespace glimmer
