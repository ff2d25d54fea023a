// Reading a formula into a tree (formula.hpp).
#include "formulas/formula.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "reading/near_names.hpp"

namespace sympl::app::formulas {

const std::vector<std::string>& function_names() {
    static const std::vector<std::string> names{"sin",  "cos", "tan", "sinh", "cosh", "tanh",
                                                "exp",  "log", "sqrt", "abs", "atan", "sum"};
    return names;
}

bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

namespace {

// A character as an error shows it: printable, or its code.
std::string shown(char c) {
    if (std::isprint(static_cast<unsigned char>(c))) return std::string("'") + c + "'";
    return "byte " + std::to_string(static_cast<unsigned char>(c));
}

class parser {
public:
    parser(const std::string& text, const names& known) : s_(text), known_(known) {}

    formula run() {
        if (s_.size() > max_length)
            throw formula_error(1, "a formula of " + std::to_string(s_.size()) + " characters; expected at most " +
                                       std::to_string(max_length));
        formula f;
        f.text = s_;
        f.root = sum_of();
        skip();
        if (at_ < s_.size()) throw formula_error(at_ + 1, shown(s_[at_]) + " after a complete formula; expected an "
                                                             "operator (+ - * / ^) or the end");
        f.uses_q = uses_q_;
        f.uses_p = uses_p_;
        return f;
    }

private:
    void skip() {
        while (at_ < s_.size() && (s_[at_] == ' ' || s_[at_] == '\t' || s_[at_] == '\n' || s_[at_] == '\r')) ++at_;
    }
    bool take(char c) {
        skip();
        if (at_ < s_.size() && s_[at_] == c) {
            ++at_;
            return true;
        }
        return false;
    }
    void expect(char c, const std::string& where) {
        if (take(c)) return;
        throw formula_error(at_ + 1, (at_ < s_.size() ? shown(s_[at_]) : std::string("the end")) + " " + where +
                                         "; expected '" + std::string(1, c) + "'");
    }
    // One level deeper: bounded, so that no text makes the parser recurse without end.
    struct level {
        explicit level(parser& p) : p_(p) {
            if (++p_.depth_ > max_depth)
                throw formula_error(p_.at_ + 1, "brackets and operators nested more than " +
                                                    std::to_string(max_depth) + " deep; expected a shallower formula");
        }
        ~level() { --p_.depth_; }
        parser& p_;
    };

    static std::unique_ptr<node> make(node::kind_t k, std::size_t column) {
        auto n = std::make_unique<node>();
        n->kind = k;
        n->column = column;
        return n;
    }
    static std::unique_ptr<node> binary(node::kind_t k, std::unique_ptr<node> a, std::unique_ptr<node> b,
                                        std::size_t column) {
        auto n = make(k, column);
        n->children.push_back(std::move(a));
        n->children.push_back(std::move(b));
        return n;
    }

    std::unique_ptr<node> sum_of() {
        level l(*this);
        auto left = product();
        for (;;) {
            skip();
            const std::size_t column = at_ + 1;
            if (take('+')) left = binary(node::add, std::move(left), product(), column);
            else if (take('-')) left = binary(node::subtract, std::move(left), product(), column);
            else return left;
        }
    }
    std::unique_ptr<node> product() {
        level l(*this);
        auto left = unary();
        for (;;) {
            skip();
            const std::size_t column = at_ + 1;
            if (take('*')) left = binary(node::multiply, std::move(left), unary(), column);
            else if (take('/')) left = binary(node::divide, std::move(left), unary(), column);
            else return left;
        }
    }
    std::unique_ptr<node> unary() {
        level l(*this);
        skip();
        const std::size_t column = at_ + 1;
        if (take('-')) {
            auto n = make(node::negate, column);
            n->children.push_back(unary());
            return n;
        }
        if (take('+')) return unary();
        return power();
    }
    std::unique_ptr<node> power() {
        level l(*this);
        auto base = atom();
        skip();
        const std::size_t column = at_ + 1;
        if (take('^')) return binary(node::power, std::move(base), unary(), column);
        return base;
    }

