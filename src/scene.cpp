// Scene files: parsing, validation with file:line:column, and the built-in set.
#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include <sympl/catalog.hpp>

#include "format.hpp"
#include "systems.hpp"

namespace sympl::app {

namespace {

std::string join(const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
    return out;
}

struct reader {
    std::string source;

    [[noreturn]] void fail(const toml::source_region& where, const std::string& what) const {
        throw scene_error(source + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column) +
                          ": " + what);
    }
    [[noreturn]] void fail(const toml::node& n, const std::string& what) const { fail(n.source(), what); }

    // Only the listed keys: anything else is a typo the user wants to hear about.
    void only_keys(const toml::table& t, const std::set<std::string>& allowed, const std::string& where) const {
        for (const auto& [key, node] : t)
            if (!allowed.count(std::string(key.str()))) {
                std::vector<std::string> names(allowed.begin(), allowed.end());
                fail(node, "unknown key '" + std::string(key.str()) + "' in " + where + "; expected one of: " + join(names));
            }
    }

    double number(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<double>(); v && (n.is_floating_point() || n.is_integer())) return *v;
        fail(n, "'" + key + "' must be a number");
    }
    double positive(const toml::node& n, const std::string& key) const {
        const double v = number(n, key);
        if (!(v > 0) || !std::isfinite(v))
            fail(n, "'" + key + "' = " + shortest(v) + "; expected a finite number > 0");
        return v;
    }
    std::string string(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<std::string>(); v && n.is_string()) return *v;
        fail(n, "'" + key + "' must be a string");
    }
    bool boolean(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<bool>(); v && n.is_boolean()) return *v;
        fail(n, "'" + key + "' must be true or false");
    }
    std::vector<double> numbers(const toml::node& n, const std::string& key) const {
        const toml::array* a = n.as_array();
        if (!a) fail(n, "'" + key + "' must be an array of numbers");
        std::vector<double> out;
        for (const auto& e : *a) out.push_back(number(e, key));
        return out;
    }

    // dt = 0.01 | [0.1, 0.05] | { from = 0.1, to = 0.001, count = 7 } (geometric)
    std::vector<double> sweep(const toml::node& n, const std::string& key) const {
        std::vector<double> out;
        if (n.is_array()) {
            for (const auto& e : *n.as_array()) out.push_back(positive(e, key));
            if (out.empty()) fail(n, "'" + key + "' is an empty array; expected at least one value");
        } else if (const toml::table* t = n.as_table()) {
            only_keys(*t, {"from", "to", "count"}, "'" + key + "'");
            const toml::node* from = t->get("from");
            const toml::node* to = t->get("to");
            const toml::node* count = t->get("count");
            if (!from || !to || !count) fail(n, "'" + key + "' needs from, to and count");
            const double a = positive(*from, key + ".from"), b = positive(*to, key + ".to");
            const auto c = count->value<std::int64_t>();
            if (!c || *c < 1 || *c > 1000) fail(*count, "'" + key + ".count' must be an integer in [1, 1000]");
            for (std::int64_t i = 0; i < *c; ++i)
                out.push_back(*c == 1 ? a : a * std::pow(b / a, double(i) / double(*c - 1)));
        } else {
            out.push_back(positive(n, key));
        }
        std::sort(out.rbegin(), out.rend());
        return out;
    }
};

// "name" or {name = "name", dt = ..., tolerances = ...}
scene_method method_by_name(const reader& r, const toml::node& n, const std::map<std::string, table>& inline_tables) {
    const toml::node* name_node = &n;
    const toml::table* t = n.as_table();
    if (t) {
        r.only_keys(*t, {"name", "dt", "tolerances"}, "a method");
        name_node = t->get("name");
        if (!name_node) r.fail(n, "a method given as a table needs a name");
    }
    const std::string name = r.string(*name_node, "methods");
    std::optional<method_spec> m;
    try {
        m = resolve_method(name, inline_tables);
    } catch (const invalid_argument& e) {
        r.fail(*name_node, e.what());
    }
    if (!m)
        r.fail(*name_node, "unknown method '" + name + "'; expected a catalog name (sympl tables), an inline [[table]], "
                           "logh(<table>), extrapolated(<table>, k), compensated(<table>), or one of: " + join(method_names_beside_tables()));
    scene_method sm{*m, {}, {}};
    if (t && t->get("dt")) sm.dt = r.sweep(*t->get("dt"), "dt");
    if (t && t->get("tolerances")) sm.tolerances = r.sweep(*t->get("tolerances"), "tolerances");
    return sm;
}

