// `sympl check-table`.
#include "commands/check_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>

#include "reading/coefficient_list.hpp"
#include "output/format.hpp"

namespace sympl::app {

// The exact order from the BCH series to degree 11 certifies orders up to 10.
constexpr int algebraic_degree = 11;

namespace {

// How far the typed coefficients may be from the intended ones: half a unit
// in the last digit given, the largest over the list ("1.3512" -> 5e-5;
// integers and "2e-1" without a point are taken as exact).
double given_rounding(const std::string& text) {
    double largest = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find(',', start), text.size());
        const std::string token = text.substr(start, end - start);
        const std::size_t e = token.find_first_of("eE"), point = token.find('.');
        if (point != std::string::npos && point < e) {
            std::size_t decimals = 0;
            for (std::size_t i = point + 1; i < std::min(e, token.size()); ++i) decimals += std::isdigit(token[i]) != 0;
            const double exponent = e == std::string::npos ? 0 : std::strtod(token.c_str() + e + 1, nullptr);
            largest = std::max(largest, 0.5 * std::pow(10.0, exponent - double(decimals)));
        }
        start = end + 1;
    }
    return largest;
}

// The order to believe, in words: the series' exact order, or the measured one
// when the only unmet condition is as small as the given digits' rounding
// leaves it (a table typed to 5 digits satisfies its conditions to ~1e-5; each
// condition is a polynomial of the coefficients, moved by about stages x rounding).
struct order_verdict {
    int order = 0;
    std::string text;
};
order_verdict verdict(const sympl::order_conditions_reading& exact, double measured, double rounding,
                      std::size_t stages) {
    const long read = std::lround(measured);
    if (!exact.representable) return {int(read), "order " + std::to_string(read) + " (measured; no series)"};
    if (exact.general >= algebraic_degree) return {exact.general, "order at least " + std::to_string(algebraic_degree)};
    const double leaves = 10 * double(stages) * rounding;
    if (read > exact.general && std::abs(measured - double(read)) < 0.2 && exact.leading_error <= leaves)
        return {int(read), "order " + std::to_string(read) + " up to rounding of the given digits (|E_" +
                               std::to_string(exact.general + 1) + "| = " + scientific(exact.leading_error, 2) +
                               " is what digits rounded by " + scientific(rounding, 0) +
                               " leave; more digits give the exact order)"};
    std::string text = "order " + std::to_string(exact.general) + " (exact, from the BCH series";
    if (read != exact.general) text += "; the measured slope " + fixed(measured, 2) + " is not the asymptotic one";
    return {exact.general, text + ")"};
}

}  // namespace

int check_table(const std::string& kick_text, const std::string& drift_text, const std::string& convention, bool json) {
    const auto kick = parse_coefficient_list(kick_text, "--kick");
    const auto drift = parse_coefficient_list(drift_text, "--drift");
    const sympl::table t = convention == "seed"          ? sympl::from_seed("user", kick, drift)
                           : convention == "drift-first" ? sympl::from_drift_first("user", drift, kick)
                                                         : sympl::table("user", kick, drift);
    const auto quadratic = sympl::measure_order(t, sympl::order_problem::pendulum);
    const auto general = sympl::measure_order(t, sympl::order_problem::nonquadratic_kinetic);
    const sympl::order_conditions_reading exact = sympl::read_order_conditions(t, algebraic_degree);
    order_verdict v = verdict(exact, general.order,
                              std::max(given_rounding(kick_text), given_rounding(drift_text)), t.stages());
    if (exact.representable && exact.quadratic > exact.general)
        v.text += "; for T = p^2/2 order " + std::to_string(exact.quadratic);
    const auto range = [](const sympl::order_measurement& m) {
        return nlohmann::json{{"largest_difference", m.largest_difference},
                              {"smallest_difference", m.smallest_difference},
                              {"agreeing_slopes", m.agreeing},
                              {"coefficient_rounding_below", m.rounding_level}};
    };
    if (json) {
        const nlohmann::json out = {{"stages", t.stages()},
                                    {"force_evaluations", t.force_evaluations()},
                                    {"symmetric", t.is_symmetric()},
                                    {"order", std::round(quadratic.order * 1000) / 1000},
                                    {"order_read", range(quadratic)},
                                    {"order_general", std::round(general.order * 1000) / 1000},
                                    {"order_general_read", range(general)},
                                    {"stability_interval", t.stability_interval()},
                                    {"error_at_equal_cost", sympl::error_at_equal_cost(t)},
                                    {"algebraic_order", exact.representable ? nlohmann::json(exact.general) : nlohmann::json()},
                                    {"algebraic_order_quadratic_T",
                                     exact.representable ? nlohmann::json(exact.quadratic) : nlohmann::json()},
                                    {"leading_error",
                                     exact.representable ? nlohmann::json(exact.leading_error) : nlohmann::json()},
                                    {"verdict_order", v.order},
                                    {"verdict", v.text},
                                    {"kick", as_doubles(t.kick())},
                                    {"drift", as_doubles(t.drift())}};
        std::cout << out.dump() << "\n";
        return 0;
    }
    const auto where = [](const sympl::order_measurement& m) {
        std::string w = "read where |x(dt) - x(dt/2)| fell from " + scientific(m.largest_difference, 1) + " to " +
                        scientific(m.smallest_difference, 1) + " (" + std::to_string(m.agreeing) + " slopes agreeing";
        if (m.rounding_level > 0)
            w += "; below " + scientific(m.rounding_level, 1) + " the rounding of the coefficients sets the slope";
        return w + ")";
    };
    std::cout << "canonical table (kick first):\n  kick  = " << nlohmann::json(as_doubles(t.kick())).dump()
              << "\n  drift = " << nlohmann::json(as_doubles(t.drift())).dump() << "\n"
              << "stages              " << t.stages() << "\n"
              << "force_evaluations   " << t.force_evaluations() << "\n"
              << "symmetric           " << (t.is_symmetric() ? "yes" : "no") << "\n"
              << "order               " << fixed(quadratic.order, 2) << "   pendulum, T = p^2/2; " << where(quadratic) << "\n"
              << "order_general       " << fixed(general.order, 2) << "   relativistic pendulum, T = sqrt(1+p^2); "
              << where(general) << "\n"
              << "algebraic_order     ";
    if (!exact.representable) {
        std::cout << "-      the coefficients overflow the series (magnitudes near the double range)\n";
    } else {
        const auto shown = [](int p) {
            return p == algebraic_degree ? std::to_string(p) + "+" : std::to_string(p);
        };
        std::cout << std::left << std::setw(7) << shown(exact.general) << std::right
                  << "exact, from the BCH series; T = p^2/2: " << shown(exact.quadratic);
        if (exact.general < algebraic_degree)
            std::cout << "; first unmet condition |E_" << exact.general + 1 << "| = "
                      << scientific(exact.leading_error, 2);
        std::cout << "\n";
    }
    std::cout << "verdict             " << v.text << "\n";
    std::cout << "stability_interval  " << fixed(t.stability_interval(), 4)
              << "   largest omega*dt stable on the harmonic oscillator\n"
              << "error_at_equal_cost " << scientific(sympl::error_at_equal_cost(t), 2)
              << "   pendulum at t = 3 with 300 force evaluations\n";
    return 0;
}

}  // namespace sympl::app
