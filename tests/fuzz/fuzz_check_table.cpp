// libFuzzer target: check-table's input. The bytes are two lines, the kick
// and the drift list; they are parsed and made into a table, whose canonical
// form, symmetry, stability interval and order conditions (to degree 6, where
// coefficients near the double range overflow the series) are computed (the
// order measurement is left out: it is the slow part, fed only by valid
// tables). Success or
// sympl::error; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include <sympl/core/error.hpp>
#include <sympl/analysis/order_conditions.hpp>
#include <sympl/core/table.hpp>

#include "reading/coefficient_list.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const auto newline = text.find('\n');
    const std::string kick = text.substr(0, newline), drift = newline == std::string::npos ? "" : text.substr(newline + 1);
    try {
        const sympl::table t("fuzz", sympl::app::parse_coefficient_list(kick, "--kick"),
                             sympl::app::parse_coefficient_list(drift, "--drift"));
        (void)t.is_symmetric();
        (void)t.force_evaluations();
        (void)t.stability_interval();
        (void)sympl::adjoint(t);
        (void)sympl::read_order_conditions(t, 6);
    } catch (const sympl::error&) {
    }
    return 0;
}
