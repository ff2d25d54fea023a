#pragma once
// An ensemble (ensemble.hpp) over the ranks of an MPI communicator
// (Boost.MPI): the batches are split in static blocks by index, rank r taking
// batches [B*r/K, B*(r+1)/K) of B, and the results are gathered in input
// order on the root. Each trajectory runs in the same lanes with the same
// arithmetic whatever the rank count, so the results are bitwise identical
// for 1, 2, 3 or any number of ranks. Link sympl::mpi (Boost.MPI and MPI).
#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <boost/mpi/collectives.hpp>
#include <boost/mpi/communicator.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include "ensemble.hpp"

namespace sympl {

// The index range of rank `rank` of `ranks` for n trajectories in batches of W.
inline std::pair<std::size_t, std::size_t> rank_block(std::size_t n, int W, int rank, int ranks) {
    const std::size_t batches = (n + std::size_t(W) - 1) / std::size_t(W);
    const std::size_t first = batches * std::size_t(rank) / std::size_t(ranks);
    const std::size_t last = batches * std::size_t(rank + 1) / std::size_t(ranks);
    return {std::min(n, first * std::size_t(W)), std::min(n, last * std::size_t(W))};
}

// Every rank passes the same starts and options; the root (rank `root`)
// returns all results in input order, the other ranks an empty vector.
template <int W = native_double_width, class H, class State, class Reduction = no_reduction>
std::vector<trajectory_result<State>> run_ensemble_mpi(const boost::mpi::communicator& world, const H& h,
                                                       const table& method, const std::vector<State>& starts,
                                                       const ensemble_options& o, const Reduction& reduction = {},
                                                       int root = 0) {
    const auto [begin, end] = rank_block(starts.size(), W, world.rank(), world.size());
    const auto mine = run_ensemble_range<W>(h, method, starts, begin, end, o, reduction);
    // Numbers as doubles (steps below 2^53 are exact), failures as strings.
    std::vector<double> numbers;
    std::vector<std::string> failures;
    for (const auto& r : mine) {
        for (Eigen::Index i = 0; i < r.final_state.size(); ++i) numbers.push_back(r.final_state.q[i]);
        for (Eigen::Index i = 0; i < r.final_state.size(); ++i) numbers.push_back(r.final_state.p[i]);
        numbers.insert(numbers.end(), {r.stable ? 1.0 : 0.0, double(r.blowup_step), r.blowup_time, r.max_energy_error,
                                       r.megno, r.quantity});
        failures.push_back(r.failure);
    }
    std::vector<std::vector<double>> all_numbers;
    std::vector<std::vector<std::string>> all_failures;
    boost::mpi::gather(world, numbers, all_numbers, root);
    boost::mpi::gather(world, failures, all_failures, root);
    std::vector<trajectory_result<State>> results;
    if (world.rank() != root) return results;
    const Eigen::Index n = starts.empty() ? 0 : starts.front().size();
    for (std::size_t rank = 0; rank < all_numbers.size(); ++rank) {
        const double* x = all_numbers[rank].data();
        for (const std::string& failure : all_failures[rank]) {
            trajectory_result<State> r;
            r.final_state = State(n);
            for (Eigen::Index i = 0; i < n; ++i) r.final_state.q[i] = *x++;
            for (Eigen::Index i = 0; i < n; ++i) r.final_state.p[i] = *x++;
            r.stable = *x++ != 0;
            r.blowup_step = std::size_t(*x++);
            r.blowup_time = *x++;
            r.max_energy_error = *x++;
            r.megno = *x++;
            r.quantity = *x++;
            r.failure = failure;
            results.push_back(std::move(r));
        }
    }
    return results;
}

}  // namespace sympl
