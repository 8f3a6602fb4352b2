#include "render/frame/frame_resources.h"

#include <algorithm>

#include "core/error.h"

namespace glimmer {

const char* frameResourceName(FrameResource resource) {
    static const char* const names[kFrameResourceCount] = {
        "gbuffer",     "depth",         "shadow_maps", "shadow_mask",    "ambient_occlusion_raw",
        "ambient_occlusion", "reflection_probes", "environment_glints", "shading_class", "hdr", "glint_part",
        "method_targets", "opaque_mean", "post_hdr",  "exposure_state", "bloom",
        "display"};
    const int i = int(resource);
    return i >= 0 && i < kFrameResourceCount ? names[i] : "unknown";
}

bool PassResources::declares(FrameResource r) const {
    auto has = [r](const std::vector<FrameResource>& list) { return std::find(list.begin(), list.end(), r) != list.end(); };
    return has(reads) || has(writes) || has(readsPrevious);
}

void FrameResources::publish(FrameResource resource, FrameImage image) {
    FrameImage& slot = images_[size_t(resource)];
    // Republishing the same objects keeps the serial. A reallocation gets new names (gl::create* makes the new object
    // before the old one is deleted), so it always gets a new serial.
    const bool same = slot.textures == image.textures && slot.buffer == image.buffer && slot.width == image.width &&
                      slot.height == image.height && slot.levels == image.levels;
    image.serial = same ? slot.serial : ++published_;
    slot = std::move(image);
}

// Checked in every build, not only debug ones: a handful of list lookups per pass and frame, and the whole test
// suite then runs with the declarations enforced.
void FrameResources::check(FrameResource resource, bool write) const {
    if (!declared_) return;   // outside a pass: the renderer itself
    const bool declared = write ? std::find(declared_->writes.begin(), declared_->writes.end(), resource) !=
                                      declared_->writes.end()
                                : declared_->declares(resource);
    if (!declared)
        throw Error(std::string("pass ") + passName_ + (write ? " writes " : " reads ") + frameResourceName(resource) +
                    " without declaring it (Pass::resources)");
}

const FrameImage& FrameResources::read(FrameResource resource) const {
    check(resource, false);
    return images_[size_t(resource)];
}

const FrameImage& FrameResources::write(FrameResource resource) const {
    check(resource, true);
    return images_[size_t(resource)];
}

std::vector<std::string> checkFrameList(const std::vector<DeclaredPass>& passes) {
    std::vector<std::string> problems;
    std::array<bool, kFrameResourceCount> written{};
    std::array<bool, kFrameResourceCount> writtenAnywhere{};
    for (const DeclaredPass& pass : passes)
        for (FrameResource r : pass.resources.writes) writtenAnywhere[size_t(r)] = true;
    for (const DeclaredPass& pass : passes) {
        for (FrameResource r : pass.resources.reads)
            if (!written[size_t(r)])
                problems.push_back(pass.name + " reads " + frameResourceName(r) + " before any pass writes it");
        for (FrameResource r : pass.resources.readsPrevious)
            if (!writtenAnywhere[size_t(r)])
                problems.push_back(pass.name + " reads the previous " + frameResourceName(r) + " that no pass writes");
        for (FrameResource r : pass.resources.writes) written[size_t(r)] = true;
    }
    return problems;
}

}  // namespace glimmer
