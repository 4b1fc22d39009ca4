// The encoding entries of the registry: what the node run's encoding phase reports.
#include <gtest/gtest.h>

#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform {
namespace {

TEST(EncodingChecksEntriesTest, AreRunPhasesOfTheEncodingCategoryInOrder) {
    const std::vector<CheckSpec> specs = checks::encoding_checks();
    ASSERT_FALSE(specs.empty());
    int last = 0;
    for (const CheckSpec& s : specs) {
        EXPECT_TRUE(s.id.starts_with("encoding.")) << s.id;
        EXPECT_EQ(s.category, Category::kEncoding) << s.id;
        EXPECT_EQ(s.run, nullptr) << s.id;  // the encoding phase reports it, not a check
        EXPECT_GT(s.order, last) << s.id;
        last = s.order;
        const CheckSpec* found = find_check(s.id);
        ASSERT_NE(found, nullptr) << s.id;
        EXPECT_EQ(found->order, s.order) << s.id;
    }
    CheckSelection selection;
    selection.only = {"encoding.int"};
    EXPECT_TRUE(selection.wants_writes());  // selecting one needs the writes of the phase
    selection.only = {"cdi.*"};
    EXPECT_FALSE(selection.wants_writes());
}

}  // namespace
}  // namespace olcb::conform
