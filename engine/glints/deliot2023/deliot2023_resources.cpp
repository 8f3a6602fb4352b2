#include "glints/deliot2023/deliot2023_resources.h"

#include "core/clock.h"
#include "core/log.h"
#include "glints/deliot2023/deliot2023_noise.h"

namespace glimmer {

Deliot2023Resources::Deliot2023Resources() {
    Stopwatch clock;
    std::vector<uint32_t> texels = deliot2023::makeNoiseTexels();
    int size = deliot2023::kNoiseSize;
    // Integer texture read with texelFetch: packed half pairs must never be filtered or converted.
    noise_ = gl::createTexture2D(GL_R32UI, size, size, 1);
    glTextureSubImage2D(noise_.id(), 0, 0, 0, size, size, GL_RED_INTEGER, GL_UNSIGNED_INT, texels.data());
    glTextureParameteri(noise_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(noise_.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTextureParameteri(noise_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(noise_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    log::debug("deliot2023: random-number texture ", size, "x", size, " in ", clock.elapsedMs(), " ms");
}

void Deliot2023Resources::bind() { glBindTextureUnit(kNoiseUnit, noise_.id()); }

std::unique_ptr<GlintMethodResources> createDeliot2023Resources() { return std::make_unique<Deliot2023Resources>(); }

}  // namespace glimmer
