// The common parameters named in code (render/settings.h, param::) against the table that defines them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "render/settings.h"

namespace glimmer {
namespace {

TEST(RenderSettings, EveryKeyNamesACommonParameterAndEveryParameterHasAKey) {
    std::set<std::string> table;
    for (const CommonParam& p : commonParams()) table.insert(p.spec.name);
    std::set<std::string> keys;
    for (const CommonParamKey& key : param::kAll) {
        EXPECT_TRUE(table.count(key.name)) << "param key '" << key.name << "' names no entry of commonParams()";
        keys.insert(key.name);
    }
    for (const std::string& name : table) EXPECT_TRUE(keys.count(name)) << "no param:: key for '" << name << "'";
    // A key with no entry must fail loudly, not read a default.
    RenderSettings settings;
    EXPECT_THROW(settings.value(CommonParamKey{"exposure.typo"}), std::exception);
    EXPECT_EQ(settings.value(param::exposure), 0.0f);
    settings.apply("exposure=2");
    EXPECT_EQ(settings.value(param::exposure), 2.0f);
    EXPECT_TRUE(settings.isSet(param::exposure));
}

}  // namespace
}  // namespace glimmer
