// A scene's [ensemble] table.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "reading/scene_reader.hpp"

namespace sympl::app {

// [ensemble]: a grid over the system's parameters or a CSV of states, one
// table, one dt. Counts are range-checked here; grid points that are not
// valid states become rows of status `invalid` when the ensemble runs.
ensemble_spec read_ensemble(const reader& r, const toml::node& node, const scene& s, const system_entry& entry,
                            const toml::array& methods) {
    const toml::table* t = node.as_table();
    if (!t) r.fail(node, "'ensemble' must be a table with grid (or states) and indicator");
    r.only_keys(*t, {"grid", "states", "indicator", "sample_every", "orbits"}, "[ensemble]");
    ensemble_spec e;
    const auto integer = [&](const toml::node& n, const std::string& key, std::int64_t low, std::int64_t high) {
        const auto v = n.value<std::int64_t>();
        if (!n.is_integer() || !v || *v < low || *v > high)
            r.fail(n, "'" + key + "' must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
        return std::size_t(*v);
    };
    const toml::node* grid = t->get("grid");
    const toml::node* states = t->get("states");
    if (!grid == !states) r.fail(node, "[ensemble] needs either grid = {name = {from, to, count}, ...} or states = \"file.csv\"");
    if (grid) {
        const toml::table* g = grid->as_table();
        if (!g || g->empty()) r.fail(*grid, "'ensemble.grid' must be a table of {from, to, count} per parameter");
        std::set<std::string> known;
        for (const auto& q : entry.parameters) known.insert(q.name);
        r.only_keys(*g, known, "ensemble.grid of " + s.system);
        std::vector<std::pair<toml::source_position, ensemble_axis>> axes;
        for (const auto& [key, n] : *g) {
            const std::string name(key.str());
            if (!known.count(name)) continue;  // noted by only_keys
            const toml::table* a = n.as_table();
            if (!a) r.fail(n, "'ensemble.grid." + name + "' must be {from = ..., to = ..., count = ...}");
            r.only_keys(*a, {"from", "to", "count"}, "ensemble.grid." + name);
            r.need_keys(n, *a, {"from", "to", "count"}, "ensemble.grid." + name);
            ensemble_axis axis{name, r.number(*a->get("from"), name + ".from"), r.number(*a->get("to"), name + ".to"),
                               integer(*a->get("count"), name + ".count", 1, 1000000)};
            if (!std::isfinite(axis.from) || !std::isfinite(axis.to))
                r.fail(n, "'ensemble.grid." + name + "' from = " + shortest(axis.from) + ", to = " + shortest(axis.to) +
                              "; expected finite numbers");
            axes.emplace_back(n.source().begin, axis);
        }
        // toml++ keeps keys sorted: the file's order comes from their positions.
        std::sort(axes.begin(), axes.end(), [](const auto& a, const auto& b) {
            return std::pair(a.first.line, a.first.column) < std::pair(b.first.line, b.first.column);
        });
        for (auto& [where, axis] : axes) e.grid.push_back(axis);
        double total = 1;
        for (const auto& axis : e.grid) total *= double(axis.count);
        if (total > max_ensemble_size)
            r.fail(*grid, "the grid has " + shortest(total) + " points; expected at most " + shortest(max_ensemble_size));
    } else {
        e.states_file = r.string(*states, "ensemble.states");
        if (e.states_file.empty()) r.fail(*states, "'ensemble.states' is empty; expected a CSV file name");
        if (!s.source.empty() && s.source != "built-in" && std::filesystem::path(e.states_file).is_relative())
            e.states_file = (std::filesystem::path(s.source).parent_path() / e.states_file).string();
    }
    if (const toml::node* i = t->get("indicator")) {
        const std::string v = r.string(*i, "ensemble.indicator");
        if (v != "megno" && v != "none") r.fail(*i, "ensemble.indicator = '" + v + "'; expected \"megno\" or \"none\"");
        e.megno = v == "megno";
    }
    if (const toml::node* k = t->get("sample_every")) e.sample_every = integer(*k, "ensemble.sample_every", 1, 1000000000);
    if (const toml::node* k = t->get("orbits")) e.orbits = integer(*k, "ensemble.orbits", 0, 100);
    if (s.methods.size() != 1 || s.methods[0].kind != method_kind::table || s.methods[0].compensated ||
        s.methods[0].extrapolation_columns > 0)
        r.fail(methods, "an ensemble runs one splitting table; expected methods = [\"<table>\"] (one catalog or [[table]] name)");
    if (s.methods[0].coefficients->has_force_gradient())
        r.fail(methods, "an ensemble runs plain kick-drift tables; '" + s.methods[0].name +
                            "' has force-gradient kicks (expected a catalog or [[table]] name)");
    if (s.dt.size() != 1) r.fail(node, "an ensemble runs one step size; expected dt = <number>, not a sweep");
    return e;
}

}  // namespace sympl::app
