// A scene's [test_particles] table: massless bodies about the star of a
// planetary system, run with its planets by one wh(...) method.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "methods/run_plan.hpp"
#include "commands/run_test_particles.hpp"
#include "reading/scene_reader.hpp"

namespace sympl::app {

namespace {

std::size_t checked_count(const reader& r, const toml::node& n, const std::string& key, std::int64_t low,
                          std::int64_t high) {
    const auto v = n.value<std::int64_t>();
    if (!n.is_integer() || !v || *v < low || *v > high)
        r.fail(n, "'" + key + "' = " + reader::text_of(n) + "; expected an integer in [" + std::to_string(low) + ", " +
                      std::to_string(high) + "]");
    return std::size_t(*v);
}

// grid.a or grid.e: {from, to, count}, every value inside [low, high) (a > 0; 0 <= e < 1).
ensemble_axis read_axis(const reader& r, const toml::node& n, const std::string& name, double low, bool low_open,
                        double high, const std::string& range) {
    const std::string key = "test_particles.grid." + name;
    const toml::table* t = n.as_table();
    if (!t) r.fail(n, "'" + key + "' must be {from = ..., to = ..., count = ...}");
    r.only_keys(*t, {"from", "to", "count"}, key);
    r.need_keys(n, *t, {"from", "to", "count"}, key);
    ensemble_axis axis{name, r.number(*t->get("from"), key + ".from"), r.number(*t->get("to"), key + ".to"),
                       checked_count(r, *t->get("count"), key + ".count", 1, 1000000)};
    for (const auto& [end, v] : {std::pair{"from", axis.from}, std::pair{"to", axis.to}})
        if (!std::isfinite(v) || v < low || (low_open && v == low) || v >= high)
            r.fail(*t->get(end), "'" + key + "." + end + "' = " + shortest(v) + "; expected " + range);
    if (axis.count > 1 && axis.from == axis.to)
        r.fail(*t->get("count"), "'" + key + "' from = to = " + shortest(axis.from) + " with count = " +
                                     std::to_string(axis.count) + "; expected count = 1 for a single value");
    return axis;
}

// An angle in degrees: finite (any turn).
double read_angle(const reader& r, const toml::table& t, const char* key) {
    const toml::node* n = t.get(key);
    if (!n) return 0;
    const double v = r.number(*n, std::string("test_particles.") + key);
    if (!std::isfinite(v))
        r.fail(*n, std::string("'test_particles.") + key + "' = " + shortest(v) + "; expected a finite angle in degrees");
    return v;
}

// The system and the method a population of test particles can run with.
void check_planetary_run(const reader& r, const toml::node& node, const scene& s, const toml::array& methods) {
    const runnable_system p = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
    if (!p.form.planetary || p.masses.size() < 2)
        r.fail(node, "[test_particles] needs a planetary system (a star and planets with masses and G); '" + s.system +
                         "' is not one (expected system = \"outer_solar_system\")");
    if (s.methods.size() != 1 || s.methods[0].kind != method_kind::wisdom_holman)
        r.fail(methods, "[test_particles] runs one Wisdom-Holman method; expected methods = [\"wh(<table>, ...)\"], "
                        "not " + std::to_string(s.methods.size()) + " method(s) starting with '" + s.methods[0].name +
                        "'");
    if (sweep_of(s, s.methods[0]).size() != 1)
        r.fail(node, "[test_particles] runs one step size; expected dt = <number>, not a sweep");
    if (s.ensemble) r.fail(node, "[test_particles] with [ensemble]; expected one of them");
}

}  // namespace

test_particle_spec read_test_particles(const reader& r, const toml::node& node, const scene& s,
                                       const toml::array& methods) {
    const toml::table* t = node.as_table();
    if (!t) r.fail(node, "'test_particles' must be a table with grid (or elements) and indicator");
    r.only_keys(*t, {"grid", "elements", "indicator", "inclination", "node", "pericentre", "mean_anomaly"},
                "[test_particles]");
    test_particle_spec tp;
    const toml::node* grid = t->get("grid");
    const toml::node* elements = t->get("elements");
    if (!grid == !elements)
        r.fail(node, "[test_particles] needs either grid = {a = {from, to, count}, e = {from, to, count}} or "
                     "elements = \"file.csv\"");
    if (grid) {
        const toml::table* g = grid->as_table();
        if (!g) r.fail(*grid, "'test_particles.grid' must be {a = {from, to, count}, e = {from, to, count}}");
        r.only_keys(*g, {"a", "e"}, "test_particles.grid");
        r.need_keys(*grid, *g, {"a", "e"}, "test_particles.grid");
        tp.a = read_axis(r, *g->get("a"), "a", 0, true, INFINITY, "a finite semi-major axis > 0 (AU)");
        tp.e = read_axis(r, *g->get("e"), "e", 0, false, 1, "an eccentricity in [0, 1) (elliptic orbits)");
        const double total = double(tp.a.count) * double(tp.e.count);
        if (total > max_test_particles)
            r.fail(*grid, "the grid has " + std::to_string(tp.a.count) + " x " + std::to_string(tp.e.count) + " = " +
                              std::to_string(tp.a.count * tp.e.count) + " test particles; expected at most " +
                              std::to_string(std::size_t(max_test_particles)));
        // The grid's extreme orbits: least pericentre and greatest apocentre at the largest e.
        const double e_max = std::max(tp.e.from, tp.e.to);
        for (double a_end : {std::min(tp.a.from, tp.a.to), std::max(tp.a.from, tp.a.to)})
            if (const std::string why = orbit_outside(a_end, e_max); !why.empty())
                r.fail(*grid, "test_particles.grid holds " + why);
        tp.inclination = read_angle(r, *t, "inclination");
        tp.node = read_angle(r, *t, "node");
        tp.pericentre = read_angle(r, *t, "pericentre");
        tp.mean_anomaly = read_angle(r, *t, "mean_anomaly");
    } else {
        for (const char* angle : {"inclination", "node", "pericentre", "mean_anomaly"})
            if (const toml::node* n = t->get(angle))
                r.fail(*n, std::string("'test_particles.") + angle + "' with elements = \"...\": the file gives the "
                           "angles; expected it only with grid");
        tp.elements_file = r.string(*elements, "test_particles.elements");
        if (tp.elements_file.empty()) r.fail(*elements, "'test_particles.elements' is empty; expected a CSV file name");
        if (!s.source.empty() && !s.source.starts_with("built-in") &&
            std::filesystem::path(tp.elements_file).is_relative())
            tp.elements_file = (std::filesystem::path(s.source).parent_path() / tp.elements_file).string();
    }
    if (const toml::node* i = t->get("indicator")) {
        const std::string v = r.string(*i, "test_particles.indicator");
        if (v != "megno" && v != "none")
            r.fail(*i, "test_particles.indicator = '" + v + "'; expected \"megno\" or \"none\"");
        tp.megno = v == "megno";
    }
    check_planetary_run(r, node, s, methods);
    return tp;
}

}  // namespace sympl::app
