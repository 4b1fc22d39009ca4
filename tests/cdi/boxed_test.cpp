#include "cdi/boxed.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

TEST(Boxed, BehavesLikeAnOptional) {
    Boxed<std::string> box;
    EXPECT_FALSE(box);
    EXPECT_FALSE(box.has_value());
    EXPECT_EQ(box, std::nullopt);
    EXPECT_EQ(box.value_or("none"), "none");
    box = "text";  // converts
    ASSERT_TRUE(box);
    EXPECT_EQ(*box, "text");
    EXPECT_EQ(box->size(), 4u);
    EXPECT_EQ(box, "text");
    EXPECT_FALSE(box == "other");
    EXPECT_EQ(box.value_or("none"), "text");
    box = std::nullopt;
    EXPECT_FALSE(box);
    box.emplace(3, 'x');
    EXPECT_EQ(*box, "xxx");
    box.reset();
    EXPECT_FALSE(box);
}

TEST(Boxed, TakesAnOptional) {
    Boxed<double> box;
    box = std::optional<double>(2.5);
    EXPECT_EQ(box, 2.5);
    box = std::optional<double>();
    EXPECT_FALSE(box);
}

TEST(Boxed, CopiesAreDeepAndMovesEmptyTheSource) {
    Boxed<std::vector<int>> a = std::vector<int>{1, 2};
    Boxed<std::vector<int>> b = a;
    b->push_back(3);
    EXPECT_EQ(a->size(), 2u);
    EXPECT_EQ(b->size(), 3u);
    EXPECT_FALSE(a == b);
    a = b;
    EXPECT_TRUE(a == b);
    EXPECT_NE(&*a, &*b);
    Boxed<std::vector<int>> c = std::move(a);
    EXPECT_FALSE(a);  // NOLINT(bugprone-use-after-move): a moved-from box is empty
    EXPECT_EQ(c->size(), 3u);
    Boxed<std::vector<int>> empty;
    c = empty;
    EXPECT_FALSE(c);
    EXPECT_TRUE(c == empty);
}

}  // namespace
}  // namespace olcb::cdi
