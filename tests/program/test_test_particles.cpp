// A scene's [test_particles] (scene_test_particles.cpp, run_test_particles.hpp):
//   (a) each error of the table, with its line and what was expected;
//   (b) a small belt run of 440 years: MEGNO near 2 for particles far inside
//       Jupiter (2.2-3.2 AU, not the 3:1 resonance), above 4 for some just
//       outside it, in the chaotic zone of Wisdom (1980) and Duncan, Quinn &
//       Tremaine (1989);
//   (c) test_particles.csv byte-identical for 1 and 2 threads;
//   (d) the built-in belt scene parses, runs by name, and its map is drawn.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "reading/scene.hpp"
#include "scratch_directory.hpp"
#include "commands/ensemble_run.hpp"
#include "output/row_checkpoint.hpp"
#include "commands/run_test_particles.hpp"
#include "output/format.hpp"
#include "methods/run_plan.hpp"
#include "report/report.hpp"
#include "output/writers.hpp"

namespace test_program_test_test_particles {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
// a from 2.2 AU (regular) to 5.9 AU (near Jupiter) in steps of 0.1 AU, at e = 0 and 0.05.
const std::string belt = R"toml(name = "belt"
system = "outer_solar_system"
methods = ["wh(saba_2)"]
dt = 20
t_end = 160000
[test_particles]
grid = {a = {from = 2.2, to = 5.9, count = 38}, e = {from = 0.0, to = 0.05, count = 2}}
indicator = "megno"
)toml";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
}

std::string error_of(const std::string& text) {
    try {
        parse_scene(text, "belt.toml");
    } catch (const sympl::error& e) {
        return e.what();
    }
    return "no error";
}

std::string contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

TEST_CASE("test particles belt: the scene table's errors, each with its line") {
    const scene s = parse_scene(belt, "belt.toml");
    REQUIRE(s.test_particles);
    CHECK(s.test_particles->grid_size() == 76);
    CHECK(s.test_particles->megno);
    const std::string grid = "grid = {a = {from = 2.2, to = 5.9, count = 38}, e = {from = 0.0, to = 0.05, count = 2}}";
    CHECK(error_of(replaced(belt, "indicator", "indicatr")) ==
          "belt.toml:8:12: unknown key 'indicatr' in [test_particles]; did you mean 'indicator'? expected one of: "
          "elements, grid, inclination, indicator, mean_anomaly, node, pericentre");
    CHECK(error_of(replaced(belt, "count = 38", "count = 0")) ==
          "belt.toml:7:44: 'test_particles.grid.a.count' = 0; expected an integer in [1, 1000000]");
    CHECK(error_of(replaced(belt, "count = 38", "count = 2.5")) ==
          "belt.toml:7:44: 'test_particles.grid.a.count' = 2.5; expected an integer in [1, 1000000]");
    CHECK(error_of(replaced(belt, "count = 38", "count = 1000000")) ==
          "belt.toml:7:8: the grid has 1000000 x 2 = 2000000 test particles; expected at most 1000000");
    CHECK(error_of(replaced(belt, "from = 2.2", "from = -1")) ==
          "belt.toml:7:21: 'test_particles.grid.a.from' = -1; expected a finite semi-major axis > 0 (AU)");
    CHECK(error_of(replaced(belt, "to = 0.05", "to = 1")) ==
          "belt.toml:7:71: 'test_particles.grid.e.to' = 1; expected an eccentricity in [0, 1) (elliptic orbits)");
    // Orbits the run would remove at its first step: refused with the figure.
    CHECK(error_of(replaced(belt, "from = 2.2", "from = 0.005")) ==
          "belt.toml:7:8: test_particles.grid holds a = 0.005 AU, e = 0.05: pericentre 0.00475 AU, inside the star; "
          "expected orbits between the star's radius (0.005 AU) and the escape distance (100 AU)");
    CHECK(error_of(replaced(belt, "to = 5.9", "to = 99")) ==
          "belt.toml:7:8: test_particles.grid holds a = 99 AU, e = 0.05: apocentre 103.95 AU, past the escape "
          "distance; expected orbits between the star's radius (0.005 AU) and the escape distance (100 AU)");
    CHECK(error_of(replaced(belt, ", e = {from = 0.0, to = 0.05, count = 2}", "")) ==
          "belt.toml:7:8: 'test_particles.grid' has no 'e'; expected {a = ..., e = ...}");
    CHECK(error_of(replaced(belt, grid, "")) ==
          "belt.toml:6:1: [test_particles] needs either grid = {a = {from, to, count}, e = {from, to, count}} or "
          "elements = \"file.csv\"");
    CHECK(error_of(replaced(belt, grid, grid + "\nelements = \"e.csv\"")) ==
          "belt.toml:6:1: [test_particles] needs either grid = {a = {from, to, count}, e = {from, to, count}} or "
          "elements = \"file.csv\"");
    CHECK(error_of(replaced(belt, grid, "elements = \"e.csv\"\ninclination = 3")) ==
          "belt.toml:8:15: 'test_particles.inclination' with elements = \"...\": the file gives the angles; expected "
          "it only with grid");
    CHECK(error_of(replaced(belt, "\"megno\"", "\"lyapunov\"")) ==
          "belt.toml:8:13: test_particles.indicator = 'lyapunov'; expected \"megno\" or \"none\"");
    CHECK(error_of(replaced(belt, "wh(saba_2)", "saba_2")) ==
          "belt.toml:3:11: [test_particles] runs one Wisdom-Holman method; expected methods = [\"wh(<table>, ...)\"], "
          "not 1 method(s) starting with 'saba_2'");
    CHECK(error_of(replaced(belt, "dt = 20", "dt = [20, 10]")) ==
          "belt.toml:6:1: [test_particles] runs one step size; expected dt = <number>, not a sweep");
    CHECK(error_of(replaced(replaced(belt, "outer_solar_system", "kepler"), "wh(saba_2)", "saba_2")) ==
          "belt.toml:6:1: [test_particles] needs a planetary system (a star and planets with masses and G); 'kepler' "
          "is not one (expected system = \"outer_solar_system\")");
}

