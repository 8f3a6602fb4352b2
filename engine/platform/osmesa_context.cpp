// OSMesa: software context with a mandatory client colour buffer (1x1: all rendering goes to FBOs).
#include <glad/gl.h>
#include <GL/osmesa.h>

#include <vector>

#include "core/error.h"
#include "platform/context.h"

namespace glimmer {
namespace {

class OSMesaContextHolder final : public GLContext {
public:
    OSMesaContextHolder() : buffer_(4 * 4 * 4) {
        const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                                  OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                                  OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!context_) throw Error("OSMesa: cannot create a 4.5 core context");
        makeCurrent();
        loadGLFunctions(reinterpret_cast<void* (*)(const char*)>(OSMesaGetProcAddress), "OSMesa");
    }
    ~OSMesaContextHolder() override { OSMesaDestroyContext(context_); }
    Backend backend() const override { return Backend::OSMesa; }
    void makeCurrent() override {
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4))
            throw Error("OSMesa: OSMesaMakeCurrent failed");
    }

private:
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GLContext> createOSMesaContext() { return std::make_unique<OSMesaContextHolder>(); }

}  // namespace glimmer
