// run_sort against std::stable_sort: the same order (equal keys keep their input order) for
// already sorted input, a few ascending runs (merged) and many (the full sort).
#include "base/run_sort.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

namespace olcb::base {
namespace {

using Item = std::pair<int, int>;  // key, input position

bool by_key(const Item& a, const Item& b) {
    return a.first < b.first;
}

// `runs` ascending runs of random keys (with repeats), each item tagged with its position.
std::vector<Item> runs_of(std::size_t runs, std::size_t length, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> key(0, 50);
    std::vector<Item> items;
    for (std::size_t r = 0; r < runs; ++r) {
        std::vector<int> keys(length);
        for (int& k : keys) k = key(random);
        std::sort(keys.begin(), keys.end());
        for (int k : keys) items.emplace_back(k, static_cast<int>(items.size()));
    }
    return items;
}

void expect_as_stable_sort(std::vector<Item> items) {
    std::vector<Item> expected = items;
    std::stable_sort(expected.begin(), expected.end(), by_key);
    run_sort(items.begin(), items.end(), by_key);
    EXPECT_EQ(items, expected);
}

TEST(RunSortTest, OrdersLikeStableSortForAnyNumberOfRuns) {
    for (std::size_t runs : {std::size_t{1}, std::size_t{2}, std::size_t{3}, kMaxMergedRuns,
                             kMaxMergedRuns + 1, std::size_t{40}}) {
        for (unsigned seed = 1; seed <= 5; ++seed) {
            SCOPED_TRACE(testing::Message() << runs << " runs, seed " << seed);
            expect_as_stable_sort(runs_of(runs, 37, seed));
        }
    }
}

TEST(RunSortTest, EmptyAndSingleAndDescending) {
    expect_as_stable_sort({});
    expect_as_stable_sort({{4, 0}});
    std::vector<Item> descending;
    descending.reserve(100);
    for (int i = 0; i < 100; ++i) descending.emplace_back(100 - i, i);
    expect_as_stable_sort(descending);  // 100 runs of one: the full sort
}

}  // namespace
}  // namespace olcb::base
