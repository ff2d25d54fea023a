// A scene's formulas written out as C functions (formula_code.hpp).
#include "formulas/formula_code.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

namespace sympl::app::formulas {

namespace {

// A double as a C literal that reads back to the same double (17 digits).
std::string literal(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    std::string s = buffer;
    if (s.find_first_of(".en") == std::string::npos) s += ".0";
    return s;
}

// The interpreter's test for an exponent it takes as repeated products (formula_eval.hpp).
bool small_integer_exponent(const node& n) {
    const node& e = *n.children[1];
    return e.kind == node::number && e.value == std::floor(e.value) && std::fabs(e.value) <= 16;
}

const char* c_function(int function) {
    static const char* names[] = {"sin", "cos", "tan", "sinh", "cosh", "tanh", "exp", "log", "sqrt", "fabs", "atan"};
    return names[function];
}

// One function's body in one precision.
class writer {
public:
    writer(std::string real, std::string suffix) : R_(std::move(real)), F_(std::move(suffix)) {}

    std::string text;

    void line(const std::string& s) { text += std::string(4 * (indent_ + 1), ' ') + s + "\n"; }

    // Statements that compute n's value; the variable that holds it.
    std::string value(const node& n) {
        std::string v;
        const auto operand = [&](std::size_t k) { return held(*n.children[k]); };  // each value once a scope
        switch (n.kind) {
            case node::number: v = declare("(" + R_ + ")" + literal(n.value)); break;
            case node::parameter: v = declare("(" + R_ + ")k[" + std::to_string(n.slot) + "]"); break;
            case node::index: v = declare("(" + R_ + ")i" + std::to_string(n.slot)); break;
            case node::q:
            case node::p: v = declare(element(n)); break;
            case node::add: {
                const std::string a = operand(0), b = operand(1);
                v = declare(a + " + " + b);
                break;
            }
            case node::subtract: {
                const std::string a = operand(0), b = operand(1);
                v = declare(a + " - " + b);
                break;
            }
            case node::multiply: {
                const std::string a = operand(0), b = operand(1);
                v = declare(a + " * " + b);
                break;
            }
            case node::divide: {
                const std::string a = operand(0), b = operand(1);
                v = declare(a + " / " + b);
                break;
            }
            case node::negate: v = declare("-" + operand(0)); break;
            case node::power:
                if (small_integer_exponent(n)) {
                    // As the interpreter: r = 1, then r = r * base |e| times, 1 / r for e < 0.
                    const std::string base = operand(0);
                    const int e = int(n.children[1]->value);
                    v = fresh();
                    line(R_ + " " + v + " = (" + R_ + ")1.0;");
                    for (int k = 0; k < std::abs(e); ++k) line(v + " = " + v + " * " + base + ";");
                    if (e < 0) line(v + " = (" + R_ + ")1.0 / " + v + ";");
                } else {
                    const std::string a = operand(0), b = operand(1);
                    v = declare("__builtin_pow" + F_ + "(" + a + ", " + b + ")");
                }
                break;
            case node::call: {
                const std::string a = operand(0);
                v = declare("__builtin_" + std::string(c_function(n.function)) + F_ + "(" + a + ")");
                break;
            }
            case node::sum: {
                v = fresh();
                line(R_ + " " + v + " = (" + R_ + ")0.0;");
                open_loop(n);
                const std::string term = held(*n.children[2]);
                line(v + " = " + v + " + " + term + ";");
                close_loop();
                break;
            }
        }
        scopes_.back()[&n] = v;
        return v;
    }

