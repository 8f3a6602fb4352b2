#include "platform/driver_pinning.h"

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>

#include <cstdlib>
#include <string>
#include <vector>
#endif

namespace glimmer {

void pinGlDriversUnderSanitizers() {
#if defined(__SANITIZE_ADDRESS__)
    static const bool pinned = [] {
        std::vector<std::string> dirs;
        if (const char* env = std::getenv("LIBGL_DRIVERS_PATH")) dirs.emplace_back(env);
        for (const char* d : {"/usr/lib/x86_64-linux-gnu/dri", "/usr/lib/aarch64-linux-gnu/dri", "/usr/lib64/dri",
                              "/usr/lib/dri"})
            dirs.emplace_back(d);
        bool any = false;
        for (const std::string& dir : dirs)
            for (const char* driver : {"swrast_dri.so", "kms_swrast_dri.so"})
                any |= dlopen((dir + "/" + driver).c_str(), RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE) != nullptr;
        return any;
    }();
    (void)pinned;
#endif
}

}  // namespace glimmer
