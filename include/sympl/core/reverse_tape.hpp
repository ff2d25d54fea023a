#pragma once
// The tape of reverse-mode differentiation (reverse_mode.hpp): one statement
// per value a function computes into a taped number, each with the partial
// derivatives of that value with respect to the earlier values it was computed
// from (Griewank & Walther, Evaluating Derivatives, 2nd ed. 2008, sec. 3.2 and
// 4.1; the statement-level form is Hogan 2014, ACM TOMS 40:26, sec. 2).
// The backward sweep accumulates adjoints statement by statement; the
// operations of one statement are independent of each other, so the sweep's
// chain of dependent memory updates is one per statement, not one per +, *.
//
// One tape per thread and scalar type, reused: no allocation once warm.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "error.hpp"

namespace sympl::detail {

// d(statement)/d(node) = multiplier.
template <class T>
struct tape_operation {
    T multiplier;
    std::int32_t node;
};

template <class T>
class reverse_tape {
public:
    static reverse_tape& of_this_thread() {
        thread_local reverse_tape tape;
        return tape;
    }
    // The tape recording on this thread, if any: a plain pointer, so that each
    // statement reaches it without thread_local's initialisation guard.
    static reverse_tape*& active() {
        thread_local reverse_tape* tape = nullptr;
        return tape;
    }

    // Starts a recording with n independent variables: statements 1..n, with no
    // operations. Statement 0 stands for every constant and is never swept.
    void begin(std::size_t n, const char* who) {
        if (active() != nullptr)
            throw invalid_argument(std::string(who) +
                                   ": a reverse-mode gradient was asked for inside another of the same scalar type; "
                                   "expected one at a time per thread");
        if (n + 2 > std::size_t(INT32_MAX))
            throw invalid_argument(std::string(who) + ": " + std::to_string(n) +
                                   " independent variables; expected fewer than 2^31");
        if (first_.size() < n + 2) first_.resize(std::max<std::size_t>(1024, 2 * (n + 2)));
        first_[n + 1] = 0;  // where the first statement's operations start; inputs have none, never read
        inputs_ = n;
        statements_ = n + 1;
        operations_ = 0;
        active() = this;
    }

    // Writes one statement's operations through a cursor that stays in
    // registers while the expression emits (a member of the tape would be
    // stored and reloaded at every operation). A node met twice in a row
    // within a statement (r * r) is one operation: one update of its adjoint
    // instead of two that would wait on each other.
    struct writer {
        tape_operation<T>* cursor;
        tape_operation<T>* start;
        std::int32_t last = 0;
        void emit(std::int32_t node, T multiplier) {
            if (node == last) {
                cursor[-1].multiplier += multiplier;
                return;
            }
            *cursor++ = {multiplier, node};
            last = node;
        }
    };
    // Room for a statement of at most `count` operations.
    writer open_statement(std::size_t count) {
        if (operations_ + count > ops_.size()) [[unlikely]]
            grow(operations_ + count);
        tape_operation<T>* at = ops_.data() + operations_;
        return {at, at};
    }
    // Ends the statement `w` wrote; 0 when it has no operations (a value that
    // depends on no variable is a constant).
    std::int32_t close_statement(const writer& w) {
        if (w.cursor == w.start) return 0;
        if (statements_ + 2 > first_.size()) [[unlikely]]
            grow_statements();
        operations_ += std::size_t(w.cursor - w.start);
        first_[statements_ + 1] = std::int32_t(operations_);
        return std::int32_t(statements_++);
    }

    // Sweeps backwards from `output`, whose adjoint is `seed`, and ends the recording; the adjoint of
    // input i (0-based) is then input_adjoint(i).
    void sweep(std::int32_t output, T seed = T(1)) {
        active() = nullptr;
        adjoints_.assign(statements_, T(0));
        if (output > 0) adjoints_[std::size_t(output)] = seed;
        T* adj = adjoints_.data();
        const tape_operation<T>* op = ops_.data();
        const std::int32_t* first = first_.data();
        for (std::size_t s = statements_; s-- > inputs_ + 1;) {
            const T g = adj[s];
            for (std::int32_t k = first[s]; k < first[s + 1]; ++k) adj[op[k].node] += op[k].multiplier * g;
        }
    }
    void abandon() { active() = nullptr; }
    const T& input_adjoint(std::size_t i) const { return adjoints_[i + 1]; }
    std::size_t statements() const { return statements_; }
    std::size_t operations() const { return operations_; }

private:
    void grow(std::size_t needed) {
        if (needed >= std::size_t(INT32_MAX) / 2)
            throw invalid_argument("reverse mode: one evaluation recorded more than 2^30 operations; expected fewer "
                                   "(give the Hamiltonian an analytic force)");
        ops_.resize(std::max<std::size_t>({4096, 2 * ops_.size(), needed}));
    }
    void grow_statements() {
        if (first_.size() >= std::size_t(INT32_MAX) / 2)
            throw invalid_argument("reverse mode: one evaluation recorded more than 2^30 statements; expected fewer");
        first_.resize(2 * first_.size());
    }

    std::vector<std::int32_t> first_;  // statement s's operations are [first_[s], first_[s + 1])
    std::vector<tape_operation<T>> ops_;
    std::vector<T> adjoints_;
    std::size_t inputs_ = 0, statements_ = 0, operations_ = 0;
};

}  // namespace sympl::detail
