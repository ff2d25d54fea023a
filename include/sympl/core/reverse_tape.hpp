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
// One array of 16-byte records, written forwards and swept backwards, so
// that both passes stream through memory: a statement is its operations
// (multiplier, node) followed by its own record (adjoint, number of
// operations), and its node is that record's position. The adjoint is
// zeroed as the statement is written, where the record is in cache anyway,
// not by a pass of its own. One capacity check per statement.
// One tape per thread and scalar type, reused: no allocation once warm.
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "error.hpp"

namespace sympl::detail {

// An operation: d(statement)/d(node) = value, at `index` = node.
// A statement's own record: its adjoint in `value`, its operation count in `index`.
template <class T>
struct tape_record {
    T value;
    std::int32_t index;
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

    // Starts a recording with n independent variables: the records 1..n, with
    // no operations. Node 0 stands for every constant and is never written.
    void begin(std::size_t n, const char* who) {
        if (active() != nullptr)
            throw invalid_argument(std::string(who) +
                                   ": a reverse-mode gradient was asked for inside another of the same scalar type; "
                                   "expected one at a time per thread");
        if (n + 2 > std::size_t(INT32_MAX) / 2)
            throw invalid_argument(std::string(who) + ": " + std::to_string(n) +
                                   " independent variables; expected fewer than 2^30");
        inputs_ = n;
        end_ = 0;
        reserve(n + 1);
        for (std::size_t i = 0; i <= n; ++i) records_[i] = {T(0), 0};
        end_ = n + 1;
        active() = this;
    }

    // Writes one statement's operations through a cursor that stays in
    // registers while the expression emits (a member of the tape would be
    // stored and reloaded at every operation). A node met twice in a row
    // within a statement (r * r) is one operation: one update of its adjoint
    // instead of two that would wait on each other.
    struct writer {
        tape_record<T>* cursor;
        tape_record<T>* start;
        std::int32_t last = 0;
        void emit(std::int32_t node, T multiplier) {
            if (node == last) {
                cursor[-1].value += multiplier;
                return;
            }
            *cursor++ = {multiplier, node};
            last = node;
        }
    };
    // Room for a statement of at most `count` operations and its own record.
    writer open_statement(std::size_t count) {
        if (end_ + count + 1 > capacity_) [[unlikely]]
            reserve(end_ + count + 1);
        tape_record<T>* at = data_ + end_;
        return {at, at};
    }
    // Ends the statement `w` wrote; 0 when it has no operations (a value that
    // depends on no variable is a constant).
    std::int32_t close_statement(const writer& w) {
        const auto count = std::int32_t(w.cursor - w.start);
        if (count == 0) return 0;
        *w.cursor = {T(0), count};
        end_ = std::size_t(w.cursor - data_) + 1;
        return std::int32_t(end_ - 1);
    }

    // Sweeps backwards from `output`, whose adjoint is `seed`, and ends the recording; the adjoint of
    // input i (0-based) is then input_adjoint(i).
    void sweep(std::int32_t output, T seed = T(1)) {
        active() = nullptr;
        tape_record<T>* r = data_;
        if (output > 0) r[output].value = seed;
        for (std::size_t at = end_; at > inputs_ + 1;) {
            const tape_record<T> own = r[--at];
            const std::size_t first = at - std::size_t(own.index);
            for (std::size_t k = first; k < at; ++k) r[r[k].index].value += r[k].value * own.value;
            at = first;
        }
    }
    void abandon() { active() = nullptr; }
    const T& input_adjoint(std::size_t i) const { return data_[i + 1].value; }
    // Statements of the last recording (the constants' node, the inputs and
    // each one recorded) and operations: for tests, by a walk of the tape.
    std::size_t statements() const { return inputs_ + 1 + recorded().first; }
    std::size_t operations() const { return recorded().second; }

private:
    std::pair<std::size_t, std::size_t> recorded() const {
        std::size_t statements = 0, operations = 0;
        for (std::size_t at = end_; at > inputs_ + 1; at -= std::size_t(data_[at - 1].index) + 1) {
            ++statements;
            operations += std::size_t(data_[at - 1].index);
        }
        return {statements, operations};
    }
    void reserve(std::size_t needed) {
        if (needed >= std::size_t(INT32_MAX) / 2)
            throw invalid_argument("reverse mode: one evaluation recorded more than 2^30 operations; expected fewer "
                                   "(give the Hamiltonian an analytic force)");
        if (needed <= records_.size()) return;
        records_.resize(std::max<std::size_t>({4096, 2 * records_.size(), needed}));
        data_ = records_.data();
        capacity_ = records_.size();
    }

    std::vector<tape_record<T>> records_;
    tape_record<T>* data_ = nullptr;
    std::size_t inputs_ = 0, end_ = 0, capacity_ = 0;
};

}  // namespace sympl::detail
