#pragma once
// The time span of a run: finite t0 and t_end with t_end > t0, checked once
// for every driver that runs from t0 to t_end.
#include <cmath>
#include <string>
#include <string_view>

#include "dual.hpp"
#include "error.hpp"

namespace sympl {

// Throws invalid_argument naming `who` and both times unless t_end > t0, both finite.
template <class T>
void check_time_span(std::string_view who, const T& t0, const T& t_end) {
    using std::isfinite;
    if (isfinite(t0) && isfinite(t_end) && t_end > t0) return;
    const auto text = [](const T& v) { return detail::number_text(static_cast<long double>(primal(v))); };
    throw invalid_argument(std::string(who) + ": t_end = " + text(t_end) + " with t0 = " + text(t0) +
                           "; expected finite times with t_end > t0");
}

}  // namespace sympl
