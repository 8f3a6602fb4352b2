// main() of glimmer_tests: GoogleTest, plus the ctest labels derived from what each suite needs (test_needs.h).
//
// --gtest_filter=glimmer_label_LABEL (LABEL: fast, gl, golden, window) selects the tests of one label; CMake's test
// discovery lists each label this way (tests/CMakeLists.txt), so the labels come from the declarations in the test
// files, not from a list kept in CMake. A listener checks, test by test, that a test labelled fast neither created a
// GL context nor started a process.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdio>
#include <string>

#include "platform/context.h"
#include "support/test_needs.h"

namespace {

using glimmer::test::Need;

constexpr const char* kLabelFilterPrefix = "glimmer_label_";

// "AllScenes/Deliot2023Golden" -> "Deliot2023Golden": value-parameterized suites carry their instantiation's name.
std::string baseSuiteName(const std::string& suite) {
    size_t slash = suite.rfind('/');
    return slash == std::string::npos ? suite : suite.substr(slash + 1);
}

const Need* declaredNeed(const std::string& suite) {
    const auto& needs = glimmer::test::declaredSuiteNeeds();
    auto it = needs.find(baseSuiteName(suite));
    return it == needs.end() ? nullptr : &it->second;
}

std::string labelOf(const std::string& suite, const std::string& test) {
    const Need* need = declaredNeed(suite);
    if (need && *need == Need::Window) return "window";
    if ((suite + "." + test).find("Golden") != std::string::npos) return "golden";
    return need ? "gl" : "fast";
}

// The gtest filter that selects exactly the tests of `label`.
std::string filterForLabel(const std::string& label) {
    std::string filter;
    const testing::UnitTest& unit = *testing::UnitTest::GetInstance();
    for (int s = 0; s < unit.total_test_suite_count(); ++s) {
        const testing::TestSuite& suite = *unit.GetTestSuite(s);
        for (int t = 0; t < suite.total_test_count(); ++t) {
            const testing::TestInfo& test = *suite.GetTestInfo(t);
            if (labelOf(suite.name(), test.name()) != label) continue;
            filter += (filter.empty() ? "" : ":") + std::string(suite.name()) + "." + test.name();
        }
    }
    return filter.empty() ? "-*" : filter;   // no test: a filter that matches none
}

// Sum of what the kernel accounts to this process's reaped children: it grows whenever a child process has run.
long childProcessUsage() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return usage.ru_minflt + usage.ru_majflt + usage.ru_nvcsw + usage.ru_nivcsw + usage.ru_utime.tv_usec +
           usage.ru_stime.tv_usec + usage.ru_utime.tv_sec + usage.ru_stime.tv_sec;
}

class NeedsChecker : public testing::EmptyTestEventListener {
    // From the suite's start, so that what SetUpTestSuite creates counts too.
    void OnTestSuiteStart(const testing::TestSuite&) override {
        suiteContexts_ = glimmer::glContextsCreated();
        suiteChildren_ = childProcessUsage();
    }
    void OnTestStart(const testing::TestInfo&) override {
        contexts_ = glimmer::glContextsCreated();
        children_ = childProcessUsage();
    }

    // Runs before the result printer's OnTestEnd (end events go to listeners in reverse order), so a failure added
    // here is part of the test's result.
    void OnTestEnd(const testing::TestInfo& test) override {
        if (test.result()->Skipped()) return;
        const bool madeContext = glimmer::glContextsCreated() != contexts_;
        const bool ranProcess = childProcessUsage() != children_;
        const bool suiteMadeContext = glimmer::glContextsCreated() != suiteContexts_;
        const bool suiteRanProcess = childProcessUsage() != suiteChildren_;
        const std::string suite = test.test_suite_name();
        if (labelOf(suite, test.name()) == "fast" && (suiteMadeContext || suiteRanProcess)) {
            ADD_FAILURE() << suite << "." << test.name() << " is labelled fast (its suite declares no need) but "
                          << (suiteMadeContext ? "created a GL context" : "started a process")
                          << ": add GLIMMER_SUITE_NEEDS(" << baseSuiteName(suite) << ", "
                          << (suiteMadeContext ? "GlContext" : "Process") << ") beside its tests (tests/support/test_needs.h)";
        }
        // A declaration the test does not use costs CI time: say so, without failing (a test may skip its GL part).
        const Need* need = declaredNeed(suite);
        if (need && *need != Need::Window && !madeContext && !ranProcess && !test.result()->Failed())
            std::fprintf(stderr, "note: %s.%s created no GL context and started no process: without its "
                                 "GLIMMER_SUITE_NEEDS it would be labelled fast\n", suite.c_str(), test.name());
    }

    int contexts_ = 0, suiteContexts_ = 0;
    long children_ = 0, suiteChildren_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);   // also instantiates the value-parameterized tests
    const std::string filter = GTEST_FLAG_GET(filter);
    if (filter.rfind(kLabelFilterPrefix, 0) == 0) {
        const std::string label = filter.substr(std::string(kLabelFilterPrefix).size());
        if (label != "fast" && label != "gl" && label != "golden" && label != "window") {
            std::fprintf(stderr, "glimmer_tests: --gtest_filter=%s: unknown label (fast, gl, golden, window)\n",
                         filter.c_str());
            return 2;
        }
        GTEST_FLAG_SET(filter, filterForLabel(label));
    }
    testing::UnitTest::GetInstance()->listeners().Append(new NeedsChecker);
    return RUN_ALL_TESTS();
}