// [[table]] name = "...", kick = [...], drift = [...], order = 4, convention = "kick-first"
void read_inline_table(const reader& r, const toml::node& e, std::map<std::string, table>& tables) {
    const toml::table* t = e.as_table();
    if (!t) r.fail(e, "each [[table]] must be a table");
    r.only_keys(*t, {"name", "kick", "drift", "order", "convention"}, "[[table]]");
    if (!t->get("name") || !t->get("kick") || !t->get("drift")) r.fail(e, "[[table]] needs name, kick and drift");
    const toml::node& name_node = *t->get("name");
    const std::string name = r.string(name_node, "table.name");
    // A scene's table never hides a method of the same name, nor another of its tables.
    if (tables.count(name)) r.fail(name_node, "a second [[table]] named '" + name + "'; expected each name once");
    if (resolve_method(name, {})) r.fail(name_node, "[[table]] name '" + name + "' is already a method; expected a new name");
    const auto kick = r.numbers(*t->get("kick"), "table.kick"), drift = r.numbers(*t->get("drift"), "table.drift");
    int order = 0;
    if (const toml::node* o = t->get("order")) {
        const auto v = o->value<std::int64_t>();
        if (!o->is_integer() || !v || *v < 0 || *v > 100) r.fail(*o, "'table.order' must be an integer in [0, 100] (0: unknown)");
        order = int(*v);
    }
    const std::string convention = t->get("convention") ? r.string(*t->get("convention"), "table.convention") : "kick-first";
    std::vector<coefficient> k(kick.begin(), kick.end()), d(drift.begin(), drift.end());
    try {
        if (convention == "seed") tables.emplace(name, from_seed(name, k, d, order));
        else if (convention == "drift-first") tables.emplace(name, from_drift_first(name, d, k, order));
        else if (convention == "kick-first") tables.emplace(name, table(name, k, d, order));
        else r.fail(*t->get("convention"), "convention '" + convention + "'; expected kick-first, drift-first or seed");
    } catch (const invalid_table& x) {
        r.fail(e, x.what());
    }
}

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
            const toml::table* a = n.as_table();
            if (!a) r.fail(n, "'ensemble.grid." + name + "' must be {from = ..., to = ..., count = ...}");
            r.only_keys(*a, {"from", "to", "count"}, "ensemble.grid." + name);
            if (!a->get("from") || !a->get("to") || !a->get("count"))
                r.fail(n, "'ensemble.grid." + name + "' needs from, to and count");
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

}  // namespace

std::size_t ensemble_spec::size() const {
    std::size_t n = 1;
    for (const auto& a : grid) n *= a.count;
    return n;
}

