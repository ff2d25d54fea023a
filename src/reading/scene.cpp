// Scene files: parsing, validation with file:line:column, and the built-in set.
#include "reading/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <sympl/methods/catalog.hpp>

#include "reading/file_text.hpp"
#include "reading/scene_reader.hpp"

namespace sympl::app {

namespace {

// Every name a method can have in this scene: for "did you mean".
std::vector<std::string> method_names(const std::map<std::string, table>& inline_tables) {
    std::vector<std::string> names;
    for (const auto& [name, t] : inline_tables) names.push_back(name);
    for (const auto& t : sympl::catalog()) names.push_back(t.name());
    for (const auto& name : method_names_beside_tables()) names.push_back(name);
    return names;
}

// "name" or {name = "name", dt = ..., tolerances = ...}; nullopt for an
// unknown name (noted in the reader, which reports every one together).
std::optional<scene_method> method_by_name(const reader& r, const toml::node& n,
                                           const std::map<std::string, table>& inline_tables) {
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
        r.unknown_name(*name_node, e.what());
        return std::nullopt;
    }
    if (!m) {
        const std::string hint = did_you_mean_method(name, inline_tables);
        r.unknown_name(*name_node, "unknown method '" + name + "'; " +
                                       (hint.empty() ? did_you_mean(name, method_names(inline_tables)) : hint) +
                                       "expected a catalog name (sympl tables), an inline [[table]], "
                                       "logh(<table>), extrapolated(<table>, k), compensated(<table>), tao(<table>), "
                                       "semiexplicit(<table>), or one of: " + join(method_names_beside_tables()));
        return std::nullopt;
    }
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
    r.need_keys(e, *t, {"name", "kick", "drift"}, "[[table]]");
    const toml::node& name_node = *t->get("name");
    const std::string name = r.string(name_node, "table.name");
    // A scene's table never hides a method of the same name, nor another of its tables.
    if (tables.count(name)) r.fail(name_node, "a second [[table]] named '" + name + "'; expected each name once");
    bool taken = false;
    try {
        taken = resolve_method(name, {}).has_value();
    } catch (const invalid_argument& e) {  // a name no method has (nested too deep, a malformed pattern)
        r.fail(name_node, std::string("[[table]] name: ") + e.what());
    }
    if (taken) r.fail(name_node, "[[table]] name '" + name + "' is already a method; expected a new name");
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

}  // namespace

std::size_t ensemble_spec::size() const {
    std::size_t n = 1;
    for (const auto& a : grid) n *= a.count;
    return n;
}

namespace {

void read_initial(const reader& r, const toml::table& doc, scene& s);

// system, [parameters], [initial]
void read_system(const reader& r, const toml::table& doc, scene& s) {
    const toml::source_region top{{1, 1}, {1, 1}, nullptr};
    const toml::node* system = doc.get("system");
    if (!system) r.fail(top, "missing 'system'; expected one of: " + join(system_names()) +
                                 ", or a [system] table of formulas");
    if (const toml::table* formulas = system->as_table()) {
        read_initial(r, doc, s);
        if (const toml::node* p = doc.get("parameters"))
            r.fail(*p, "[parameters] beside a [system] of formulas; expected its parameters in the [system] table, "
                       "as parameters = {k = 1}");
        read_formula_system(r, *system, *formulas, s);
        return;
    }
    s.system = r.string(*system, "system");
    const auto& systems = system_names();
    if (std::find(systems.begin(), systems.end(), s.system) == systems.end()) {
        r.unknown_name(*system, "unknown system '" + s.system + "'; " + expected_one_of(s.system, systems));
        return;  // its parameters cannot be checked; the rest of the scene can
    }

    const system_entry& entry = *find_system(s.system);
    if (const toml::node* p = doc.get("parameters")) {
        const toml::table* t = p->as_table();
        if (!t) r.fail(*p, "'parameters' must be a table of numbers");
        std::set<std::string> known;
        for (const auto& q : entry.parameters) known.insert(q.name);
        r.only_keys(*t, known, "[parameters] of " + s.system);
        for (const auto& [key, node] : *t) {
            if (!entry.find(std::string(key.str()))) continue;  // noted by only_keys
            const parameter& q = *entry.find(std::string(key.str()));
            const double v = r.number(node, q.name);
            if (!q.accepts(v)) r.fail(node, s.system + " " + q.name + " = " + shortest(v) + "; expected " + q.expected());
            s.parameters[q.name] = v;
        }
    }
    read_initial(r, doc, s);
}

// [initial] q and p
void read_initial(const reader& r, const toml::table& doc, scene& s) {
    if (const toml::node* i = doc.get("initial")) {
        const toml::table* t = i->as_table();
        if (!t) r.fail(*i, "'initial' must be a table with q and p");
        r.only_keys(*t, {"q", "p"}, "[initial]");
        r.need_keys(*i, *t, {"q", "p"}, "[initial]");
        s.q0 = r.numbers(*t->get("q"), "initial.q");
        s.p0 = r.numbers(*t->get("p"), "initial.p");
        if (s.q0.size() != s.p0.size() || s.q0.empty())
            r.fail(*i, "initial q has " + std::to_string(s.q0.size()) + " values and p has " + std::to_string(s.p0.size()) +
                           "; expected the same number, at least one");
    }
}

// [[table]]s and methods
void read_methods(const reader& r, const toml::table& doc, scene& s) {
    const toml::source_region top{{1, 1}, {1, 1}, nullptr};
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
        std::optional<scene_method> named = method_by_name(r, m, inline_tables);
        if (!named) continue;
        s.methods.push_back(std::move(*named));
        for (std::size_t k = 0; k + 1 < s.methods.size(); ++k)
            if (s.methods[k].name == s.methods.back().name)
                r.fail(m, "method '" + s.methods.back().name + "' is listed twice; expected each method once");
    }
}

// [output]
// output.times = [t1, t2, ...] | {from, to, count} (evenly spaced, both ends
// included): finite, sorted (ties allowed), inside the file's [t0, t_end];
// under --quick the times past its t_end are left out.
std::vector<double> read_output_times(const reader& r, const toml::node& n, const scene& s, double file_t_end) {
    std::vector<double> times;
    const auto check_count = [&](const toml::node& where, double count) {
        if (count > double(max_output_times))
            r.fail(where, "'output.times' asks for " + format_number(count, 6) + " rows; expected at most " +
                              format_number(double(max_output_times), 6));
    };
    if (const toml::array* a = n.as_array()) {
        check_count(n, double(a->size()));
        for (const auto& e : *a) {
            const double t = r.number(e, "output.times");
            if (!std::isfinite(t) || t < s.t0 || t > file_t_end)
                r.fail(e, "output time " + shortest(t) + " is outside the run; expected a time in [t0, t_end] = [" +
                              shortest(s.t0) + ", " + shortest(file_t_end) + "]");
            if (!times.empty() && t < times.back())
                r.fail(e, "output time " + shortest(t) + " comes after " + shortest(times.back()) +
                              "; expected the times sorted, earliest first");
            times.push_back(t);
        }
        if (times.empty()) r.fail(n, "'output.times' is an empty array; expected at least one time");
    } else if (const toml::table* t = n.as_table()) {
        r.only_keys(*t, {"from", "to", "count"}, "'output.times'");
        const toml::node* from = t->get("from");
        const toml::node* to = t->get("to");
        const toml::node* count = t->get("count");
        r.need_keys(n, *t, {"from", "to", "count"}, "output.times");
        const double a = r.number(*from, "output.times.from"), b = r.number(*to, "output.times.to");
        for (const auto& [node, v] : {std::pair{from, a}, std::pair{to, b}})
            if (!std::isfinite(v) || v < s.t0 || v > file_t_end)
                r.fail(*node, "output time " + shortest(v) + " is outside the run; expected a time in [t0, t_end] = [" +
                                  shortest(s.t0) + ", " + shortest(file_t_end) + "]");
        if (b < a) r.fail(*to, "'output.times.to' = " + shortest(b) + " is before from = " + shortest(a) +
                                   "; expected to >= from");
        const auto c = count->value<std::int64_t>();
        if (!c || !count->is_integer() || *c < 1)
            r.fail(*count, "'output.times.count' = " + reader::text_of(*count) + "; expected an integer >= 1");
        check_count(*count, double(*c));
        if (*c > 1 && a == b) r.fail(*count, "'output.times' from = to = " + shortest(a) + " with count = " +
                                                 std::to_string(*c) + "; expected count = 1 for a single time");
        if (*c == 1 && a != b)  // one time cannot span from..to; which end was meant is a guess
            r.fail(*count, "'output.times' count = 1 with from = " + shortest(a) + " < to = " + shortest(b) +
                               "; expected count >= 2, or from = to for a single time");
        times.reserve(std::size_t(*c));
        for (std::int64_t i = 0; i < *c; ++i)  // the last one is `to` itself, not a rounded sum
            times.push_back(i + 1 == *c ? b : a + (b - a) * (double(i) / double(*c - 1)));
    } else {
        r.fail(n, "'output.times' must be an array of times or {from, to, count}");
    }
    return times;
}

// output.trajectory_every, output.energy_every: every k-th step, k >= 1.
std::size_t every_k_steps(const reader& r, const toml::node& n, const std::string& key, const std::string& what) {
    const auto k = n.value<std::int64_t>();
    if (!k || !n.is_integer() || *k < 1)
        r.fail(n, "'" + key + "' must be an integer >= 1 (every k-th step; leave it out for no " + what + ")");
    return std::size_t(*k);
}

void read_output(const reader& r, const toml::node& o, scene& s, double file_t_end) {
    const toml::table* t = o.as_table();
    if (!t) r.fail(o, "'output' must be a table");
    r.only_keys(*t, {"energy_error", "energy_every", "final_error", "trajectory_every", "times", "final_state", "loop_area",
                     "directory"},
                "[output]");
    if (auto* n = t->get("energy_error")) s.output.energy_error = r.boolean(*n, "output.energy_error");
    if (auto* n = t->get("final_error")) s.output.final_error = r.boolean(*n, "output.final_error");
    if (auto* n = t->get("energy_every")) {
        s.output.energy_every = every_k_steps(r, *n, "output.energy_every", "energy file");
        if (!s.output.energy_error)
            r.fail(*n, "'output.energy_every' with energy_error = false; expected energy_error = true (or no energy_every)");
    }
    if (auto* n = t->get("final_state")) s.output.final_state = r.boolean(*n, "output.final_state");
    if (auto* n = t->get("loop_area")) s.output.loop_area = r.boolean(*n, "output.loop_area");
    if (auto* n = t->get("directory")) s.output.directory = r.string(*n, "output.directory");
    if (auto* n = t->get("trajectory_every"))
        s.output.trajectory_every = every_k_steps(r, *n, "output.trajectory_every", "trajectory");
    if (auto* n = t->get("times")) {
        if (s.output.trajectory_every)
            r.fail(*n, "'output.times' and 'output.trajectory_every' both choose the trajectory's rows; expected one "
                       "of them");
        s.output.times = read_output_times(r, *n, s, file_t_end);
        s.output.times_dropped = std::erase_if(s.output.times, [&](double t) { return t > s.t_end; });  // --quick
    }
}

// checkpoint = {every_steps = N, file = "..."}
void read_checkpoint(const reader& r, const toml::node& c, const toml::array& methods, scene& s) {
    const toml::table* t = c.as_table();
    if (!t) r.fail(c, "'checkpoint' must be a table {every_steps = N, file = \"...\"}");
    r.only_keys(*t, {"every_steps", "file"}, "'checkpoint'");
    const toml::node* every = t->get("every_steps");
    const toml::node* file = t->get("file");
    r.need_keys(c, *t, {"every_steps", "file"}, "checkpoint");
    const auto n = every->value<std::int64_t>();
    if (!every->is_integer() || !n || *n < 1 || *n > std::int64_t(1e15))
        r.fail(*every, "'checkpoint.every_steps' must be an integer in [1, 1e15]");
    s.checkpoint.every_steps = std::size_t(*n);
    s.checkpoint.file = r.string(*file, "checkpoint.file");
    if (s.checkpoint.file.empty()) r.fail(*file, "'checkpoint.file' is empty; expected a file name");
    for (std::size_t k = 0; k < s.methods.size(); ++k)
        if (const std::string why = why_not_resumable(s.methods[k]); !why.empty()) r.fail(*methods.get(k), why);
}

}  // namespace

