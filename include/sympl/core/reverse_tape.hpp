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
// with no loop per statement: an edge's `of` is final when the sweep reaches
// it, since every edge that feeds it belongs to a later statement. Edges
// stream through memory (written forwards, read backwards); the adjoints are
// an array of their own, one per node, zeroed by one fill before the sweep.
// One capacity check per statement; one tape per thread and scalar type,
// reused: no allocation once warm. What it costs, and what was tried:
// docs/speed.md, "What each way of writing H costs".
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
    // reloaded at every operation). Each operand emits its pair of nodes (the
    // second 0 for a single node); the latest pair is held back in registers,
    // and the same pair again (r * r), or a single node after a held single
    // node (a - b), adds to it instead of opening edges. A statement that ends
    // holding everything it emitted writes nothing: its value is the held pair
    // with its partials (reverse_mode.hpp's taped). Anything else is written
    // out, a node possibly twice (x0 * x0 + x1 * x1 gives x0, x1, x1: the
    // sweep adds both; a test for it cost more than it saves, docs/speed.md). An
    // expression of one taped leaf is written by a writer with no cursor: it
    // emits once and can never flush.
    struct writer {
        tape_edge<T>* cursor;
        std::int32_t of;
        std::int32_t held = -1, held2 = 0;  // the held pair of nodes (held2 0: one node); none yet
        T partial = T(0), partial2 = T(0);
        // A taped value is a pair of nodes, the second 0 when it is one node.
        void emit(std::int32_t node, T p, std::int32_t node2, T p2) {
            if (node < 0) __builtin_unreachable();
            if (node == held && node2 == held2) {
                partial += p;
                partial2 += p2;
                return;
            }
            if (held2 == 0 && node2 == 0 && held >= 0) {  // two single nodes: one pair
                held2 = node;
                partial2 = p;
                return;
            }
            if (held >= 0) {
                *cursor++ = {partial, held, of};
                if (held2 != 0) *cursor++ = {partial2, held2, of};
            }
            held = node;
            partial = p;
            held2 = node2;
            partial2 = p2;
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
    // Ends the statement `w` wrote. Of three or more distinct nodes, it is
    // kept: the value is its node, with scale 1. Of two or fewer, it is not:
    // the value is the held nodes and partials (node 0 for none).
    template <class Value>
    void close_statement(const writer& w, Value& v) {
        if (w.cursor != end_) {
            tape_edge<T>* c = w.cursor;
            *c++ = {w.partial, w.held, w.of};
            if (w.held2 != 0) *c++ = {w.partial2, w.held2, w.of};
            end_ = c;
            v.node = std::int32_t(nodes_++);
            v.scale = T(1);
            v.node2 = 0;
            v.scale2 = T(0);
        } else {
            keep_held(w, v);
        }
    }
    template <class Value>
    static void keep_held(const writer& w, Value& v) {
        v.node = w.held;
        v.scale = w.partial;
        v.node2 = w.held2;
        v.scale2 = w.partial2;
    }

    // Sweeps backwards from the output, the nodes `output` and `output2` with
    // adjoints `seed` and `seed2` (a value of two nodes not recorded), and ends
    // the recording; the adjoint of input i (0-based) is then input_adjoint(i).
    // The adjoints are zeroed here in one pass, not one store per statement.
    void sweep(std::int32_t output, T seed = T(1), std::int32_t output2 = 0, T seed2 = T(0)) {
        active() = nullptr;
        T* adjoint = adjoints_data_;
        std::fill(adjoint, adjoint + nodes_, T(0));
        adjoint[output] = seed;  // node 0: a constant, whose adjoint no edge reads
        adjoint[output2] += seed2;
        const tape_edge<T>* first = edges_.data();
        // The adjoint of the statement being swept, and of the node written
        // last, are kept in registers: a running sum's next statement reads
        // the adjoint its last edge wrote without a store and a load between.
        std::int32_t of = -1, written = -1;
        T of_adjoint = T(0), written_adjoint = T(0);
        for (const tape_edge<T>* e = end_; e != first;) {
            --e;
            if (e->of != of) {
                of = e->of;
                of_adjoint = of == written ? written_adjoint : adjoint[of];
            }
            written = e->with_respect_to;
            written_adjoint = adjoint[written] + e->partial * of_adjoint;
            adjoint[written] = written_adjoint;
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
