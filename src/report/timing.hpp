#pragma once
// The one timing procedure of the program and the benchmarks: a measurement
// repeats a call until it has lasted a least time and gives the time per
// call; several measurements give the median, with min and max beside it.
// Shared machines are noisy: the median of repeated measurements, taken where
// possible in rounds interleaved between contenders, is what is compared.
#include <algorithm>
#include <chrono>
#include <vector>

namespace sympl::app {

struct timing {
    double median = -1, min = -1, max = -1;  // seconds per call; -1: not timed
};

inline double clock_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The clock's resolution as seen: the smallest nonzero step between two
// successive readings (at most the tick, at least the cost of a reading).
inline double clock_resolution() {
    double best = 1;
    for (int k = 0; k < 1000; ++k) {
        const auto a = std::chrono::steady_clock::now();
        auto b = std::chrono::steady_clock::now();
        while (b == a) b = std::chrono::steady_clock::now();
        best = std::min(best, std::chrono::duration<double>(b - a).count());
    }
    return best;
}

// One measurement: f called until `least` seconds have passed; seconds per call.
template <class F>
double seconds_per_call(F&& f, double least) {
    std::size_t calls = 0;
    const double start = clock_seconds();
    double elapsed = 0;
    do {
        f();
        ++calls;
        elapsed = clock_seconds() - start;
    } while (elapsed < least);
    return elapsed / double(calls);
}

inline timing summary_of(std::vector<double> samples) {
    if (samples.empty()) return {};
    std::sort(samples.begin(), samples.end());
    return {samples[samples.size() / 2], samples.front(), samples.back()};
}

// `repeats` measurements of f, each lasting at least `least` seconds.
template <class F>
timing time_per_call(F&& f, int repeats, double least) {
    std::vector<double> samples;
    for (int k = 0; k < repeats; ++k) samples.push_back(seconds_per_call(f, least));
    return summary_of(std::move(samples));
}

}  // namespace sympl::app