scene parse_scene(const std::string& text, const std::string& source, bool quick) {
    const reader r{source};
    toml::table doc;
    try {
        doc = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        r.fail(e.source(), "not valid TOML: " + std::string(e.description()));
    }
    r.only_keys(doc, {"name", "system", "parameters", "initial", "methods", "table", "dt", "tolerances", "t0", "t_end",
                      "output", "quick", "checkpoint", "ensemble"},
                "the scene");
    // [quick]: what `--quick` changes (a shorter span, a shorter sweep).
    const toml::table* quick_table = nullptr;
    if (const toml::node* q = doc.get("quick")) {
        quick_table = q->as_table();
        if (!quick_table) r.fail(*q, "'quick' must be a table of t_end, dt and tolerances");
        r.only_keys(*quick_table, {"t_end", "dt", "tolerances"}, "[quick]");
    }
    const auto timing = [&](const char* key) -> const toml::node* {
        if (quick && quick_table && quick_table->get(key)) return quick_table->get(key);
        return doc.get(key);
    };
    scene s;
    s.source = source;
    s.text_hash = fnv1a_hex(text);
    const toml::source_region top{{1, 1}, {1, 1}, nullptr};
    s.name = doc.get("name") ? r.string(*doc.get("name"), "name") : source;

    const toml::node* system = doc.get("system");
    if (!system) r.fail(top, "missing 'system'; expected one of: " + join(system_names()));
    s.system = r.string(*system, "system");
    const auto& systems = system_names();
    if (std::find(systems.begin(), systems.end(), s.system) == systems.end())
        r.fail(*system, "unknown system '" + s.system + "'; expected one of: " + join(systems));

    const system_entry& entry = *find_system(s.system);
    if (const toml::node* p = doc.get("parameters")) {
        const toml::table* t = p->as_table();
        if (!t) r.fail(*p, "'parameters' must be a table of numbers");
        std::set<std::string> known;
        for (const auto& q : entry.parameters) known.insert(q.name);
        r.only_keys(*t, known, "[parameters] of " + s.system);
        for (const auto& [key, node] : *t) {
            const parameter& q = *entry.find(std::string(key.str()));
            const double v = r.number(node, q.name);
            if (!q.accepts(v)) r.fail(node, s.system + " " + q.name + " = " + shortest(v) + "; expected " + q.expected());
            s.parameters[q.name] = v;
        }
    }
    if (const toml::node* i = doc.get("initial")) {
        const toml::table* t = i->as_table();
        if (!t) r.fail(*i, "'initial' must be a table with q and p");
        r.only_keys(*t, {"q", "p"}, "[initial]");
        if (!t->get("q") || !t->get("p")) r.fail(*i, "[initial] needs both q and p");
        s.q0 = r.numbers(*t->get("q"), "initial.q");
        s.p0 = r.numbers(*t->get("p"), "initial.p");
        if (s.q0.size() != s.p0.size() || s.q0.empty())
            r.fail(*i, "initial q has " + std::to_string(s.q0.size()) + " values and p has " + std::to_string(s.p0.size()) +
                           "; expected the same number, at least one");
    }

    std::map<std::string, table> inline_tables;
    if (const toml::node* tables = doc.get("table")) {
        const toml::array* a = tables->as_array();
        if (!a) r.fail(*tables, "'table' must be an array of tables: [[table]]");
        for (const auto& e : *a) read_inline_table(r, e, inline_tables);
    }

    const toml::node* methods = doc.get("methods");
    if (!methods) r.fail(top, "missing 'methods'; expected an array of method names");
    const toml::array* ma = methods->as_array();
    if (!ma || ma->empty()) r.fail(*methods, "'methods' must be a non-empty array of method names");
    if (ma->size() > 1000) r.fail(*methods, std::to_string(ma->size()) + " methods; expected at most 1000");
    for (const auto& m : *ma) {
        s.methods.push_back(method_by_name(r, m, inline_tables));
        for (std::size_t k = 0; k + 1 < s.methods.size(); ++k)
            if (s.methods[k].name == s.methods.back().name)
                r.fail(m, "method '" + s.methods.back().name + "' is listed twice; expected each method once");
    }

    const toml::node* dt = timing("dt");
    if (!dt) r.fail(top, "missing 'dt'; expected a step size, an array, or {from, to, count}");
    s.dt = r.sweep(*dt, "dt");
    s.tolerances = timing("tolerances") ? r.sweep(*timing("tolerances"), "tolerances")
                                         : std::vector<double>{1e-3, 1e-5, 1e-7, 1e-9, 1e-11};
    if (const toml::node* t0 = doc.get("t0")) s.t0 = r.number(*t0, "t0");
    const toml::node* t_end = timing("t_end");
    if (!t_end) r.fail(top, "missing 't_end'");
    s.t_end = r.number(*t_end, "t_end");
    if (!(s.t_end > s.t0) || !std::isfinite(s.t_end))
        r.fail(*t_end, "t_end = " + shortest(s.t_end) + " is not after t0 = " + shortest(s.t0) +
                           "; expected t_end > t0");

    if (const toml::node* o = doc.get("output")) {
        const toml::table* t = o->as_table();
        if (!t) r.fail(*o, "'output' must be a table");
        r.only_keys(*t, {"energy_error", "trajectory_every", "final_state", "loop_area", "directory"}, "[output]");
        if (auto* n = t->get("energy_error")) s.output.energy_error = r.boolean(*n, "output.energy_error");
        if (auto* n = t->get("final_state")) s.output.final_state = r.boolean(*n, "output.final_state");
        if (auto* n = t->get("loop_area")) s.output.loop_area = r.boolean(*n, "output.loop_area");
        if (auto* n = t->get("directory")) s.output.directory = r.string(*n, "output.directory");
        if (auto* n = t->get("trajectory_every")) {
            const auto k = n->value<std::int64_t>();
            if (!k || !n->is_integer() || *k < 0) r.fail(*n, "'output.trajectory_every' must be an integer >= 0");
            s.output.trajectory_every = std::size_t(*k);
        }
    }
    if (const toml::node* c = doc.get("checkpoint")) {
        const toml::table* t = c->as_table();
        if (!t) r.fail(*c, "'checkpoint' must be a table {every_steps = N, file = \"...\"}");
        r.only_keys(*t, {"every_steps", "file"}, "'checkpoint'");
        const toml::node* every = t->get("every_steps");
        const toml::node* file = t->get("file");
        if (!every || !file) r.fail(*c, "'checkpoint' needs every_steps and file");
        const auto n = every->value<std::int64_t>();
        if (!every->is_integer() || !n || *n < 1 || *n > std::int64_t(1e15))
            r.fail(*every, "'checkpoint.every_steps' must be an integer in [1, 1e15]");
        s.checkpoint.every_steps = std::size_t(*n);
        s.checkpoint.file = r.string(*file, "checkpoint.file");
        if (s.checkpoint.file.empty()) r.fail(*file, "'checkpoint.file' is empty; expected a file name");
        for (std::size_t k = 0; k < s.methods.size(); ++k)
            if (const std::string why = why_not_resumable(s.methods[k]); !why.empty()) r.fail(*ma->get(k), why);
    }
    if (const toml::node* e = doc.get("ensemble")) s.ensemble = read_ensemble(r, *e, s, entry, *ma);
    return s;
}

