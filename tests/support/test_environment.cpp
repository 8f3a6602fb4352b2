// Environment every test process needs before Mesa is loaded, set here rather than through CTest properties so
// that running build/tests/glimmer_tests directly behaves like ctest (child `glimmer` processes inherit it).
// Values already set by the caller win.
#include <cstdlib>

namespace {

struct TestEnvironment {
    TestEnvironment() {
        // Mesa's shader cache on, in a folder of the build tree shared by every test process of the run: the same
        // ~40 programs (and their llvmpipe fragment variants) are otherwise compiled from source by each of ~250
        // GL test processes, about 2 CPU-s of a 3 CPU-s small render. A cache entry cannot stand for a changed
        // shader: Mesa keys it by the SHA-1 of the exact source text given to glShaderSource (our #include-expanded
        // text, defines included) and the driver's build id, and it stores only shaders that compiled and linked,
        // so an edited shader is a miss and a broken one still fails to compile. It does not change output
        // (../shared/toolchain.md). MESA_SHADER_CACHE_DISABLE=true in the caller's environment turns it off.
        setenv("MESA_SHADER_CACHE_DISABLE", "false", 0);
        setenv("MESA_SHADER_CACHE_DIR", GLIMMER_TEST_OUTPUT_DIR "/mesa_shader_cache", 0);
        // One llvmpipe code path on every x86 machine (AVX2 and AVX-512 hosts otherwise round differently),
        // which keeps golden images bit-stable across machines.
        setenv("GALLIUM_OVERRIDE_CPU_CAPS", "avx", 0);
        // The engine's disk caches (environment precompute, reflection probes, sky visibility, tables) in the build
        // tree, not the user's ~/.cache: a run neither reads stale entries of another checkout nor evicts the user's.
        // It keeps every environment the suite uses (about two dozen, 38 MB each): with the default 6 the suite
        // recomputed 56 environments (368 s of test time) where 23 were distinct.
        setenv("GLIMMER_CACHE_DIR", GLIMMER_TEST_OUTPUT_DIR "/cache", 0);
        setenv("GLIMMER_CACHE_KEEP", "64", 0);
    }
};

const TestEnvironment kTestEnvironment;

}  // namespace