    // Statements that add adjoint * d(n)/d(wrt) into grad[...], for n that
    // depends on wrt (node::q or node::p); the values it uses are computed
    // where first needed (held()).
    void adjoint(const node& n, const std::string& a, node::kind_t wrt, const std::string& grad) {
        const auto depends_on = [&](std::size_t k) { return depends(*n.children[k], wrt); };
        const auto of = [&](std::size_t k) { return held(*n.children[k]); };
        const auto into = [&](std::size_t k, const std::string& expression) {
            adjoint(*n.children[k], declare(expression), wrt, grad);
        };
        switch (n.kind) {
            case node::q:
            case node::p:
                if (n.kind == wrt) accumulate(grad, index_of(n), offset_in_loop(n), a);
                return;
            case node::add:
                if (depends_on(0)) adjoint(*n.children[0], a, wrt, grad);
                if (depends_on(1)) adjoint(*n.children[1], a, wrt, grad);
                return;
            case node::subtract:
                if (depends_on(0)) adjoint(*n.children[0], a, wrt, grad);
                if (depends_on(1)) into(1, "-" + a);
                return;
            case node::multiply:
                if (depends_on(0)) into(0, a + " * " + of(1));
                if (depends_on(1)) into(1, a + " * " + of(0));
                return;
            case node::divide:
                if (depends_on(0)) into(0, a + " / " + of(1));
                if (depends_on(1)) into(1, "-(" + a + " * " + held(n) + ") / " + of(1));
                return;
            case node::negate: into(0, "-" + a); return;
            case node::power:
                if (small_integer_exponent(n)) {
                    // d(b^e)/db = e b^(e-1): products for e > 0, e b^e / b below.
                    const int e = int(n.children[1]->value);
                    if (e == 0) return;
                    const std::string d = fresh();
                    line(R_ + " " + d + " = " + a + " * (" + R_ + ")" + literal(e) + ";");
                    if (e > 0) {
                        for (int k = 1; k < e; ++k) line(d + " = " + d + " * " + of(0) + ";");
                    } else {
                        line(d + " = " + d + " * " + held(n) + " / " + of(0) + ";");
                    }
                    adjoint(*n.children[0], d, wrt, grad);
                    return;
                }
                if (depends_on(0))
                    into(0, a + " * " + of(1) + " * __builtin_pow" + F_ + "(" + of(0) + ", " + of(1) + " - (" + R_ +
                                ")1.0)");
                if (depends_on(1)) into(1, a + " * " + held(n) + " * __builtin_log" + F_ + "(" + of(0) + ")");
                return;
            case node::call: {
                const std::string x = of(0), y = held(n), one = "(" + R_ + ")1.0";
                const auto f = [&](const char* name) { return "__builtin_" + std::string(name) + F_ + "(" + x + ")"; };
                switch (n.function) {
                    case 0: into(0, a + " * " + f("cos")); return;
                    case 1: into(0, "-(" + a + " * " + f("sin") + ")"); return;
                    case 2: into(0, a + " * (" + one + " + " + y + " * " + y + ")"); return;
                    case 3: into(0, a + " * " + f("cosh")); return;
                    case 4: into(0, a + " * " + f("sinh")); return;
                    case 5: into(0, a + " * (" + one + " - " + y + " * " + y + ")"); return;
                    case 6: into(0, a + " * " + y); return;
                    case 7: into(0, a + " / " + x); return;
                    case 8: into(0, "(" + a + " * (" + R_ + ")0.5) / " + y); return;
                    case 9: into(0, "(" + x + " > 0 ? " + a + " : " + x + " < 0 ? -" + a + " : (" + R_ + ")0.0)"); return;
                    case 10: into(0, a + " / (" + one + " + " + x + " * " + x + ")"); return;
                }
                return;
            }
            case node::sum:
                // Each term's adjoint share, with the values it needs.
                open_loop(n);
                adjoint(*n.children[2], a, wrt, grad);
                close_loop();
                return;
            default: return;  // numbers, parameters, indices
        }
    }