    std::unique_ptr<node> atom() {
        level l(*this);
        skip();
        const std::size_t column = at_ + 1;
        if (at_ >= s_.size()) throw formula_error(column, "the formula ends where a value was expected");
        const char c = s_[at_];
        if (take('(')) {
            auto inner = sum_of();
            expect(')', "inside brackets opened at column " + std::to_string(column));
            return inner;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number(column);
        if (name_start(c)) return named(column);
        throw formula_error(column, shown(c) + " where a value was expected; expected a number, a name, a function "
                                               "or '('");
    }

    std::unique_ptr<node> number(std::size_t column) {
        std::size_t end = at_;
        while (end < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[end])) || s_[end] == '.')) ++end;
        if (end < s_.size() && (s_[end] == 'e' || s_[end] == 'E')) {
            std::size_t e = end + 1;
            if (e < s_.size() && (s_[e] == '+' || s_[e] == '-')) ++e;
            if (e < s_.size() && std::isdigit(static_cast<unsigned char>(s_[e]))) {
                while (e < s_.size() && std::isdigit(static_cast<unsigned char>(s_[e]))) ++e;
                end = e;
            }
        }
        double v = 0;
        const auto [ptr, ec] = std::from_chars(s_.data() + at_, s_.data() + end, v);
        if (ec != std::errc() || ptr != s_.data() + end || !std::isfinite(v))
            throw formula_error(column, "'" + s_.substr(at_, end - at_) + "' is not a finite number");
        at_ = end;
        auto n = make(node::number, column);
        n->value = v;
        return n;
    }

    std::unique_ptr<node> named(std::size_t column) {
        const std::size_t start = at_;
        while (at_ < s_.size() && name_char(s_[at_])) ++at_;
        const std::string name = s_.substr(start, at_ - start);
        skip();
        if (at_ < s_.size() && s_[at_] == '(') return call(name, column);
        if ((name == "q" || name == "p") && take('[')) {
            auto n = make(name == "q" ? node::q : node::p, column);
            (name == "q" ? uses_q_ : uses_p_) = true;
            n->indexed = true;
            n->children.push_back(sum_of());
            expect(']', "after the index of " + name);
            return n;
        }
        for (std::size_t d = indices_.size(); d-- > 0;)
            if (indices_[d] == name) {
                auto n = make(node::index, column);
                n->slot = d;
                return n;
            }
        for (std::size_t k = 0; k < known_.parameters.size(); ++k)
            if (known_.parameters[k] == name) {
                auto n = make(node::parameter, column);
                n->slot = k;
                return n;
            }
        for (int which = 0; which < 2; ++which) {
            const auto& list = which == 0 ? known_.q_names : known_.p_names;
            for (std::size_t k = 0; k < list.size(); ++k)
                if (list[k] == name) {
                    auto n = make(which == 0 ? node::q : node::p, column);
                    (which == 0 ? uses_q_ : uses_p_) = true;
                    n->slot = k;
                    return n;
                }
        }
        throw formula_error(column, "unknown name '" + name + "'; " + expected_one_of(name, known_names()));
    }

    std::unique_ptr<node> call(const std::string& name, std::size_t column) {
        const auto& functions = function_names();
        const auto found = std::find(functions.begin(), functions.end(), name);
        if (found == functions.end())
            throw formula_error(column, "unknown function '" + name + "'; " + expected_one_of(name, functions));
        expect('(', "after a function's name");
        auto n = make(name == "sum" ? node::sum : node::call, column);
        n->function = int(found - functions.begin());
        if (name == "sum") {
            // sum(i, first, last, term): i is bound inside the term only.
            skip();
            const std::size_t at = at_;
            while (at_ < s_.size() && name_char(s_[at_])) ++at_;
            const std::string index = s_.substr(at, at_ - at);
            if (index.empty() || !name_start(index[0]))
                throw formula_error(at + 1, "sum's first argument must be the index's name, as in sum(i, 0, n - 1, "
                                            "q[i]^2)");
            expect(',', "after sum's index");
            n->children.push_back(sum_of());
            expect(',', "after sum's first value");
            n->children.push_back(sum_of());
            expect(',', "after sum's last value");
            indices_.push_back(index);
            n->children.push_back(sum_of());
            indices_.pop_back();
            expect(')', "at the end of sum(...)");
            return n;
        }
        n->children.push_back(sum_of());
        expect(')', "after " + name + "'s argument (functions take one)");
        return n;
    }

    std::vector<std::string> known_names() const {
        std::vector<std::string> all = known_.parameters;
        all.insert(all.end(), known_.q_names.begin(), known_.q_names.end());
        all.insert(all.end(), known_.p_names.begin(), known_.p_names.end());
        all.insert(all.end(), indices_.begin(), indices_.end());
        all.push_back("q[i]");
        all.push_back("p[i]");
        return all;
    }

    const std::string& s_;
    const names& known_;
    std::size_t at_ = 0, depth_ = 0;
    std::vector<std::string> indices_;
    bool uses_q_ = false, uses_p_ = false;
};

}  // namespace

formula parse(const std::string& text, const names& known) { return parser(text, known).run(); }

}  // namespace sympl::app::formulas