TEST_CASE("test particles belt: the elements file's errors name it and the line") {
    const fs::path dir = scratch_directory("sympl_test_belt_elements");
    fs::create_directories(dir);
    const auto orbits_of = [&](const std::string& csv) -> std::string {
        std::ofstream(dir / "e.csv", std::ios::binary) << csv;
        const scene s = parse_scene(replaced(belt, "grid = {a = {from = 2.2, to = 5.9, count = 38}, e = {from = 0.0, "
                                                   "to = 0.05, count = 2}}",
                                             "elements = \"e.csv\""),
                                    (dir / "belt.toml").string());
        try {
            return std::to_string(test_particle_orbits(s).size());
        } catch (const sympl::error& e) {
            return std::string(e.what()).substr((dir / "e.csv").string().size());
        }
    };
    CHECK(orbits_of("a,e\n6.5,0.1\n7,0\n") == "2");
    CHECK(orbits_of("a,e,inclination\n6.5,0.1,2\n") == "1");
    CHECK(orbits_of("a,i\n6.5,0.1\n") ==
          ":1: header 'a,i'; expected 'a,e' and optionally the next of ',inclination,node,pericentre,mean_anomaly' in "
          "that order (angles in degrees)");
    CHECK(orbits_of("a,e\n6.5,0.1\n7,1.5\n") == ":3: e = 1.5; expected an eccentricity in [0, 1) (elliptic orbits)");
    CHECK(orbits_of("a,e\n6.5,0.1\n120,0\n") ==
          ":3: a = 120 AU, e = 0: apocentre 120 AU, past the escape distance; expected orbits between the star's "
          "radius (0.005 AU) and the escape distance (100 AU)");
    CHECK(orbits_of("a,e\n6.5,x\n") == ":2: field 2 'x'; expected a finite number");
    CHECK(orbits_of("a,e\n6.5,0.1,3\n") == ":2: 3 fields; expected 2 as the header names");
    CHECK(orbits_of("a,e\n") == ": no orbits; expected a header and at least one line of elements");
    fs::remove_all(dir);
}

