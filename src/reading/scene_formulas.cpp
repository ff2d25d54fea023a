// A scene's own system written as formulas (docs/formulas.md): the [system]
// table's values taken as they are, read and checked by
// define_formula_system (formula_entry.hpp), whose errors are placed here at
// their key's file:line:column, and at the column inside a formula.
#include <string>
#include <vector>

#include "formulas/formula_entry.hpp"
#include "reading/scene_reader.hpp"

namespace sympl::app {

namespace {
std::vector<std::string> strings(const reader& r, const toml::node& n, const std::string& key) {
    const toml::array* a = n.as_array();
    if (!a) r.fail(n, "'" + key + "' must be an array of names");
    if (a->size() > std::size_t(largest_chain))
        r.fail(n, "'" + key + "' has " + std::to_string(a->size()) + " names; expected at most one per degree of freedom");
    std::vector<std::string> out;
    for (const auto& e : *a) out.push_back(r.string(e, key));
    return out;
}
}  // namespace

void read_formula_system(const reader& r, const toml::node& node, const toml::table& t, scene& s) {
    using namespace formulas;
    r.only_keys(t, {"name", "T", "V", "H", "parameters", "coordinates", "momenta", "period", "exact_q", "exact_p"},
                "[system]");
    if (s.q0.empty())
        r.fail(node, "a [system] of formulas without [initial] q and p; expected them: they set the degrees of "
                     "freedom and the starting state");
    formula_texts texts;
    for (const char* key : {"name", "T", "V", "H"})
        if (const toml::node* v = t.get(key)) {
            std::string& into = key[0] == 'n' ? texts.name : key[0] == 'T' ? texts.T : key[0] == 'V' ? texts.V : texts.H;
            into = r.string(*v, std::string("system.") + key);
            if (into.empty()) r.fail(*v, std::string("system.") + key + " is empty; expected a formula");
        }
    if (const toml::node* ps = t.get("parameters")) {
        const toml::table* pt = ps->as_table();
        if (!pt) r.fail(*ps, "'system.parameters' must be a table of numbers, as {k = 1, n = 32}");
        for (const auto& [key, value] : *pt)
            texts.parameters.emplace_back(std::string(key.str()),
                                          r.number(value, "system.parameters." + std::string(key.str())));
    }
    if (const toml::node* c = t.get("coordinates")) texts.coordinates = strings(r, *c, "system.coordinates");
    if (const toml::node* m = t.get("momenta")) texts.momenta = strings(r, *m, "system.momenta");
    if (const toml::node* period = t.get("period"))
        texts.period = period->is_string() ? r.string(*period, "system.period")
                                            : shortest(r.positive(*period, "system.period"));
    for (const char* key : {"exact_q", "exact_p"})
        if (const toml::node* e = t.get(key)) {
            const toml::array* a = e->as_array();
            if (!a) r.fail(*e, std::string("'system.") + key + "' must be an array of formulas of t, one per degree of freedom");
            if (a->size() > std::size_t(largest_chain))
                r.fail(*e, std::string("'system.") + key + "' has " + std::to_string(a->size()) + " formulas; expected "
                           "one per degree of freedom");
            auto& into = key[6] == 'q' ? texts.exact_q : texts.exact_p;
            for (const auto& f : *a) into.push_back(r.string(f, std::string("system.") + key));
        }
    texts.q0 = s.q0;
    texts.p0 = s.p0;
    try {
        s.system = define_formula_system(texts).name;
    } catch (const formula_input_error& e) {
        // The key's node (the table where it has none), and inside a formula
        // the column (the opening quote is the node's first column).
        const toml::node* at = e.key == "initial" ? nullptr : t.get(e.key);
        // exact_q[k]: the k-th formula of the array.
        if (const std::size_t open = e.key.find('['); open != std::string::npos)
            if (const toml::node* list = t.get(e.key.substr(0, open)); list && list->as_array()) {
                const std::size_t k = std::stoul(e.key.substr(open + 1));
                if (k < list->as_array()->size()) at = list->as_array()->get(k);
            }
        if (!at) r.fail(node, e.what());
        if (e.column == 0) r.fail(*at, e.what());
        toml::source_region where = at->source();
        if (where.begin.line == where.end.line) where.begin.column += toml::source_index(e.column);
        r.fail(where, "system." + e.key + ": " + e.what() + " (column " + std::to_string(e.column) + " of the formula)");
    }
}

}  // namespace sympl::app
