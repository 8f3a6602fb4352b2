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

#if defined(__SANITIZE_ADDRESS__)
// LeakSanitizer's built-in suppressions hook, compiled into every binary that creates a GL context: leaks inside the
// GL stack (Mesa, LLVM, GLVND, X11), not ours. With the driver pinned above, their stacks name these modules.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libLLVM\nleak:libgallium\nleak:mesa\nleak:libEGL\nleak:libGLX\nleak:libGLdispatch\nleak:libOSMesa\nleak:libX11\nleak:libglfw\nleak:libdl\nleak:libglapi\nleak:dri\n";
}
#endif