TEST_CASE("test particles belt: MEGNO about 2 far inside Jupiter, above 4 near it, the same for 1 and 2 threads") {
    const scene s = parse_scene(belt, "belt.toml");
    const fs::path dir = scratch_directory("sympl_test_belt");
    std::ostringstream said;
    // Pieces of 16 particles (5 pieces, not the program's one of 256 here), so that the threads share them.
    test_particles_command(s, dir / "one", 1, default_max_steps, said, 16);
    test_particles_command(s, dir / "two", 2, default_max_steps, said, 16);
    MESSAGE(said.str());
    const std::string one = contents(dir / "one" / "test_particles.csv");
    REQUIRE(!one.empty());
    CHECK(one == contents(dir / "two" / "test_particles.csv"));
    CHECK(fs::exists(dir / "one" / "summary.md"));
    if (have_gnuplot()) CHECK(fs::exists(dir / "one" / "test_particles_megno.png"));
    const std::vector<test_particle_row> rows = run_test_particles(s, test_particle_orbits(s), 2, default_max_steps);
    REQUIRE(rows.size() == 76);
    double worst_regular = 0, most_chaotic = 0;
    for (const test_particle_row& r : rows) {
        // Inside the 2:1 resonance with Jupiter (3.28 AU) but for the 3:1 at
        // 2.5 AU, the Kirkwood gap whose orbits are chaotic (Wisdom 1982, AJ 87, 577).
        if (r.start.a <= 3.2 && std::fabs(r.start.a - 2.5) > 0.05) {
            REQUIRE(r.kept);
            worst_regular = std::max(worst_regular, std::fabs(r.megno - 2));
            CHECK(std::fabs(r.a - r.start.a) < 0.05 * r.start.a);
        }
        if (r.start.a >= 5.6 && r.kept) most_chaotic = std::max(most_chaotic, r.megno);
    }
    MESSAGE("MEGNO: within " << worst_regular << " of 2 at a <= 3.2 AU (not 2.5), up to " << most_chaotic
                               << " at a >= 5.6 AU");
    CHECK(worst_regular < 0.15);
    CHECK(most_chaotic > 4);
    fs::remove_all(dir);
}

TEST_CASE("test particles belt: pieces shared among 3 ranks give rank 0 the rows of one process, bit for bit") {
    const scene s = parse_scene(replaced(belt, "t_end = 160000", "t_end = 40000"), "belt.toml");
    const std::vector<sympl::orbital_elements> orbits = test_particle_orbits(s);
    // Pieces of 16: 5 pieces, ranks 0 and 1 two each, rank 2 one.
    const std::vector<test_particle_row> alone = run_test_particles(s, orbits, 1, default_max_steps, 16);
    auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    std::vector<std::string> texts(3);
    std::size_t removed = 0;
    for (int rank : {1, 2, 0}) {  // the others first: rank 0's gather returns what they sent
        exchange ranks;
        ranks.rank = rank;
        ranks.size = 3;
        ranks.gather = [&texts, rank](const std::string& mine) {
            texts[std::size_t(rank)] = mine;
            return rank == 0 ? texts : std::vector<std::string>{};
        };
        const std::vector<test_particle_row> rows =
            run_test_particles(s, orbits, 1, default_max_steps, ranks, false, 16);
        if (rank != 0) {
            CHECK(rows.empty());
            CHECK_FALSE(texts[std::size_t(rank)].empty());
            continue;
        }
        REQUIRE(rows.size() == alone.size());
        for (std::size_t i = 0; i < rows.size(); ++i) {
            INFO("particle " << i);
            CHECK(rows[i].kept == alone[i].kept);
            CHECK(rows[i].reason == alone[i].reason);
            CHECK(same_bits(rows[i].start.a, alone[i].start.a));
            CHECK(same_bits(rows[i].start.e, alone[i].start.e));
            for (auto field : {&test_particle_row::megno, &test_particle_row::a, &test_particle_row::e,
                               &test_particle_row::removed_time})
                CHECK(same_bits(rows[i].*field, alone[i].*field));
            removed += rows[i].kept ? 0 : 1;
        }
    }
    CHECK(removed > 0);  // reasons and times crossed between ranks too
    // Bytes that are not whole rows: an error that says where, never rows made up.
    exchange broken;
    broken.size = 2;
    broken.gather = [](const std::string& mine) { return std::vector<std::string>{mine, "abc"}; };
    CHECK_THROWS_WITH_AS(run_test_particles(s, orbits, 1, default_max_steps, broken, false, 16),
                         "run_test_particles: a rank's rows end at byte 0 of 3; expected whole rows of this run's "
                         "particles",
                         sympl::error);
}

