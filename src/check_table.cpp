// `sympl check-table`.
#include "check_table.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>

#include "coefficient_list.hpp"
#include "format.hpp"

namespace sympl::app {

// The exact order from the BCH series to degree 11 certifies orders up to 10.
constexpr int algebraic_degree = 11;

int check_table(const std::string& kick_text, const std::string& drift_text, const std::string& convention, bool json) {
    const auto kick = parse_coefficient_list(kick_text, "--kick");
    const auto drift = parse_coefficient_list(drift_text, "--drift");
    const sympl::table t = convention == "seed"          ? sympl::from_seed("user", kick, drift)
                           : convention == "drift-first" ? sympl::from_drift_first("user", drift, kick)
                                                         : sympl::table("user", kick, drift);
    const auto quadratic = sympl::measure_order(t, sympl::order_problem::pendulum);
    const auto general = sympl::measure_order(t, sympl::order_problem::nonquadratic_kinetic);
    const sympl::order_conditions_reading exact = sympl::read_order_conditions(t, algebraic_degree);
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
    std::cout << "stability_interval  " << fixed(t.stability_interval(), 4)
              << "   largest omega*dt stable on the harmonic oscillator\n"
              << "error_at_equal_cost " << scientific(sympl::error_at_equal_cost(t), 2)
              << "   pendulum at t = 3 with 300 force evaluations\n";
    return 0;
}

}  // namespace sympl::app