    // The contributions to each element of the gradient gathered in a scope
    // are added to it once, at the scope's end (flush): one load and store
    // per element and term instead of one per occurrence.
    void accumulate(const std::string& array, const std::string& index, std::optional<long> offset,
                    const std::string& a) {
        auto& pending = pending_.back();
        for (pending_add& e : pending)
            if (e.array == array && e.index == index) {
                e.sum = declare(e.sum + " + " + a);
                return;
            }
        pending.push_back({array, index, offset, a});
    }
    void flush() {
        for (const pending_add& e : pending_.back()) line(e.element() + " += " + e.sum + ";");
        written_.back() = written_.back() || !pending_.back().empty();
        pending_.back().clear();
    }

    bool depends(const node& n, node::kind_t wrt) {
        auto& memo = wrt == node::q ? on_q_ : on_p_;
        if (const auto found = memo.find(&n); found != memo.end()) return found->second;
        bool d = false;
        if (n.kind == node::q || n.kind == node::p) d = n.kind == wrt;  // an index never holds q or p
        else
            for (const auto& c : n.children) d = d || depends(*c, wrt);
        memo[&n] = d;
        return d;
    }

private:
    std::string fresh() { return "t" + std::to_string(next_++); }
    std::string declare(const std::string& expression) {
        const std::string v = fresh();
        line("const " + R_ + " " + v + " = " + expression + ";");
        return v;
    }
    // n's value, computed here in the current scope if it is not yet: a
    // gradient computes only the values its adjoints use.
    std::string held(const node& n) {
        for (auto s = scopes_.rbegin(); s != scopes_.rend(); ++s)
            if (const auto found = s->find(&n); found != s->end()) return found->second;
        return value(n);
    }

    // An index or a sum's bound: in double, as the interpreter computes it
    // (formula_eval.hpp, plain()), then taken as an integer; that it is one is
    // checked by the interpreter at the initial state (formula_system.hpp).
    std::string plain(const node& n) const {
        const auto a = [&](std::size_t k) { return plain(*n.children[k]); };
        switch (n.kind) {
            case node::number: return literal(n.value);
            case node::parameter: return "k[" + std::to_string(n.slot) + "]";
            case node::index: return "(double)i" + std::to_string(n.slot);
            case node::add: return "(" + a(0) + " + " + a(1) + ")";
            case node::subtract: return "(" + a(0) + " - " + a(1) + ")";
            case node::multiply: return "(" + a(0) + " * " + a(1) + ")";
            case node::divide: return "(" + a(0) + " / " + a(1) + ")";
            case node::negate: return "(-" + a(0) + ")";
            case node::power: return "__builtin_pow(" + a(0) + ", " + a(1) + ")";
            default:
                throw formula_error(n.column, "an index or a sum's bound depends on q or p, or calls a function; "
                                              "expected integers, parameters and the enclosing sums' indices");
        }
    }
    // An index in long arithmetic where it is made of integers, indices and
    // + - * alone (the same value: the interpreter's doubles are exact
    // below 2^53, and every index was checked to lie in the state); in double
    // otherwise, as the interpreter computes it.
    static bool integral(const node& n) {
        switch (n.kind) {
            case node::number: return n.value == std::floor(n.value) && std::fabs(n.value) < 0x1p52;
            case node::index: return true;
            case node::add:
            case node::subtract:
            case node::multiply: return integral(*n.children[0]) && integral(*n.children[1]);
            case node::negate: return integral(*n.children[0]);
            default: return false;
        }
    }
    static std::string integer(const node& n) {
        const auto a = [&](std::size_t k) { return integer(*n.children[k]); };
        switch (n.kind) {
            case node::number: return std::to_string(long(n.value)) + "L";
            case node::index: return "i" + std::to_string(n.slot);
            case node::add: return "(" + a(0) + " + " + a(1) + ")";
            case node::subtract: return "(" + a(0) + " - " + a(1) + ")";
            case node::multiply: return "(" + a(0) + " * " + a(1) + ")";
            default: return "(-" + a(0) + ")";
        }
    }
    std::string index_of(const node& n) const {
        if (!n.indexed) return std::to_string(n.slot);
        const node& i = *n.children[0];
        return integral(i) ? integer(i) : "(long)" + plain(i);
    }
    std::string element(const node& n) const {
        return std::string(n.kind == node::q ? "q" : "p") + "[" + index_of(n) + "]";
    }
    // An element q[i + c] or p[i + c] of the innermost sum's index i, c an
    // integer: its offset c.
    std::optional<long> offset_in_loop(const node& n) const {
        if (!n.indexed || depth_ == 0) return std::nullopt;
        const node& i = *n.children[0];
        const auto is_index = [&](const node& m) { return m.kind == node::index && m.slot == depth_ - 1; };
        const auto is_whole = [](const node& m) {
            return m.kind == node::number && m.value == std::floor(m.value) && std::fabs(m.value) < 0x1p52;
        };
        if (is_index(i)) return 0;
        if (i.kind == node::add && is_index(*i.children[0]) && is_whole(*i.children[1])) return long(i.children[1]->value);
        if (i.kind == node::add && is_whole(*i.children[0]) && is_index(*i.children[1])) return long(i.children[0]->value);
        if (i.kind == node::subtract && is_index(*i.children[0]) && is_whole(*i.children[1]))
            return -long(i.children[1]->value);
        return std::nullopt;
    }