TEST_CASE("test particles belt: a checkpointed map resumes the pieces no file holds, to the bits of a whole run") {
    const fs::path dir = scratch_directory("sympl_test_belt_checkpoint");
    const std::string file = (dir / "state" / "belt").string();
    fs::create_directories(dir / "state");
    const std::string text = replaced(belt, "t_end = 160000", "t_end = 40000") + "";
    const scene s = parse_scene(replaced(text, "dt = 20\n", "dt = 20\ncheckpoint = {every_steps = 1, file = \"" + file +
                                                                   "\"}\n"),
                                "belt.toml");
    const std::vector<sympl::orbital_elements> orbits = test_particle_orbits(s);
    const std::vector<test_particle_row> whole = run_test_particles(s, orbits, 1, default_max_steps, 16);
    auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    auto same = [](const std::vector<test_particle_row>& a, const std::vector<test_particle_row>& b) {
        bool all = a.size() == b.size();
        for (std::size_t i = 0; all && i < a.size(); ++i)
            all = a[i].kept == b[i].kept && a[i].reason == b[i].reason &&
                  std::memcmp(&a[i].megno, &b[i].megno, sizeof(double)) == 0 &&
                  std::memcmp(&a[i].a, &b[i].a, sizeof(double)) == 0 &&
                  std::memcmp(&a[i].e, &b[i].e, sizeof(double)) == 0 &&
                  std::memcmp(&a[i].removed_time, &b[i].removed_time, sizeof(double)) == 0 &&
                  std::memcmp(&a[i].start.a, &b[i].start.a, sizeof(double)) == 0;
        return all;
    };
    remove_test_particle_checkpoints(s);
    // Rank 1 of 2 runs pieces 1 and 3 and saves them; a resume in one process runs 0, 2 and 4 only.
    exchange half;
    half.rank = 1;
    half.size = 2;
    half.gather = [](const std::string&) { return std::vector<std::string>{}; };
    run_test_particles(s, orbits, 1, default_max_steps, half, false, 16);
    REQUIRE(fs::exists(dir / "state" / "belt.test-particles-rank-1"));
    CHECK(same(run_test_particles(s, orbits, 1, default_max_steps, exchange{}, true, 16), whole));
    // What a file holds is taken, not run again: piece 1 (particles 16-31) saved
    // whole with MEGNO 42 comes back so; piece 2 with one row missing runs anew.
    remove_test_particle_checkpoints(s);
    std::string rows;
    for (std::size_t i = 16; i < 47; ++i) rows += "row " + std::to_string(i) + " 1 0x1.5p+5 0x1p+0 0x0p+0 0x0p+0 0 \n";
    write_row_checkpoint(row_checkpoint_file(file, "test-particles", 5), "sympl-test-particles-checkpoint 1\n",
                         s.text_hash, rows);
    const std::vector<test_particle_row> taken = run_test_particles(s, orbits, 1, default_max_steps, exchange{}, true, 16);
    CHECK(taken[16].megno == 42);
    CHECK(taken[31].megno == 42);
    CHECK(same_bits(taken[32].megno, whole[32].megno));
    CHECK(same_bits(taken[15].megno, whole[15].megno));
    remove_test_particle_checkpoints(s);
    run_test_particles(s, orbits, 1, default_max_steps, half, false, 16);
    // A resume of a file that is not whole is refused with the reason, never read in part.
    {
        std::ofstream cut(dir / "state" / "belt.test-particles-rank-1", std::ios::app | std::ios::binary);
        cut << "row";
    }
    CHECK_THROWS_WITH_AS(run_test_particles(s, orbits, 1, default_max_steps, exchange{}, true, 16),
                         doctest::Contains("belt.test-particles-rank-1: is corrupted (checksum mismatch); not resumed "
                                           "from (remove it to start over)"),
                         sympl::error);
    remove_test_particle_checkpoints(s);
    CHECK_FALSE(fs::exists(dir / "state" / "belt.test-particles-rank-1"));
    // --resume without a checkpoint in the scene says so.
    CHECK_THROWS_WITH_AS(run_test_particles(parse_scene(text, "belt.toml"), orbits, 1, default_max_steps, exchange{},
                                            true, 16),
                         "belt.toml: --resume, but the scene has no checkpoint = {every_steps = N, file = \"...\"}",
                         sympl::error);
    fs::remove_all(dir);
}

