// A scene's own system written as formulas (docs/scenes.md, "Your own
// system"): the [system] table read, its formulas parsed and checked at the
// initial state, and its entry added to the program's systems by name.
//
//   [system]
//   name = "my_henon_heiles"
//   coordinates = ["x", "y"]              # optional; momenta px, py (or momenta = [...])
//   parameters = {lambda = 1}             # optional
//   T = "(px^2 + py^2) / 2"               # T(p) and V(q), or one H(q, p)
//   V = "(x^2 + y^2) / 2 + lambda * (x^2 * y - y^3 / 3)"
//   period = 6.283185307179586            # optional: a number or a formula of the parameters
//   [initial]                             # required: it sets the degrees of freedom
//   q = [0, 0.1]
//   p = [0.49, 0]
#include <cctype>
#include <memory>
#include <set>

#include <Eigen/Core>

#include "formulas/formula_entry.hpp"
#include "reading/scene_reader.hpp"

namespace sympl::app {

namespace {

using namespace formulas;

bool is_name(const std::string& s) {
    if (s.empty() || s.size() > 64 || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    return true;
}

// A system's name: it names output files and rows.
bool is_system_name(const std::string& s) {
    if (s.empty() || s.size() > 64 || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
    return true;
}

// A formula error at its column inside the string's node (the opening quote
// is the node's first column).
[[noreturn]] void fail_in(const reader& r, const toml::node& n, const std::string& key, const formula_error& e) {
    toml::source_region at = n.source();
    if (at.begin.line == at.end.line) at.begin.column += toml::source_index(e.column);
    r.fail(at, key + ": " + e.what() + " (column " + std::to_string(e.column) + " of the formula)");
}

std::vector<std::string> name_list(const reader& r, const toml::node& n, const std::string& key, std::size_t count) {
    const toml::array* a = n.as_array();
    if (!a) r.fail(n, "'" + key + "' must be an array of names");
    if (a->size() != count)
        r.fail(n, "'" + key + "' has " + std::to_string(a->size()) + " names for " + std::to_string(count) +
                      " degrees of freedom (the [initial] q); expected one name each");
    std::vector<std::string> out;
    for (const auto& e : *a) {
        const std::string s = r.string(e, key);
        if (!is_name(s)) r.fail(e, "'" + key + "': '" + s + "' is not a name; expected letters, digits and '_', "
                                                           "not starting with a digit, at most 64");
        out.push_back(s);
    }
    return out;
}

}  // namespace

void read_formula_system(const reader& r, const toml::node& node, const toml::table& t, scene& s) {
    r.only_keys(t, {"name", "T", "V", "H", "parameters", "coordinates", "momenta", "period"}, "[system]");
    if (s.q0.empty())
        r.fail(node, "a [system] of formulas without [initial] q and p; expected them: they set the degrees of "
                     "freedom and the starting state");
    const std::size_t n = s.q0.size();
    formula_definition d;
    d.name = "formulas";
    if (const toml::node* name = t.get("name")) {
        d.name = r.string(*name, "system.name");
        if (!is_system_name(d.name))
            r.fail(*name, "system.name = '" + d.name + "'; expected letters, digits, '_' and '-', starting with a "
                                                       "letter, at most 64");
    }
    // Every name a formula may use, each once.
    std::set<std::string> taken{"q", "p"};
    for (const auto& f : function_names()) taken.insert(f);
    const auto claim = [&](const toml::node& at, const std::string& name, const std::string& what) {
        if (!taken.insert(name).second)
            r.fail(at, what + " '" + name + "' is already a name (q, p, a function, a coordinate or a parameter); "
                                            "expected a name of its own");
    };
    if (const toml::node* ps = t.get("parameters")) {
        const toml::table* pt = ps->as_table();
        if (!pt) r.fail(*ps, "'system.parameters' must be a table of numbers, as {k = 1, n = 32}");
        for (const auto& [key, value] : *pt) {
            const std::string name(key.str());
            if (!is_name(name)) r.fail(value, "parameter '" + name + "' is not a name; expected letters, digits and '_'");
            claim(value, name, "parameter");
            const double v = r.number(value, "system.parameters." + name);
            if (!std::isfinite(v)) r.fail(value, "parameter " + name + " = " + shortest(v) + "; expected a finite number");
            d.known.parameters.push_back(name);
            d.parameter_values.push_back(v);
        }
    }
    if (const toml::node* c = t.get("coordinates")) {
        d.known.q_names = name_list(r, *c, "system.coordinates", n);
        for (std::size_t k = 0; k < n; ++k) claim(*c, d.known.q_names[k], "coordinate");
        if (const toml::node* m = t.get("momenta")) {
            d.known.p_names = name_list(r, *m, "system.momenta", n);
        } else {
            for (const auto& q : d.known.q_names) d.known.p_names.push_back("p" + q);
        }
        for (std::size_t k = 0; k < n; ++k) claim(t.get("momenta") ? *t.get("momenta") : *c, d.known.p_names[k],
                                                  "momentum");
    } else if (const toml::node* m = t.get("momenta")) {
        r.fail(*m, "'system.momenta' without 'system.coordinates'; expected both, or neither (q[i] and p[i])");
    }
    d.known.dimension = n;
    d.q0 = s.q0;
    d.p0 = s.p0;

    const toml::node *T = t.get("T"), *V = t.get("V"), *H = t.get("H");
    if (H && (T || V)) r.fail(*H, "[system] has H and T or V; expected T and V (a separable H) or H alone");
    if (!H && !(T && V))
        r.fail(node, "[system] has " + std::string(T ? "T but no V" : V ? "V but no T" : "no T, V or H") +
                         "; expected T and V, or H");
    const Eigen::VectorXd q0 = Eigen::Map<const Eigen::VectorXd>(s.q0.data(), Eigen::Index(n)),
                          p0 = Eigen::Map<const Eigen::VectorXd>(s.p0.data(), Eigen::Index(n));
    std::string definition = d.name;
    // One formula: parsed, held to the variables it may use, and finite at
    // the initial state (which checks every index it reads).
    const auto read = [&](const toml::node& at, const char* key, bool q_allowed,
                          bool p_allowed) -> std::shared_ptr<const formula> {
        const std::string text = r.string(at, std::string("system.") + key);
        definition += std::string("\n") + key + "=" + text;
        try {
            auto f = std::make_shared<formula>(parse(text, d.known));
            if (f->uses_q && !q_allowed)
                throw formula_error(1, std::string(key) + " uses q; expected " +
                                           (p_allowed ? "T(p) alone (write H = ... for a non-separable system)"
                                                      : "a formula of the parameters alone"));
            if (f->uses_p && !p_allowed)
                throw formula_error(1, std::string(key) + " uses p; expected " +
                                           (q_allowed ? "V(q) alone (write H = ... for a non-separable system)"
                                                      : "a formula of the parameters alone"));
            const double v = evaluate<double>(*f, d.parameter_values, q0, p0);
            if (!std::isfinite(v))
                r.fail(at, std::string(key) + " = " + shortest(v) + " at the initial state; expected a finite value");
            return f;
        } catch (const formula_error& e) {
            fail_in(r, at, std::string("system.") + key, e);
        }
    };
    if (H) {
        d.H = read(*H, "H", true, true);
    } else {
        d.T = read(*T, "T", false, true);
        d.V = read(*V, "V", true, false);
    }
    if (const toml::node* period = t.get("period")) {
        if (period->is_string()) {
            d.period = read(*period, "period", false, false);
        } else {
            const double v = r.positive(*period, "system.period");
            formula constant;
            constant.text = shortest(v);
            constant.root = std::make_unique<formulas::node>();
            constant.root->kind = formulas::node::number;
            constant.root->value = v;
            d.period = std::make_shared<formula>(std::move(constant));
        }
    }
    for (std::size_t k = 0; k < d.known.parameters.size(); ++k)
        definition += "\n" + d.known.parameters[k] + "=" + shortest(d.parameter_values[k]);
    for (const auto& names : {d.known.q_names, d.known.p_names})
        for (const auto& name : names) definition += "\n" + name;
    for (double v : s.q0) definition += "\n" + shortest(v);
    for (double v : s.p0) definition += "\n" + shortest(v);
    try {
        s.system = add_scene_system(formula_entry(std::move(d)), definition).name;
    } catch (const invalid_argument& e) {
        r.fail(t.get("name") ? *t.get("name") : node, e.what());
    }
}

}  // namespace sympl::app
