// The report's rows: measured, timed, gathered, finished.
#include "report/report_rows.hpp"

#include <atomic>
#include <charconv>

#include "output/format.hpp"
#include "report/loop_area.hpp"
#include "running/systems.hpp"
#include "report/timing.hpp"

#include <sympl/parallel/ensemble.hpp>

namespace sympl::app {

namespace {

// A row's measurements as text, for the gather to rank 0 under MPI: numbers
// as the shortest text that reads back as the same double (to_chars), the
// failure message with its length. Rank 0 then has exactly what it would
// have measured itself, timings aside.
std::string row_record(std::size_t index, const report_row& r) {
    std::string t = std::to_string(index);
    const auto number = [&](double v) { t += ' ' + shortest(v); };
    const run_result& m = r.r;
    t += ' ' + std::to_string(int(m.stable)) + ' ' + std::to_string(int(m.generic)) + ' ' +
         std::to_string(m.blowup_step);
    number(m.blowup_time);
    t += ' ' + std::to_string(m.steps) + ' ' + std::to_string(m.force_evaluations);
    number(m.max_energy_error);
    number(r.loop_area_error);
    t += ' ' + std::to_string(m.final_state.size());
    for (double v : m.final_state) number(v);
    t += ' ' + std::to_string(r.times.size());
    for (double v : r.times) number(v);
    t += ' ' + std::to_string(m.failure.size()) + ' ' + m.failure + '\n';
    return t;
}

// Reads the records of one rank's block into `rows`.
void read_row_records(const std::string& block, std::vector<report_row>& rows) {
    const char* at = block.data();
    const char* const end = block.data() + block.size();
    const auto fail = [] {
        throw error("sympl report: a rank sent a malformed result record; expected the same sympl on every rank");
    };
    const auto word = [&](auto& v) {
        while (at < end && (*at == ' ' || *at == '\n')) ++at;
        const auto [next, ec] = std::from_chars(at, end, v);
        if (ec != std::errc()) fail();
        at = next;
    };
    const auto count = [&](std::size_t largest) {
        std::size_t n = 0;
        word(n);
        if (n > largest) fail();
        return n;
    };
    while (true) {
        while (at < end && *at == '\n') ++at;
        if (at == end) return;
        report_row& r = rows.at(count(rows.size() - 1));
        run_result& m = r.r;
        m.stable = count(1) == 1;
        m.generic = count(1) == 1;
        word(m.blowup_step);
        word(m.blowup_time);
        word(m.steps);
        word(m.force_evaluations);
        word(m.max_energy_error);
        word(r.loop_area_error);
        m.final_state.resize(count(std::size_t(1) << 30));
        for (double& v : m.final_state) word(v);
        r.times.resize(count(1000));
        for (double& v : r.times) word(v);
        const std::size_t n = count(std::size_t(1) << 20);
        if (at == end || *at != ' ' || std::size_t(end - at - 1) < n) fail();
        m.failure.assign(at + 1, n);
        at += 1 + n;
    }
}

}  // namespace

std::vector<report_row> rows_of(const std::vector<run_plan>& plans, const std::vector<runnable_system>& systems) {
    std::vector<report_row> rows;
    for (std::size_t k = 0; k < plans.size(); ++k)
        for (const planned_run& r : plans[k].runs) rows.push_back({.s = plans[k].s, .run = &r, .p = &systems[k]});
    return rows;
}

namespace {

// The rows this process runs that `keep` accepts, in order.
template <class Keep>
std::vector<std::size_t> rows_to_run(const std::vector<report_row>& rows, const row_filter& mine, const Keep& keep) {
    std::vector<std::size_t> picked;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (mine(i) && keep(rows[i])) picked.push_back(i);
    return picked;
}

// A system of the row's own, made as the report made the scene's: runs on
// different threads share no system object (a system may keep what it has
// found out about its H between calls).
runnable_system own_problem(const report_row& r) { return make_system(r.s->system, r.s->parameters, r.s->q0, r.s->p0, r.s->source); }

}  // namespace

void measure_rows(std::vector<report_row>& rows, const row_filter& mine, const progress& bar, int threads,
                  const std::vector<std::function<void()>>& first) {
    const std::vector<std::size_t> picked = rows_to_run(rows, mine, [](const report_row&) { return true; });
    std::atomic<std::size_t> finished{0};
    for_each_in_parallel(first.size() + picked.size(), threads, [&](std::size_t k) {
        if (k < first.size()) {
            first[k]();
            bar.show("references " + counter(++finished, first.size() + picked.size()));
            return;
        }
        report_row& r = rows[picked[k - first.size()]];
        const runnable_system p = own_problem(r);
        run_request rq = r.run->request();
        rq.energy = p.hamiltonian;
        rq.timing_repeats = 0;
        r.r = p.run(r.method(), rq, r.s->t0, r.s->t_end, p.x0);
        if (r.r.stable && r.s->output.loop_area) r.loop_area_error = loop_area_error(p, r.method(), rq, r.s->t0, r.s->t_end);
        bar.show("measured runs " + counter(++finished, first.size() + picked.size()) + r.s->name + ": " + r.method().name + " " +
                 format_number(r.run->setting()));
    });
}

namespace {

// Both measures at order one (report_write.hpp): the energy error, and the
// final error where it is measured here.
bool no_solution(const report_row& r, const std::map<const scene*, reference_state>& references) {
    if (!(r.r.max_energy_error >= order_one_error)) return false;  // also: no energy (-1)
    if (r.p->exact) return relative_difference(r.r.final_state, r.p->exact(r.s->t_end - r.s->t0)) >= order_one_error;
    const auto ref = references.find(r.s);
    if (ref == references.end()) return false;  // another rank holds the reference: timed, to be safe
    return !ref->second.failure.empty() || relative_difference(r.r.final_state, ref->second.x) >= order_one_error;
}

}  // namespace

void time_rows(std::vector<report_row>& rows, const row_filter& mine, int rounds, double least, const progress& bar,
               const std::map<const scene*, reference_state>& references, int threads) {
    const std::vector<std::size_t> picked =
        rows_to_run(rows, mine, [&](const report_row& r) { return r.r.stable && !no_solution(r, references); });
    for (int round = 0; round < rounds; ++round) {
        bar.show("timing, round " + std::to_string(round + 1) + " of " + std::to_string(rounds));
        for_each_in_parallel(picked.size(), threads, [&](std::size_t k) {
            report_row& r = rows[picked[k]];
            const runnable_system p = own_problem(r);
            run_request rq = r.run->request();
            rq.observed = false;
            rq.timing_repeats = 1;
            rq.min_measurement = least;
            r.times.push_back(p.run(r.method(), rq, r.s->t0, r.s->t_end, p.x0).seconds);
        });
    }
}

void gather_rows(std::vector<report_row>& rows, const row_filter& mine, const exchange& ranks) {
    if (ranks.size <= 1) return;
    std::string records;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (mine(i)) records += row_record(i, rows[i]);
    for (const std::string& block : ranks.gather(records)) read_row_records(block, rows);
}

void finish_rows(std::vector<report_row>& rows, const std::map<const scene*, reference_state>& references) {
    for (report_row& r : rows) {
        const reference_state& ref = references.at(r.s);
        if (r.r.stable && ref.failure.empty()) r.final_error = relative_difference(r.r.final_state, ref.x);
        if (r.times.empty()) continue;
        const timing t = summary_of(r.times);
        r.r.seconds = t.median;
        r.r.seconds_min = t.min;
        r.r.seconds_max = t.max;
    }
}

}  // namespace sympl::app