TEST_CASE("test particles belt: planets not on bound orbits about the star are refused up front, nothing written") {
    const runnable_system planets = system_of(parse_scene(belt, "belt.toml"));
    const std::size_t n = planets.x0.size() / 2;
    // The scene with p[i] replaced where `momentum` says.
    const auto with = [&](auto momentum) {
        std::string q = "q = [", p = "p = [";
        for (std::size_t i = 0; i < n; ++i) {
            q += (i ? ", " : "") + shortest(planets.x0[i]);
            p += (i ? ", " : "") + momentum(i, planets.x0[n + i]);
        }
        return parse_scene(belt + "[initial]\n" + q + "]\n" + p + "]\n", "belt.toml");
    };
    const fs::path dir = scratch_directory("sympl_test_belt_unbound");
    fs::remove_all(dir);
    std::ostringstream said;
    // Every body at rest: the planets fall into the star (e = 1, pericentre 0).
    CHECK_THROWS_WITH_AS(test_particles_command(with([](std::size_t, double) { return std::string("0"); }), dir, 1,
                                                default_max_steps, said),
                         doctest::Contains("belt.toml: the planet jupiter starts on a heliocentric orbit with a = "),
                         sympl::error);
    CHECK_THROWS_WITH_AS(test_particles_command(with([](std::size_t, double) { return std::string("0"); }), dir, 1,
                                                default_max_steps, said),
                         doctest::Contains(": pericentre 0 AU, inside the star; expected planets on bound orbits "
                                           "outside the star (0.005 AU)"),
                         sympl::error);
    // Jupiter at twice its speed (escape is sqrt(2) times a circular orbit's), and at a momentum of 1e300
    // (finite, so accepted by the state's checks, its square not).
    for (const auto& fast : {std::function<std::string(std::size_t, double)>([](std::size_t i, double v) {
                                 return shortest(i >= 3 && i < 6 ? 2 * v : v);
                             }),
                             std::function<std::string(std::size_t, double)>([](std::size_t i, double v) {
                                 return i == 3 ? std::string("1e300") : shortest(v);
                             })})
        CHECK_THROWS_WITH_AS(test_particles_command(with(fast), dir, 1, default_max_steps, said),
                             doctest::Contains("belt.toml: the planet jupiter starts at "), sympl::error);
    CHECK_THROWS_WITH_AS(test_particles_command(with([](std::size_t i, double v) {
                                                    return shortest(i >= 3 && i < 6 ? 2 * v : v);
                                                }),
                                                dir, 1, default_max_steps, said),
                         doctest::Contains(" AU/day, at or past the escape speed 0.0"), sympl::error);
    CHECK_FALSE(fs::exists(dir / "test_particles.csv"));
    // The scene's own planets pass (the belt runs in the tests above).
    fs::remove_all(dir);
}

