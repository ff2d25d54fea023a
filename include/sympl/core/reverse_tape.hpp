#pragma once
// The tape of reverse-mode differentiation (reverse_mode.hpp): one statement
// per value a function computes into a taped number, each with the partial
// derivatives of that value with respect to the earlier values it was computed
// from (Griewank & Walther, Evaluating Derivatives, 2nd ed. 2008, sec. 3.2 and
// 4.1; the statement-level form is Hogan 2014, ACM TOMS 40:26, sec. 2).
//
// The partials are worked out as the statement is recorded, so the tape is a
// list of edges of the computational graph, each a partial derivative with the
// node it is taken of and the node it is taken with respect to. The backward
// sweep walks the edges last to first and does one multiply-add per edge,
//     adjoint[with_respect_to] += partial * adjoint[of],
// with no branch on what the edge came from and no loop per statement: an
// edge's `of` is final when the sweep reaches it, since every edge that feeds
// it belongs to a later statement. Edges stream through memory (written
// forwards, read backwards); the adjoints are an array of their own, one per
// node, zeroed by one fill before the sweep. One capacity check per
// statement; one tape per thread and scalar type, reused: no allocation once
// warm.
//
// What it costs (FPU chain, 2 statements and 4 edges per particle; 2026-11-27,
// loaded 2-core machine, least of many calls): recording 3.8 ns and the sweep
// 4.0 ns per particle. Both wait on memory rather than on arithmetic: each
// statement stores the tape's end and the next one loads it back (GCC keeps
// it in memory across statements), and the sweep carries the running sum's
// adjoint from one particle to the next through a store and a load.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "error.hpp"

namespace sympl::detail {

// d(node `of`)/d(node `with_respect_to`) = partial.
template <class T>
struct tape_edge {
    T partial;
    std::int32_t with_respect_to;
    std::int32_t of;
};

// Where an expression of one taped operand emits its single partial: in
// registers, never on the tape (such a value records no statement).
template <class T>
struct one_operand {
    std::int32_t node = 0;
    T partial = T(1);
    void emit(std::int32_t n, T p) {
        node = n;
        partial = p;
    }
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

    // Starts a recording with n independent variables: the nodes 1..n. Node 0
    // stands for every constant: an edge to it costs less than a test for it
    // at every operand, and its adjoint is never read.
    void begin(std::size_t n, const char* who) {
        if (active() != nullptr)
            throw invalid_argument(std::string(who) +
                                   ": a reverse-mode gradient was asked for inside another of the same scalar type; "
                                   "expected one at a time per thread");
        if (n + 2 > std::size_t(INT32_MAX) / 2)
            throw invalid_argument(std::string(who) + ": " + std::to_string(n) +
                                   " independent variables; expected fewer than 2^30");
        end_ = edges_.data();
        nodes_ = std::ptrdiff_t(n + 1);
        reserve(0);
        active() = this;
    }

    // Writes one statement's edges through a cursor that stays in registers
    // while the expression emits (a member of the tape would be stored and
    // reloaded at every operation). A node met twice in a row within a
    // statement (r * r) is one edge: one update of its adjoint instead of two
    // that would wait on each other. The latest edge is held back in
    // registers, so that a statement of one node writes nothing.
    struct writer {
        tape_edge<T>* cursor;
        std::int32_t of;
        std::int32_t last = -1;  // the held edge's node; none yet
        T held = T(0);           // and its partial
        void emit(std::int32_t node, T partial) {
            // Nodes are never negative: told, the first emit of a statement
            // compiles to no test against `last`, and the others to no test
            // of whether an edge is held.
            if (node < 0) __builtin_unreachable();
            if (node == last) {
                held += partial;
                return;
            }
            if (last >= 0) *cursor++ = {held, last, of};
            last = node;
            held = partial;
        }
    };
    // Room for a statement of at most `count` edges.
    writer open_statement(std::size_t count) {
        // In bytes: a count of edges would cost a division by their size.
        if (reinterpret_cast<const char*>(capacity_end_) - reinterpret_cast<const char*>(end_) <
            std::ptrdiff_t(count * sizeof(tape_edge<T>))) [[unlikely]]
            reserve(count);
        return {end_, std::int32_t(nodes_)};
    }
    // Ends the statement `w` wrote: `node` and `scale` of the value it
    // computed. A statement of one edge (its operands one node, or constants)
    // is not kept: its value is that edge's node, scaled by the edge's partial
    // (reverse_mode.hpp's taped).
    void close_statement(const writer& w, std::int32_t& node, T& scale) {
        if (w.cursor != end_) [[likely]] {
            *w.cursor = {w.held, w.last, w.of};
            end_ = w.cursor + 1;
            node = std::int32_t(nodes_++);
            scale = T(1);
        } else {
            node = w.last;
            scale = w.held;
        }
    }

    // Sweeps backwards from `output`, whose adjoint is `seed`, and ends the
    // recording; the adjoint of input i (0-based) is then input_adjoint(i).
    // The adjoints are zeroed here in one pass, not one store per statement.
    void sweep(std::int32_t output, T seed = T(1)) {
        active() = nullptr;
        T* adjoint = adjoints_data_;
        std::fill(adjoint, adjoint + nodes_, T(0));
        adjoint[output] = seed;  // output 0: a constant, whose adjoint no edge reads
        const tape_edge<T>* first = edges_.data();
#pragma GCC unroll 2
        for (const tape_edge<T>* e = end_; e != first;) {
            --e;
            adjoint[e->with_respect_to] += e->partial * adjoint[e->of];
        }
    }
    void abandon() { active() = nullptr; }
    const T& input_adjoint(std::size_t i) const { return adjoints_data_[i + 1]; }
    // Nodes of the last recording (the constants' node, the inputs and each
    // statement recorded) and edges: for tests.
    std::size_t statements() const { return std::size_t(nodes_); }
    std::size_t operations() const { return std::size_t(end_ - edges_.data()); }

private:
    // Room for `edges` more edges, and an adjoint for every node they could
    // open: each statement has at least one edge, so a node per edge of room
    // is enough, and open_statement need not check the adjoints too.
    void reserve(std::size_t edges) {
        const std::size_t used = std::size_t(end_ - edges_.data()), needed = used + edges;
        if (std::size_t(nodes_) + needed >= std::size_t(INT32_MAX) / 2)
            throw invalid_argument("reverse mode: one evaluation recorded more than 2^30 operations; expected fewer "
                                   "(give the Hamiltonian an analytic force)");
        if (needed > edges_.size()) edges_.resize(std::max<std::size_t>({4096, 2 * edges_.size(), needed}));
        end_ = edges_.data() + used;
        capacity_end_ = edges_.data() + edges_.size();
        const std::size_t node_room = std::size_t(nodes_) + (edges_.size() - used);
        if (node_room > adjoints_.size()) adjoints_.resize(std::max(node_room, 2 * adjoints_.size()));
        adjoints_data_ = adjoints_.data();
    }

    std::vector<tape_edge<T>> edges_;
    std::vector<T> adjoints_;
    tape_edge<T>* end_ = nullptr;           // one past the last edge recorded
    tape_edge<T>* capacity_end_ = nullptr;  // one past the room for edges
    T* adjoints_data_ = nullptr;
    std::ptrdiff_t nodes_ = 0;  // nodes so far; the next statement's node
};

}  // namespace sympl::detail
