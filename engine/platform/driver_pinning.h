// Sanitizer builds only: keeps Mesa's DRI driver loaded for the life of the process.
#pragma once

namespace glimmer {

// Mesa unloads its DRI driver (llvmpipe, with LLVM) when the last context goes away. LeakSanitizer reports at
// exit, and by then the stacks of the driver's own internal allocations point into unmapped code: they cannot be
// symbolized, so the suppressions (__lsan_default_suppressions in the .cpp) cannot recognise them as Mesa's.
// Opening the driver once more with RTLD_NODELETE keeps it mapped, its frames symbolize, and the suppressions
// apply; leaks in our code are still reported. Does nothing in builds without AddressSanitizer. Call before creating a GL context.
void pinGlDriversUnderSanitizers();

}  // namespace glimmer