    // A sum whose terms add into exactly two elements g[i + c] and g[i + c + 1]
    // of one gradient (a chain's springs) carries the second in a register to
    // the next term, where it is the first: each element is then loaded and
    // stored once, with no term waiting on the store of the one before. The
    // same additions in the same order: g[i + c] receives the carried share
    // from term i - 1, then its own. The share starts as -0.0, which adds
    // to any double without changing a bit (round to nearest), so the first
    // term needs no branch; the flag is read once, after the loop.
    bool carry(std::size_t loop_start, int loop_indent) {
        const auto& pending = pending_.back();
        if (written_.back() || pending.size() != 2 || pending[0].array != pending[1].array || !pending[0].offset ||
            !pending[1].offset)
            return false;
        const bool first_low = *pending[0].offset < *pending[1].offset;
        const pending_add& low = pending[first_low ? 0 : 1];
        const pending_add& high = pending[first_low ? 1 : 0];
        if (*high.offset != *low.offset + 1) return false;
        const std::string id = std::to_string(next_++);
        carried_ = {"c" + id, "h" + id, "j" + id, high.array};
        text.insert(loop_start, std::string(4 * (loop_indent + 1), ' ') + R_ + " " + carried_.value + " = (" + R_ +
                                    ")-0.0; int " + carried_.held + " = 0; long " + carried_.at + " = 0;\n");
        line(low.element() + " = (" + low.element() + " + " + carried_.value + ") + " + low.sum + ";");
        line(carried_.value + " = " + high.sum + "; " + carried_.held + " = 1; " + carried_.at + " = " + high.index +
             ";");
        return true;
    }

    void open_loop(const node& sum) {
        loop_starts_.push_back(text.size());
        const std::string i = "i" + std::to_string(depth_);
        line("for (long " + i + " = (long)" + plain(*sum.children[0]) + "; " + i + " <= (long)" +
             plain(*sum.children[1]) + "; ++" + i + ") {");
        ++indent_;
        ++depth_;
        scopes_.emplace_back();
        pending_.emplace_back();
        written_.push_back(false);
    }
    void close_loop() {
        const bool carried = carry(loop_starts_.back(), indent_ - 1);
        if (!carried) flush();
        const bool wrote = carried || written_.back();
        loop_starts_.pop_back();
        pending_.pop_back();
        written_.pop_back();
        scopes_.pop_back();
        --depth_;
        --indent_;
        line("}");
        if (carried)
            line("if (" + carried_.held + ") " + carried_.array + "[" + carried_.at + "] += " + carried_.value + ";");
        written_.back() = written_.back() || wrote;
    }