scene load_scene(const std::string& path, bool quick) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw scene_error(path + ": cannot open the scene file");
    // Read at most one byte past the limit: /dev/zero or a huge file is refused
    // without being read into memory.
    std::string text(max_scene_bytes + 1, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(std::size_t(in.gcount()));
    if (text.size() > max_scene_bytes)
        throw scene_error(path + ": the scene file is larger than " + std::to_string(max_scene_bytes) +
                          " bytes; expected a scene of at most that size");
    if (text.find('\0') != std::string::npos)
        throw scene_error(path + ":" + std::to_string(1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(text.find('\0')), '\n')) +
                          ": a NUL byte; expected a text file (TOML)");
    return parse_scene(text, path, quick);
}

const std::vector<double>& sweep_of(const scene& s, const scene_method& m) {
    if (entry_of(m.kind).adaptive) return m.tolerances.empty() ? s.tolerances : m.tolerances;
    return m.dt.empty() ? s.dt : m.dt;
}

double finest_step(const scene& s) {
    double finest = *std::min_element(s.dt.begin(), s.dt.end());
    for (const scene_method& m : s.methods)
        if (steps_in_physical_time(m) && !m.dt.empty())
            finest = std::min(finest, *std::min_element(m.dt.begin(), m.dt.end()));
    return finest;
}

problem problem_of(const scene& s) {
    problem p = make_problem(s.system, s.parameters, s.q0, s.p0, s.source);
    // An energy that is already infinite (q at a singularity, 1e308 squared)
    // would make every energy error read 0 or NaN.
    if (p.energy)
        if (const double e0 = p.energy(p.x0); !std::isfinite(e0))
            throw scene_error(s.source + ": the initial state of " + s.system + " has energy H = " + shortest(e0) +
                              "; expected a state of finite energy");
    for (const method_spec& m : s.methods)
        if (const std::string why = why_not(m, p.form); !why.empty()) throw scene_error(s.source + ": " + why);
    return p;
}

void check_run_size(const scene& s, const problem& p, double max_steps, bool whole_sweep) {
    const double span = s.t_end - s.t0;
    const auto refuse = [&](const std::string& what, double dt, double steps) {
        throw scene_error(s.source + ": " + what + " at dt = " + shortest(dt) + " over t = " + shortest(s.t0) + " .. " +
                          shortest(s.t_end) + " takes " + format_number(steps, 3) + " steps; the limit is " +
                          format_number(max_steps, 3) + " (raise it with --max-steps)");
    };
    double finest = HUGE_VAL;
    for (const scene_method& m : s.methods) {
        if (!steps_in_physical_time(m) || entry_of(m.kind).adaptive) continue;
        const auto& sweep = sweep_of(s, m);
        const std::size_t count = whole_sweep ? sweep.size() : 1;
        const double inner = m.extrapolation_columns > 0
                                 ? double(m.extrapolation_columns) * double(m.extrapolation_columns + 1) / 2
                                 : 1.0;
        for (std::size_t i = 0; i < count; ++i) {
            finest = std::min(finest, sweep[i]);
            if (const double steps = std::ceil(span / sweep[i]) * inner; !(steps <= max_steps))
                refuse("method '" + m.name + "'", sweep[i], steps);
        }
    }
    if (!std::isfinite(finest)) finest = whole_sweep ? finest_step(s) : s.dt.front();
    if (whole_sweep) finest = std::min(finest, finest_step(s));
    // The reference (reference.hpp) runs at finest/4 and finest/2 unless the system is exact.
    if (!p.exact)
        if (const double steps = std::ceil(span / (finest / 4)) * 1.5; !(steps <= max_steps))
            refuse("the reference (its dt is a quarter of the finest step, " + shortest(finest) + ")", finest / 4, steps);
}

std::vector<scene> default_scenes(bool quick) {
    std::vector<scene> scenes;
    for (const auto& [file, text] : builtin_scene_texts()) scenes.push_back(parse_scene(text, "built-in:" + file, quick));
    return scenes;
}

}  // namespace sympl::app
