// The named images and buffers that passes hand each other within a frame. Each pass declares what it reads and
// writes (Pass::resources()); whoever allocates a resource publishes it here, and a pass reaches another pass's
// output only through this table, never through a reference to that pass. Two checks hold the declarations true:
// - checkFrameList(): every resource a pass reads is written by an earlier pass of the list (or, for a history, by
//   any pass of the previous frame), and nothing is written that no pass declares (tests walk the renderer's list);
// - read() / write() of a resource that the running pass did not declare throws (in every build: it costs a few
//   list lookups per pass).
#pragma once
#include <glad/gl.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace glimmer {

enum class FrameResource : int {
    GBuffer,          // the six colour targets (layout in shaders/frame/gbuffer.frag), render size
    Depth,            // reversed-Z depth of the opaque surfaces, render size
    ShadowMaps,       // textures: the sun and local depth arrays, the local one without compare; buffer: the shadow block (shaders/shadows/)
    ShadowMask,       // every shadowed light's visibility, an RGBA8 array (every pixel or every second one)
    AmbientOcclusionRaw,  // GTAO's raw visibility
    AmbientOcclusion,     // the resolved factor on the environment term (1 x 1 white when AO is off)
    ReflectionProbes, // textures: the probe cube-map array; buffer: the probe block
    EnvironmentGlints,  // buffer: the environment's radiance levels; textures: the sky's and the probes' level
                        // weights (environment/environment_glints.h); no buffer: none this frame
    ShadingClass,     // DEPTH16: 1 on glinty pixels, 0 elsewhere (lighting.split_glinty)
    Hdr,              // linear HDR radiance (or the debug view), render size
    GlintPart,        // the lights' glint radiance inside Hdr, kept out of TAA's clipping (aa=taa)
    MethodTargets,    // the glint method's own lighting outputs (GlintMethod::lightingTargets)
    OpaqueMean,       // accumulating IBL modes: the opaque mean saved before the forward passes composite
    PostHdr,          // HDR radiance after TAA, post size (Hdr itself when the post size is the render size)
    ExposureState,    // buffer: metered and target EV
    Bloom,            // the sum of the bloom levels (half the post size)
    Display,          // tone-mapped sRGB, post size
    Count
};
constexpr int kFrameResourceCount = int(FrameResource::Count);
const char* frameResourceName(FrameResource resource);

struct FrameImage {
    std::vector<GLuint> textures;   // one, or several (G-buffer targets, method targets, shadow arrays)
    GLuint buffer = 0;
    int width = 0, height = 0;
    int levels = 1;                 // levels of a chain (the bloom levels summed into the first)
    // Unique per publish() (FrameResources numbers them): framebuffers over the image are rebuilt when it changes
    // (gl::AttachedFramebuffer).
    uint64_t serial = 0;
    GLuint texture(size_t i = 0) const { return i < textures.size() ? textures[i] : 0; }
};

struct PassResources {
    std::vector<FrameResource> reads, writes;
    // Read as the previous frame (or accumulation sample) left them: written later in the list.
    std::vector<FrameResource> readsPrevious;
    bool declares(FrameResource r) const;
};

class FrameResources {
public:
    // Owners publish a resource when they allocate it and may republish it every frame (the same objects keep their
    // serial); an empty image means "not allocated".
    void publish(FrameResource resource, FrameImage image);
    // The resource, for the running pass: throws Error unless it declared the read (or write).
    const FrameImage& read(FrameResource resource) const;
    const FrameImage& write(FrameResource resource) const;
    // Unchecked: the renderer's readbacks and the owner's own bookkeeping.
    const FrameImage& get(FrameResource resource) const { return images_[size_t(resource)]; }

    // The pass whose accesses are checked until endPass() (the renderer brackets each execute()).
    void beginPass(const char* name, const PassResources* declared) { passName_ = name, declared_ = declared; }
    void endPass() { passName_ = nullptr, declared_ = nullptr; }

private:
    void check(FrameResource resource, bool write) const;
    std::array<FrameImage, kFrameResourceCount> images_;
    uint64_t published_ = 0;
    const char* passName_ = nullptr;
    const PassResources* declared_ = nullptr;
};

// What checkFrameList() found wrong with an ordered list of (pass name, declaration): empty when consistent.
struct DeclaredPass {
    std::string name;
    PassResources resources;
};
std::vector<std::string> checkFrameList(const std::vector<DeclaredPass>& passes);

}  // namespace glimmer