    std::string R_, F_;
    int next_ = 0, indent_ = 0;
    std::size_t depth_ = 0;
    std::vector<std::map<const node*, std::string>> scopes_{1};
    // A contribution to array[index], gathered in a scope; offset: index = i + offset for the scope's sum index i.
    struct pending_add {
        std::string array, index;
        std::optional<long> offset;
        std::string sum;
        std::string element() const { return array + "[" + index + "]"; }
    };
    std::vector<std::vector<pending_add>> pending_{1};
    std::vector<bool> written_{false};       // a scope's nested sums wrote into a gradient
    std::vector<std::size_t> loop_starts_;   // where each open sum's loop begins in text
    struct {
        std::string value, held, at, array;
    } carried_;                               // the names of the last carry() (used at its loop's end)
    std::unordered_map<const node*, bool> on_q_, on_p_;
};

struct precision {
    const char* real;
    const char* builtin_suffix;
    const char* name_suffix;
};
constexpr precision precisions[] = {{"double", "", "_d"}, {"long double", "l", "_l"}};

// R name(arguments) { return the formula; }
std::string value_function(const precision& r, const std::string& name, const std::string& arguments,
                           const formula& f) {
    writer w(r.real, r.builtin_suffix);
    const std::string v = w.value(*f.root);
    w.line("return " + v + ";");
    return std::string(r.real) + " " + name + r.name_suffix + "(" + arguments + ") {\n" + w.text + "}\n";
}

// void name(arguments) { out = sign * d f / d wrt }, by one forward and one backward pass.
std::string gradient_function(const precision& r, const std::string& name, const std::string& arguments,
                              const formula& f, node::kind_t wrt, const char* sign) {
    writer w(r.real, r.builtin_suffix);
    const std::string R = r.real;
    // Zeroed four at a time: -O2 does not unroll a loop of unknown length,
    // and a call to memset costs more than the stores on short states.
    w.line("long j = 0;");
    w.line("for (; j + 4 <= n; j += 4) out[j] = out[j + 1] = out[j + 2] = out[j + 3] = (" + R + ")0.0;");
    w.line("for (; j < n; ++j) out[j] = (" + R + ")0.0;");
    if (w.depends(*f.root, wrt)) {
        w.line("const " + R + " seed = (" + R + ")" + sign + "1.0;");
        w.adjoint(*f.root, "seed", wrt, "out");
        w.flush();
    }
    return "void " + name + r.name_suffix + "(" + arguments + ") {\n" + w.text + "}\n";
}

std::string with_real(std::string arguments, const char* real) {
    for (std::size_t at = arguments.find('R'); at != std::string::npos; at = arguments.find('R', at))
        arguments.replace(at, 1, real);
    return arguments;
}

}  // namespace

std::string separable_source(const formula& T, const formula& V) {
    std::string s = "/* sympl: a scene's T(p) and V(q), written from their parsed trees */\n";
    for (const precision& r : precisions) {
        s += value_function(r, "sympl_T", with_real("const R* p, const double* k", r.real), T);
        s += value_function(r, "sympl_V", with_real("const R* q, const double* k", r.real), V);
        s += gradient_function(r, "sympl_velocity", with_real("const R* restrict p, R* restrict out, const double* restrict k, long n", r.real), T,
                               node::p, "");
        s += gradient_function(r, "sympl_force", with_real("const R* restrict q, R* restrict out, const double* restrict k, long n", r.real), V,
                               node::q, "-");
    }
    return s;
}

std::string general_source(const formula& H) {
    std::string s = "/* sympl: a scene's H(q, p), written from its parsed tree */\n";
    for (const precision& r : precisions) {
        s += value_function(r, "sympl_H", with_real("const R* q, const R* p, const double* k", r.real), H);
        const std::string args =
            with_real("const R* restrict q, const R* restrict p, R* restrict out, const double* restrict k, long n", r.real);
        s += gradient_function(r, "sympl_dH_dq", args, H, node::q, "");
        s += gradient_function(r, "sympl_dH_dp", args, H, node::p, "");
    }
    return s;
}

}  // namespace sympl::app::formulas
