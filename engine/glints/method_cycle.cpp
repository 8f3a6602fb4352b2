#include "glints/method_cycle.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace glimmer {

const GlintMethod& cycleGlintMethod(const std::string& from, int step, const std::string& skip) {
    const std::vector<GlintMethod>& methods = glintMethods();
    int n = int(methods.size()), current = 0;
    for (int i = 0; i < n; ++i)
        if (methods[size_t(i)].id == from) current = i;
    int direction = step < 0 ? -1 : 1, remaining = std::abs(step), at = current;
    for (int tries = 0; tries < 2 * n * std::max(remaining, 1) && remaining > 0; ++tries) {
        at = ((at + direction) % n + n) % n;
        if (methods[size_t(at)].id != skip || n == 1) --remaining;
    }
    return methods[size_t(at)];
}

}  // namespace glimmer