scene parse_scene(const std::string& text, const std::string& source, bool quick) {
    reader r{source};
    toml::table doc;
    try {
        doc = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        r.fail(e.source(), "not valid TOML: " + std::string(e.description()));
    }
    r.only_keys(doc, {"name", "system", "parameters", "initial", "methods", "table", "dt", "tolerances", "t0", "t_end",
                      "output", "quick", "checkpoint", "ensemble", "test_particles"},
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
    read_system(r, doc, s);
    if (const system_entry* entry = find_system(s.system)) {
        r.period = period_of(*entry, with_defaults(*entry, s.parameters, source));
        r.period_meaning = entry->period.meaning;
        s.period = r.period;
    }
    read_methods(r, doc, s);
    const toml::node* dt = timing("dt");
    if (!dt) r.fail(top, "missing 'dt'; expected a step size, an array, or {from, to, count}");
    s.dt = r.sweep(*dt, "dt");
    s.tolerances = timing("tolerances") ? r.sweep(*timing("tolerances"), "tolerances")
                                         : std::vector<double>{1e-3, 1e-5, 1e-7, 1e-9, 1e-11};
    if (const toml::node* t0 = doc.get("t0")) s.t0 = r.number(*t0, "t0");
    const toml::node* t_end = timing("t_end");
    if (!t_end) r.fail(top, "missing 't_end'");
    s.t_end = r.span_end(*t_end, "t_end", s.t0);
    if (!(s.t_end > s.t0) || !std::isfinite(s.t_end))
        r.fail(*t_end, "t_end = " + shortest(s.t_end) + " is not after t0 = " + shortest(s.t0) +
                           "; expected t_end > t0");

    const double file_t_end = doc.get("t_end") ? r.span_end(*doc.get("t_end"), "t_end", s.t0) : s.t_end;
    if (const toml::node* o = doc.get("output")) read_output(r, *o, s, file_t_end);
    const toml::array& methods = *doc.get("methods")->as_array();
    // What follows needs the system and every method (by index in the file).
    if (!find_system(s.system) || s.methods.size() != methods.size()) r.throw_unknown();
    if (const toml::node* c = doc.get("checkpoint")) {
        read_checkpoint(r, *c, methods, s);
        if (s.output.energy_every)  // a resumed run's series would start at the checkpoint
            r.fail(*c, "'checkpoint' with output.energy_every: a resumed run would miss the energy rows before its "
                       "checkpoint; expected one of them");
    }
    if (const toml::node* e = doc.get("ensemble")) s.ensemble = read_ensemble(r, *e, s, *find_system(s.system), methods);
    if (const toml::node* tp = doc.get("test_particles")) s.test_particles = read_test_particles(r, *tp, s, methods);
    r.throw_unknown();
    return s;
}

scene load_scene(const std::string& path, bool quick) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        // Not a file: a built-in scene by name (those the report leaves out run so).
        if (path.find('/') == std::string::npos)
            if (std::optional<scene> s = builtin_scene(path, quick)) return *s;
        throw scene_error(printable(path) + ": cannot open the scene file (nor is it a built-in scene's name)");
    }
    // A regular file of at most max_scene_bytes: /dev/zero, a directory or a
    // huge file is refused without being read into memory.
    const file_text read = read_file_text(path, max_scene_bytes);
    if (!read.failure.empty()) throw scene_error(printable(path) + ": the scene file " + read.failure);
    const std::string& text = read.text;
    if (text.find('\0') != std::string::npos)
        throw scene_error(printable(path) + ":" + std::to_string(1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(text.find('\0')), '\n')) +
                          ": a NUL byte; expected a text file (TOML)");
    scene s = parse_scene(text, path, quick);
    // A file the scene reads joins its identity (a file that cannot be read
    // is refused where it is read, with the reason).
    const auto cover = [&s](const std::string& file, std::size_t limit, const char* what) {
        const file_text input = read_file_text(file, limit);
        if (input.failure.empty()) s.text_hash = fnv1a_hex(s.text_hash + "\n" + what + " " + fnv1a_hex(input.text));
    };
    if (s.ensemble && !s.ensemble->states_file.empty()) cover(s.ensemble->states_file, max_states_bytes, "states");
    if (s.test_particles && !s.test_particles->elements_file.empty())
        cover(s.test_particles->elements_file, max_elements_bytes, "elements");
    return s;
}

