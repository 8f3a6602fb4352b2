// The LTC tables (render/lights/ltc_tables.h, fitted at build time) as one RGBA32F 2D array texture on unit
// UNIT_LTC_TABLE, bilinearly filtered and clamped, for shaders/lights/ltc.glsl. The renderer owns one per context
// and binds it before any pass of a frame (its lighting programs and the reflection probes' read it).
#pragma once
#include "gl/handles.h"

namespace glimmer {

class LtcTexture {
public:
    LtcTexture();
    void bind() const;
    unsigned id() const { return texture_.id(); }

private:
    gl::Texture texture_;
};

}  // namespace glimmer
