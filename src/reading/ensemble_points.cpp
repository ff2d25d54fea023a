// An ensemble's trajectories: grid points or states of a CSV file.
#include "reading/ensemble_points.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "reading/csv_numbers.hpp"
#include "reading/file_text.hpp"
#include "output/format.hpp"
#include "methods/run_plan.hpp"
#include "running/systems.hpp"

namespace sympl::app {

namespace {

// Points with equal keys share one Hamiltonian (their parameters of H agree).
std::string key_of(const system_entry& entry, const parameter_values& v) {
    std::string key;
    for (const auto& q : entry.parameters)
        if (!q.initial_state) key += q.name + "=" + shortest(v.at(q.name)) + ";";
    return key;
}

}  // namespace

std::vector<std::vector<double>> read_states(const std::string& path, const std::vector<std::string>& columns) {
    const file_text read = read_file_text(path, max_states_bytes);
    if (!read.failure.empty()) throw scene_error(printable(path) + ": the states file " + read.failure);
    std::istringstream in(read.text);
    std::string line;
    std::size_t number = 0;
    std::vector<std::vector<double>> states;
    const std::size_t dof = columns.size() / 2;
    std::string expected_header;
    for (const auto& c : columns) expected_header += (expected_header.empty() ? "" : ",") + c;
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string where = printable(path) + ":" + std::to_string(number) + ": ";
        if (number == 1) {
            if (line != expected_header)
                throw scene_error(where + "header '" + line + "'; expected '" + expected_header + "'");
            continue;
        }
        if (line.empty()) continue;
        std::vector<double> x = csv_numbers(line, where);
        if (x.size() != 2 * dof)
            throw scene_error(where + std::to_string(x.size()) + " numbers; expected " + std::to_string(2 * dof) +
                              " (" + columns.front() + ".." + columns.back() + ")");
        if (double(states.size()) >= max_ensemble_size)
            throw scene_error(where + "more than " + shortest(max_ensemble_size) + " states; expected at most that");
        states.push_back(std::move(x));
    }
    if (number == 0) throw scene_error(printable(path) + ": empty; expected the header '" + expected_header + "' and states");
    return states;
}

ensemble_point point_at(const scene& s, const system_entry& entry, const parameter_values& defaults, std::size_t index,
               const std::vector<std::vector<double>>& states) {
    ensemble_point pt;
    pt.parameters = s.parameters;
    std::vector<double> q0 = s.q0, p0 = s.p0;
    const ensemble_spec& e = *s.ensemble;
    if (!e.grid.empty()) {
        std::size_t rest = index;
        pt.grid_values.resize(e.grid.size());
        for (std::size_t a = e.grid.size(); a-- > 0;) {
            pt.grid_values[a] = e.grid[a].value(rest % e.grid[a].count);
            rest /= e.grid[a].count;
        }
        for (std::size_t a = 0; a < e.grid.size(); ++a) {
            const parameter& q = *entry.find(e.grid[a].name);
            if (!q.accepts(pt.grid_values[a]) && pt.invalid.empty())
                pt.invalid = q.name + " = " + shortest(pt.grid_values[a]) + "; expected " + q.expected();
            pt.parameters[q.name] = pt.grid_values[a];
        }
    } else {
        pt.grid_values = states[index];
        const std::size_t n = states[index].size() / 2;
        q0.assign(states[index].begin(), states[index].begin() + std::ptrdiff_t(n));
        p0.assign(states[index].begin() + std::ptrdiff_t(n), states[index].end());
    }
    parameter_values merged = defaults;
    for (const auto& [k, v] : pt.parameters) merged[k] = v;
    pt.hamiltonian_key = key_of(entry, merged);
    if (!pt.invalid.empty()) return pt;
    try {
        const runnable_system p = make_system(s.system, pt.parameters, q0, p0, "");
        if (p.energy && !std::isfinite(p.energy(p.x0)))
            pt.invalid = "the start has energy " + shortest(p.energy(p.x0)) + "; expected a finite energy";
        else
            pt.x0 = p.x0;
    } catch (const error& err) {
        std::string why = err.what();
        if (why.rfind(": ", 0) == 0) why.erase(0, 2);
        pt.invalid = why;
    }
    return pt;
}

ensemble_setup set_up_ensemble(const scene& s, double max_steps) {
    if (!s.ensemble) throw invalid_argument(printable(s.source) + ": the scene has no [ensemble] table");
    const ensemble_spec& e = *s.ensemble;
    ensemble_setup u{.s = &s, .entry = find_system(s.system), .base = system_of(s)};
    if (!u.base.ensemble)
        throw invalid_argument(printable(s.source) + ": " + s.system +
                               " is not a separable Hamiltonian H = T(p) + V(q); an ensemble runs splitting tables on one");
    const double span_steps = std::ceil((s.t_end - s.t0) / s.dt[0] - 1e-9);
    if (!(span_steps <= max_steps))
        throw invalid_argument(printable(s.source) + ": each trajectory at dt = " + shortest(s.dt[0]) + " over t = " + shortest(s.t0) +
                               " .. " + shortest(s.t_end) + " takes " + format_number(span_steps, 6) +
                               " steps; the limit is " + format_number(max_steps, 6) + " (raise it with --max-steps)");
    if (e.grid.empty()) u.states = read_states(e.states_file, state_columns(u.base.system, u.base.degrees_of_freedom));
    u.trajectories = e.grid.empty() ? u.states.size() : e.size();
    // What the ensemble holds until it writes (docs/reliability.md, "Memory"):
    // per trajectory its point (start, parameters, grid values), its row
    // (final state), and ensemble.csv's line twice (a block's text, then all
    // blocks'): about 25 characters a number.
    const double n = double(u.base.degrees_of_freedom), axes = double(e.grid.size());
    const double per_trajectory = 640 + 96 * double(u.entry->parameters.size()) + 2 * 2 * n * 8 +
                                  2 * 25 * (4 * n + axes + 8);
    const double held = double(u.trajectories) * per_trajectory;
    if (!(held <= memory_budget_bytes))
        throw invalid_argument(printable(s.source) + ": " + std::to_string(u.trajectories) + " trajectories of " +
                               format_number(n, 6) + " degrees of freedom would hold " +
                               format_number(held / double(1 << 30), 3) + " GiB (about " +
                               format_number(per_trajectory, 3) + " bytes each: start, row and ensemble.csv's line); "
                               "the limit is " + format_number(memory_budget_bytes / double(1 << 30), 3) +
                               " GiB (docs/reliability.md, \"Memory\"); expected fewer points");
    const double total = double(u.trajectories) * span_steps;
    if (total > 1e4 * max_steps)
        throw invalid_argument(printable(s.source) + ": " + std::to_string(u.trajectories) + " trajectories of " +
                               format_number(span_steps, 6) + " steps are " + format_number(total, 6) +
                               " trajectory-steps; the limit is 1e4 times --max-steps = " + format_number(1e4 * max_steps, 6));
    u.defaults = with_defaults(*u.entry, s.parameters, s.source);
    u.request.method = s.methods[0].coefficients;
    u.request.t0 = s.t0;
    u.request.dt = s.dt[0];
    u.request.steps = std::size_t(span_steps);
    u.request.sample_every = std::min<std::size_t>(e.sample_every, u.request.steps);
    u.request.megno = e.megno;
    return u;
}

}  // namespace sympl::app