std::vector<scene> default_scenes(bool quick) {
    // The built-in scenes of this program's systems: a program of one's own
    // (sympl_add_program) may have none of sympl's.
    std::vector<scene> scenes;
    for (const auto& [file, text] : builtin_scene_texts()) {
        const toml::table doc = toml::parse(text, "built-in:" + file);
        if (!find_system(doc["system"].value_or(std::string()))) continue;
        scene s = parse_scene(text, "built-in:" + file, quick);
        if (!s.test_particles) scenes.push_back(std::move(s));
    }
    if (scenes.empty()) {
        std::string names;
        for (const std::string& n : system_names()) names += (names.empty() ? "" : ", ") + n;
        throw scene_error("no built-in scene is of this program's systems (" + names +
                          "); expected scene files: report SCENE.toml ...");
    }
    return scenes;
}

std::optional<scene> builtin_scene(const std::string& name, bool quick) {
    for (const auto& [file, text] : builtin_scene_texts()) {
        std::string bare = file.ends_with(".toml") ? file.substr(0, file.size() - 5) : file;
        const std::size_t underscore = bare.find('_');
        const std::string unnumbered = underscore != std::string::npos && underscore > 0 &&
                                               std::all_of(bare.begin(), bare.begin() + std::ptrdiff_t(underscore),
                                                           [](char c) { return c >= '0' && c <= '9'; })
                                           ? bare.substr(underscore + 1)
                                           : bare;
        if (name == file || name == bare || name == unnumbered) return parse_scene(text, "built-in:" + file, quick);
    }
    return std::nullopt;
}

}  // namespace sympl::app
