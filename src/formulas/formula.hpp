#pragma once
// A scene's formula (issue 57): T(p), V(q) or H(q, p) written as text, read
// once into a tree and evaluated on any scalar type (double for the runs,
// long double for references, the library's dual and reverse-mode numbers
// for the gradients). Nothing of the text is ever executed or handed on: it
// is parsed here and only the tree is used.
//
// Grammar (precedence low to high; '^' binds right, unary minus below '^'):
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := '-' unary | power
//   power   := atom ('^' unary)?
//   atom    := number | name | name '[' sum ']' | name '(' arguments ')' | '(' sum ')'
// Names: the system's parameters, the coordinates q and p (indexed q[i],
// from 0) or their given names, and the index of an enclosing sum.
// Functions: sin cos tan sinh cosh tanh exp log sqrt abs atan, and
//   sum(i, first, last, term)  the terms for i = first..last (integers)
// Errors are formula_error with the column (from 1) and what was expected.
#include <cstddef>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sympl::app::formulas {

struct formula_error : std::runtime_error {
    formula_error(std::size_t column, const std::string& what)
        : std::runtime_error(what), column(column) {}
    std::size_t column;  // 1-based, in the formula's text
};

// What a name in a formula may be.
struct names {
    std::vector<std::string> parameters;    // their values are given at evaluation
    std::vector<std::string> q_names;       // named coordinates (empty: only q[i])
    std::vector<std::string> p_names;       // named momenta (empty: only p[i])
    std::size_t dimension = 0;              // the number of q (and of p)
};

struct node {
    enum kind_t { number, parameter, q, p, index, add, subtract, multiply, divide, power, negate, call, sum } kind;
    double value = 0;                      // number
    std::size_t slot = 0;                  // parameter: its position; q, p: a fixed component; index: its depth
    int function = -1;                     // call: position in function_names()
    std::vector<std::unique_ptr<node>> children;  // operands; q[i], p[i]: the index; sum: first, last, term
    std::size_t column = 0;
    bool indexed = false;                  // q[...] or p[...]: the component is children[0]'s value
};

const std::vector<std::string>& function_names();

// What a name is made of: a letter or '_' first, then letters, digits, '_'.
bool name_start(char c);
bool name_char(char c);

// The deepest nesting a formula may have, in the parser's levels (five per
// bracket: about 200 brackets): the parser and the evaluation recurse once
// per level, and no scene can make them recurse further.
inline constexpr std::size_t max_depth = 1000;
inline constexpr std::size_t max_length = 1 << 16;  // characters

struct formula {
    std::string text;
    std::unique_ptr<node> root;
    bool uses_q = false, uses_p = false;
};

formula parse(const std::string& text, const names& known);

}  // namespace sympl::app::formulas
