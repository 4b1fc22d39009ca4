// A stable sort for sequences that are nearly sorted already: a CDI's variables follow each other
// in memory and each validation pass reports in document order, so what needs sorting is a few
// ascending runs. Merging those is linear per run; std::sort and std::stable_sort pay n log n
// whatever the order (a third of the layout's cost on the largest corpus CDI).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace olcb::base {

/// Runs beyond which merging them one by one costs more than a full stable sort.
inline constexpr std::size_t kMaxMergedRuns = 8;

/// Stable sort of [first, last) by `less`: ascending runs are merged when there are at most
/// kMaxMergedRuns of them, else std::stable_sort.
template <typename It, typename Less>
void run_sort(It first, It last, Less less) {
    std::array<It, kMaxMergedRuns> runs{};  // the start of each ascending run
    std::size_t count = 0;
    for (It it = first; it != last;) {
        if (count == kMaxMergedRuns) {
            std::stable_sort(first, last, less);
            return;
        }
        runs[count++] = it;
        It next = std::next(it);
        while (next != last && !less(*next, *std::prev(next))) ++next;
        it = next;
    }
    // Each merge joins the sorted prefix with the next run; earlier elements stay first on ties.
    for (std::size_t i = 1; i < count; ++i) {
        std::inplace_merge(first, runs[i], i + 1 < count ? runs[i + 1] : last, less);
    }
}

}  // namespace olcb::base