TEST_CASE("test particles belt: planets the run does not keep are an error with the figures, nothing written") {
    // Saturn started 1e-13 AU from Jupiter with Jupiter's velocity: each
    // planet's orbit about the star is bound and outside it (the up-front
    // checks pass), the first kick flings them apart; the particles would be
    // "kept" by a run whose planets' energy changed by all of its scale.
    const runnable_system planets = system_of(parse_scene(belt, "belt.toml"));
    const std::size_t n = planets.x0.size() / 2;
    std::vector<double> q(planets.x0.begin(), planets.x0.begin() + std::ptrdiff_t(n)),
        p(planets.x0.begin() + std::ptrdiff_t(n), planets.x0.end());
    const double speed_ratio = std::hypot(p[6], p[7], p[8]) / std::hypot(p[3], p[4], p[5]);
    for (std::size_t c = 0; c < 3; ++c) {
        q[6 + c] = q[3 + c];
        p[6 + c] = p[3 + c] * speed_ratio;
    }
    q[6] += 1e-13;
    std::string initial = "[initial]\nq = [", momenta = "p = [";
    for (std::size_t i = 0; i < n; ++i) {
        initial += (i ? ", " : "") + shortest(q[i]);
        momenta += (i ? ", " : "") + shortest(p[i]);
    }
    const scene s = parse_scene(replaced(belt, "t_end = 160000", "t_end = 2000") + initial + "]\n" + momenta + "]\n",
                                "close.toml");
    const fs::path dir = scratch_directory("sympl_test_belt_close_planets");
    fs::remove_all(dir);
    std::ostringstream said;
    CHECK_THROWS_WITH_AS(test_particles_command(s, dir, 1, default_max_steps, said),
                         doctest::Contains("the planets' energy changed by "), sympl::error);
    CHECK_THROWS_WITH_AS(test_particles_command(s, dir, 1, default_max_steps, said),
                         doctest::Contains(" within 100 steps of dt = 20 from t = 0; expected below 0.1, a planetary "
                                           "system the method keeps (check the scene's initial state and dt)"),
                         sympl::error);
    CHECK_FALSE(fs::exists(dir / "test_particles.csv"));
    fs::remove_all(dir);
}

TEST_CASE("test particles belt: a checkpoint's folder that does not exist yet is made before any piece runs") {
    const fs::path dir = scratch_directory("sympl_test_belt_new_folder");
    fs::remove_all(dir);
    const std::string file = (dir / "not" / "yet" / "belt").string();
    const scene s = parse_scene(replaced(replaced(belt, "t_end = 160000", "t_end = 2000"), "dt = 20\n",
                                         "dt = 20\ncheckpoint = {every_steps = 1, file = \"" + file + "\"}\n"),
                                "belt.toml");
    const std::vector<sympl::orbital_elements> orbits = test_particle_orbits(s);
    const auto rows = run_test_particles(s, orbits, 1, default_max_steps, exchange{}, false, 16);
    CHECK(rows.size() == orbits.size());
    CHECK(fs::exists(dir / "not" / "yet" / "belt.test-particles-rank-0"));
    // Removing them removes this program's files only: not a user's copy
    // named after one, nor a symlink of a rank file's name (or its target).
    std::ofstream(dir / "not" / "yet" / "belt.test-particles-rank-0.bak") << "a user's copy\n";
    std::ofstream(dir / "target.txt") << "a user's file\n";
    fs::create_symlink(dir / "target.txt", dir / "not" / "yet" / "belt.test-particles-rank-9");
    remove_test_particle_checkpoints(s);
    CHECK_FALSE(fs::exists(dir / "not" / "yet" / "belt.test-particles-rank-0"));
    CHECK(fs::exists(dir / "not" / "yet" / "belt.test-particles-rank-0.bak"));
    CHECK(fs::is_symlink(dir / "not" / "yet" / "belt.test-particles-rank-9"));
    CHECK(fs::exists(dir / "target.txt"));
    fs::remove_all(dir);
}

TEST_CASE("test particles belt: the report refuses a MEGNO map, naming the command that runs it") {
    const scene s = parse_scene(belt, "belt.toml");
    std::ostringstream out;
    CHECK_THROWS_WITH_AS(run_report({s}, {(fs::temp_directory_path() / "sympl_unused_belt_report").string(), true,
                                          false, false},
                                    out),
                         "belt.toml: a scene with [test_particles] is a MEGNO map, not a comparison of methods; "
                         "expected it run by `sympl run`",
                         sympl::error);
}

TEST_CASE("test particles belt: the built-in belt runs by name and is not in the report's set") {
    const std::optional<scene> s = builtin_scene("outer_belt_megno");
    REQUIRE(s);
    REQUIRE(s->test_particles);
    CHECK(s->test_particles->grid_size() >= 100);
    CHECK(load_scene("outer_belt_megno").name == "outer_belt_megno");
    for (const scene& d : default_scenes(true)) CHECK(!d.test_particles);
}

}  // namespace test_program_test_test_particles
