#pragma once
// A comma-separated list of coefficients as `check-table` reads it
// ("0.5,0.5"): every token a number, no empty or trailing field, at most
// max_check_table_stages values. Errors name the option and the bad token.
#include <cstddef>
#include <string>
#include <vector>

#include <sympl/core/table.hpp>

namespace sympl::app {

// check-table measures orders by running the table thousands of times in
// 113-bit precision: 256 stages take about 3 s, 1000 over a minute.
inline constexpr std::size_t max_check_table_stages = 256;

std::vector<coefficient> parse_coefficient_list(const std::string& text, const std::string& option);

// Coefficients as JSON and tables print them (double precision).
inline std::vector<double> as_doubles(const std::vector<coefficient>& c) { return {c.begin(), c.end()}; }

}  // namespace sympl::app
