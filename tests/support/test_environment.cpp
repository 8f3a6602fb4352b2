// Environment every test process needs before Mesa is loaded, set here rather than through CTest properties so
// that running build/tests/glimmer_tests directly behaves like ctest (child `glimmer` processes inherit it).
// Values already set by the caller win.
#include <cstdlib>

namespace {

struct TestEnvironment {
    TestEnvironment() {
        // Shader cache off: every test compiles from source, so a stale cache cannot hide a shader change.
        setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
        // One llvmpipe code path on every x86 machine (AVX2 and AVX-512 hosts otherwise round differently),
        // which keeps golden images bit-stable across machines.
        setenv("GALLIUM_OVERRIDE_CPU_CAPS", "avx", 0);
    }
};

const TestEnvironment kTestEnvironment;

}  // namespace
