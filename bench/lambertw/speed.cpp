// SPDX-License-Identifier: Apache-2.0
//
// Speed of the real Lambert W branches of hcimpact against Boost.Math and GSL.
//
// For every region of inputs the program builds N inputs deterministically,
// then times throughput loops (y[i] = f(x[i]) over the array) for each
// implementation. One measurement repeats the loop until at least --min-ms
// milliseconds have passed; --repeats rounds of measurements are taken,
// interleaving the implementations of a region (the order is reversed every
// other round). Reported: the median ns/call with the min and max, and the
// ratio to a base row as the median of the per-round ratios.
//
// Timings depend on the machine and its load; they are never asserted.
// Output: Markdown on stdout.
//
// Options: --n N (inputs per region, default 4096), --min-ms MS (default 20),
//          --repeats R (default 11), --quick (N=1024, 5 ms, 3 repeats),
//          --wall (time with the elapsed-time clock instead of the CPU time
//          of the thread, CLOCK_THREAD_CPUTIME_ID), --latency (each input
//          depends on the previous result: latency instead of throughput).

#include <boost/math/special_functions/lambert_w.hpp>
#include <boost/version.hpp>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_lambert.h>
#include <gsl/gsl_version.h>

#include "hcimpact.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace {

// ---------------------------------------------------------------------------
// Deterministic inputs
// ---------------------------------------------------------------------------

// splitmix64: small, fast, and the same sequence on every platform.
struct SplitMix64 {
    std::uint64_t state;
    explicit SplitMix64(std::uint64_t seed) : state(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    // uniform in [0, 1) with 53 random bits
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

// The double nearest to -1/e (it lies 1.2e-17 below -1/e).
constexpr double kMinusInvE = -0x1.78b56362cef38p-2;

std::vector<double> log_uniform(SplitMix64& rng, std::size_t n, double lo, double hi) {
    std::vector<double> v(n);
    const double a = std::log(lo), b = std::log(hi);
    for (auto& x : v) x = std::exp(a + (b - a) * rng.uniform());
    return v;
}

std::vector<double> uniform(SplitMix64& rng, std::size_t n, double lo, double hi) {
    std::vector<double> v(n);
    for (auto& x : v) {
        do {
            x = lo + (hi - lo) * rng.uniform();
        } while (x == hi); // half-open [lo, hi)
    }
    return v;
}

// z = (double nearest -1/e) + d, d log-uniform in [dlo, dhi]; every such z
// lies above -1/e because d >= 1e-16 is more than the 1.2e-17 offset.
std::vector<double> near_branch(SplitMix64& rng, std::size_t n, double dlo, double dhi) {
    std::vector<double> v = log_uniform(rng, n, dlo, dhi);
    for (auto& x : v) x = kMinusInvE + x;
    return v;
}

// ---------------------------------------------------------------------------
// Timing
// ---------------------------------------------------------------------------

volatile double g_sink = 0.0;

// The clock: by default the CPU time of this thread, so that time spent
// descheduled on a loaded machine is not counted (--wall: elapsed time).
bool g_wall_clock = false;

double now_seconds() {
    if (!g_wall_clock) {
        timespec ts;
        if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0)
            return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// --latency: every input is made to depend on the previous result, so the
// calls cannot overlap. The dependency is x | (previous & mask) on the bit
// patterns, with mask = 0 read from a volatile (the compiler cannot drop it);
// it costs a few cycles per call, the same for every implementation.
bool g_latency = false;
volatile std::uint64_t g_zero_mask = 0;

// One timed run: `reps` passes over the array. The empty asm with a memory
// clobber makes the compiler reload the inputs and keep every store on every
// pass, so nothing can be hoisted out of the repetition loop or dropped.
//
// Throughput mode stores y[i] = f(x[i]) and sums y after the clock stops. (An
// earlier version summed f(x[i]) into one accumulator: around a call the
// compiler keeps it in memory, so every call waited for a store-to-load chain
// of ~3.4 ns here, the cost of a call of an empty function in that loop; that
// floor hid the work of any function behind a call and not of inlined ones.
// The row "empty function, out of line" shows what a call costs in this loop.)
template <class F>
double time_loop(const std::vector<double>& x, long reps, F f) {
    const double* p = x.data();
    const std::size_t n = x.size();
    double s = 0.0;
    double t0 = 0.0, t1 = 0.0;
    if (!g_latency) {
        std::vector<double> out(n);
        double* y = out.data();
        t0 = now_seconds();
        for (long r = 0; r < reps; ++r) {
            __asm__ __volatile__("" : : "r"(p), "r"(y) : "memory");
            for (std::size_t i = 0; i < n; ++i) y[i] = f(p[i]);
        }
        __asm__ __volatile__("" : : "r"(y) : "memory");
        t1 = now_seconds();
        for (std::size_t i = 0; i < n; ++i) s += y[i];
    } else {
        const std::uint64_t mask = g_zero_mask;
        double y = 0.0;
        t0 = now_seconds();
        for (long r = 0; r < reps; ++r) {
            __asm__ __volatile__("" : : "r"(p) : "memory");
            for (std::size_t i = 0; i < n; ++i) {
                std::uint64_t xb, yb;
                std::memcpy(&xb, &p[i], sizeof xb);
                std::memcpy(&yb, &y, sizeof yb);
                xb |= yb & mask;
                double xi;
                std::memcpy(&xi, &xb, sizeof xi);
                y = f(xi);
                s += y;
            }
        }
        t1 = now_seconds();
    }
    g_sink = g_sink + s;
    return t1 - t0;
}

// A timed implementation: a type-erased "run reps passes, return seconds".
struct Case {
    std::string function;         // row label
    const std::vector<double>* x; // its inputs
    std::function<double(long)> run;
    std::string base;             // label of the row its ratio refers to ("" = none)
    double goal = 0.0;            // ratio goal (0 = none)
    long reps = 1;
    std::vector<double> ns;       // ns/call of each measurement
};

template <class F>
Case make_case(std::string function, const std::vector<double>& x, F f,
               std::string base = "", double goal = 0.0) {
    Case c;
    c.function = std::move(function);
    c.x = &x;
    c.run = [&x, f](long reps) { return time_loop(x, reps, f); };
    c.base = std::move(base);
    c.goal = goal;
    return c;
}

struct Region {
    std::string name;
    std::string description;
    std::vector<double> x; // inputs of the functions of z (or t for the 1+W forms)
    std::vector<double> z; // t-regions only: z = -exp(-1 - t), rounded to double
    std::vector<Case> cases;
};

struct Options {
    std::size_t n = 4096;
    double min_ms = 20.0;
    int repeats = 11;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return (v.size() % 2) ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

void calibrate(Case& c, double min_s) {
    long reps = 1;
    for (;;) {
        const double s = c.run(reps);
        if (s >= min_s) break;
        // aim 20 % above the target, at least doubling, at most x100 per step
        double factor = (s > 0.0) ? 1.2 * min_s / s : 100.0;
        factor = std::min(100.0, std::max(2.0, factor));
        reps = static_cast<long>(std::ceil(reps * factor));
    }
    c.reps = reps;
}

void measure(Region& r, const Options& o) {
    const double min_s = o.min_ms * 1e-3;
    for (auto& c : r.cases) calibrate(c, min_s);
    for (int k = 0; k < o.repeats; ++k) {
        const std::size_t m = r.cases.size();
        for (std::size_t j = 0; j < m; ++j) {
            Case& c = r.cases[(k % 2) ? m - 1 - j : j];
            const double s = c.run(c.reps);
            c.ns.push_back(s * 1e9 / (static_cast<double>(c.reps) * static_cast<double>(c.x->size())));
        }
    }
}

// ---------------------------------------------------------------------------
// Implementations (thin lambdas; Boost is header-only and may be inlined,
// ours and GSL's are calls into the libraries, as a user gets them)
// ---------------------------------------------------------------------------

const auto ours_w0 = [](double z) { return hcimpact_lambert_w0(z); };
const auto ours_wm1 = [](double z) { return hcimpact_lambert_wm1(z); };
const auto ours_w0p1 = [](double t) { return hcimpact_lambert_w0p1(t); };
const auto ours_wm1p1 = [](double t) { return hcimpact_lambert_wm1p1(t); };
const auto boost_w0 = [](double z) { return boost::math::lambert_w0(z); };
const auto boost_wm1 = [](double z) { return boost::math::lambert_wm1(z); };
// Boost's functions behind a call the compiler may neither inline nor analyse, as
// ours are: these rows (no goal) show how much of Boost's lead near the branch point
// is its being inlined into the timing loop.
#if defined(__GNUC__) && !defined(__clang__)
#define HCIMPACT_BENCH_OUT_OF_LINE __attribute__((noipa))
#elif defined(__GNUC__)
#define HCIMPACT_BENCH_OUT_OF_LINE __attribute__((noinline))
#else
#define HCIMPACT_BENCH_OUT_OF_LINE
#endif
HCIMPACT_BENCH_OUT_OF_LINE double boost_w0_called(double z) { return boost::math::lambert_w0(z); }
HCIMPACT_BENCH_OUT_OF_LINE double boost_wm1_called(double z) { return boost::math::lambert_wm1(z); }
// A call of a function that returns its argument: the cost of the loop and the call
HCIMPACT_BENCH_OUT_OF_LINE double empty_called(double z) {
    __asm__ __volatile__("" : "+x"(z));
    return z;
}
const auto gsl_w0 = [](double z) { return gsl_sf_lambert_W0(z); };
const auto gsl_wm1 = [](double z) { return gsl_sf_lambert_Wm1(z); };
const auto naive_w0p1 = [](double t) { return 1.0 + boost::math::lambert_w0(-std::exp(-1.0 - t)); };
const auto naive_wm1p1 = [](double t) { return 1.0 + boost::math::lambert_wm1(-std::exp(-1.0 - t)); };
const auto unit_log = [](double x) { return std::log(std::fabs(x)); };
const auto unit_exp = [](double x) { return std::exp(x); };

constexpr double kGoalW0 = 0.7, kGoalWm1 = 0.5, kGoalP1 = 1.5;

// Boost throws on domain/overflow errors with the default policy: make sure
// none of the timed inputs can, before timing anything.
bool check_domain(const Region& r) {
    const auto probe = [&r](const std::vector<double>& v, bool w0, bool wm1) {
        for (double z : v) {
            try {
                if (w0) (void)boost::math::lambert_w0(z);
                if (wm1) (void)boost::math::lambert_wm1(z);
            } catch (const std::exception& e) {
                std::fprintf(stderr, "region %s: Boost throws for z = %.17g: %s\n",
                             r.name.c_str(), z, e.what());
                return false;
            }
        }
        return true;
    };
    bool any_w0 = false, any_wm1 = false;
    for (const auto& c : r.cases) {
        if (c.function.find("W0") != std::string::npos) any_w0 = true;
        if (c.function.find("W-1") != std::string::npos) any_wm1 = true;
    }
    if (!r.z.empty()) return probe(r.z, true, true);
    return probe(r.x, any_w0, any_wm1);
}

// A deque: cases point at their region's inputs, so regions must never move.
std::deque<Region> build_regions(const Options& o) {
    std::deque<Region> regions;
    const std::size_t n = o.n;
    std::uint64_t seed = 0x6863696D70616374ULL; // "hcimpact"

    // z-regions: which branches are timed in each
    struct ZSpec {
        const char* name;
        const char* description;
        bool w0, wm1;
        std::function<std::vector<double>(SplitMix64&)> gen;
    };
    const std::vector<ZSpec> zspecs = {
        {"near16_6", "z = -1/e + d, d log-uniform in [1e-16, 1e-6]", true, true,
         [n](SplitMix64& g) { return near_branch(g, n, 1e-16, 1e-6); }},
        {"near6_2", "z = -1/e + d, d log-uniform in [1e-6, 1e-2]", true, true,
         [n](SplitMix64& g) { return near_branch(g, n, 1e-6, 1e-2); }},
        {"neg", "z uniform in [-0.358, 0)", true, true,
         [n](SplitMix64& g) { return uniform(g, n, -0.358, 0.0); }},
        {"smallpos", "z log-uniform in [1e-10, 1]", true, false,
         [n](SplitMix64& g) { return log_uniform(g, n, 1e-10, 1.0); }},
        {"w0pos", "z log-uniform in [1e-300, 1e300]", true, false,
         [n](SplitMix64& g) { return log_uniform(g, n, 1e-300, 1e300); }},
        {"wm1", "z = -s, s log-uniform in [1e-300, 0.1]", false, true,
         [n](SplitMix64& g) {
             auto v = log_uniform(g, n, 1e-300, 0.1);
             for (auto& x : v) x = -x;
             return v;
         }},
    };
    for (const auto& s : zspecs) {
        SplitMix64 rng(seed++);
        regions.push_back(Region{s.name, s.description, s.gen(rng), {}, {}});
        Region& r = regions.back();
        if (s.w0) {
            r.cases.push_back(make_case("ours W0", r.x, ours_w0, "Boost W0", kGoalW0));
            r.cases.push_back(make_case("Boost W0", r.x, boost_w0, "Boost W0"));
            r.cases.push_back(make_case("Boost W0, out of line", r.x, boost_w0_called, "Boost W0"));
            r.cases.push_back(make_case("GSL W0", r.x, gsl_w0, "Boost W0"));
        }
        if (s.wm1) {
            r.cases.push_back(make_case("ours W-1", r.x, ours_wm1, "Boost W-1", kGoalWm1));
            r.cases.push_back(make_case("Boost W-1", r.x, boost_wm1, "Boost W-1"));
            r.cases.push_back(make_case("Boost W-1, out of line", r.x, boost_wm1_called, "Boost W-1"));
            r.cases.push_back(make_case("GSL W-1", r.x, gsl_wm1, "Boost W-1"));
        }
        const std::string unit_base = s.w0 ? "Boost W0" : "Boost W-1";
        r.cases.push_back(make_case("log(fabs(x))", r.x, unit_log, unit_base));
        r.cases.push_back(make_case("exp(x)", r.x, unit_exp, unit_base));
        r.cases.push_back(make_case("empty function, out of line", r.x, empty_called, unit_base));
    }

    // t-regions: the 1+W forms, with Boost on the corresponding z as the base
    struct TSpec {
        const char* name;
        const char* description;
        double lo, hi;
    };
    const std::vector<TSpec> tspecs = {
        {"t16_6", "t log-uniform in [1e-16, 1e-6] (z + 1/e ~ t/e)", 1e-16, 1e-6},
        {"t6_2", "t log-uniform in [1e-6, 1e-2]", 1e-6, 1e-2},
        {"tfar", "t log-uniform in [1e-2, 700] (z down to -1e-304)", 1e-2, 700.0},
    };
    for (const auto& s : tspecs) {
        SplitMix64 rng(seed++);
        regions.push_back(Region{s.name, s.description, log_uniform(rng, n, s.lo, s.hi), {}, {}});
        Region& r = regions.back();
        r.z.resize(r.x.size());
        for (std::size_t i = 0; i < r.x.size(); ++i) r.z[i] = -std::exp(-1.0 - r.x[i]);
        r.cases.push_back(make_case("ours 1+W0(t)", r.x, ours_w0p1, "Boost W0 on z(t)", kGoalP1));
        r.cases.push_back(make_case("ours 1+W-1(t)", r.x, ours_wm1p1, "Boost W0 on z(t)", kGoalP1));
        r.cases.push_back(make_case("Boost W0 on z(t)", r.z, boost_w0, "Boost W0 on z(t)"));
        r.cases.push_back(make_case("Boost W-1 on z(t)", r.z, boost_wm1, "Boost W0 on z(t)"));
        r.cases.push_back(make_case("naive 1+Boost W0(-exp(-1-t))", r.x, naive_w0p1, "Boost W0 on z(t)"));
        r.cases.push_back(make_case("naive 1+Boost W-1(-exp(-1-t))", r.x, naive_wm1p1, "Boost W0 on z(t)"));
        r.cases.push_back(make_case("log(fabs(t))", r.x, unit_log, "Boost W0 on z(t)"));
        r.cases.push_back(make_case("exp(t)", r.x, unit_exp, "Boost W0 on z(t)"));
        r.cases.push_back(make_case("empty function, out of line", r.x, empty_called, "Boost W0 on z(t)"));
    }
    return regions;
}

std::string cpu_model() {
    std::ifstream f("/proc/cpuinfo");
    std::string line;
    while (std::getline(f, line)) {
        if (line.rfind("model name", 0) == 0) {
            const auto p = line.find(':');
            if (p != std::string::npos) return line.substr(p + 2);
        }
    }
    return "unknown CPU";
}

void usage(const char* argv0) {
    std::fprintf(stderr, "usage: %s [--n N] [--min-ms MS] [--repeats R] [--quick] [--wall] [--latency]\n", argv0);
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool has_value = i + 1 < argc;
        if (a == "--n" && has_value) {
            o.n = static_cast<std::size_t>(std::strtoul(argv[++i], nullptr, 10));
        } else if (a == "--min-ms" && has_value) {
            o.min_ms = std::strtod(argv[++i], nullptr);
        } else if (a == "--repeats" && has_value) {
            o.repeats = std::atoi(argv[++i]);
        } else if (a == "--latency") {
            g_latency = true;
        } else if (a == "--wall") {
            g_wall_clock = true;
        } else if (a == "--quick") {
            o.n = 1024;
            o.min_ms = 5.0;
            o.repeats = 3;
        } else {
            usage(argv[0]);
            return 2;
        }
    }
    if (o.n == 0 || o.repeats < 1 || !(o.min_ms > 0.0)) {
        usage(argv[0]);
        return 2;
    }
    gsl_set_error_handler_off(); // GSL must report, never abort

    std::deque<Region> regions = build_regions(o);
    for (const auto& r : regions) {
        if (!check_domain(r)) return 1;
    }

    std::printf("### Speed, %s (median ns/call over %d measurements)\n\n",
                g_latency ? "latency" : "throughput", o.repeats);
    std::printf("CPU: %s; compiler: GCC %s; Boost %d.%d.%d; GSL %s.\n", cpu_model().c_str(),
                __VERSION__, BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, BOOST_VERSION % 100,
                GSL_VERSION);
    std::printf("N = %zu inputs per region (pseudo-random order), each measurement >= %g ms of %s, "
                "%d measurements interleaved across implementations.\n\n",
                o.n, o.min_ms, g_wall_clock ? "elapsed time" : "thread CPU time", o.repeats);
    if (g_latency)
        std::printf("Latency mode: each input depends on the previous result (a few cycles of "
                    "integer operations per call, the same for every row), so calls cannot overlap.\n\n");
    else
        std::printf("Throughput mode: y[i] = f(x[i]) over the array; the calls are independent and may "
                    "overlap in the processor.\n\n");
    std::printf("Ratio: median over the measurements of the time over the time of the row named in "
                "\"vs\" in the same round. "
                "Goals: ours W0 <= %.1fx Boost W0; ours W-1 <= %.1fx Boost W-1; "
                "each 1+W form <= %.1fx Boost W0 on the corresponding z = -exp(-1-t).\n\n",
                kGoalW0, kGoalWm1, kGoalP1);

    std::vector<std::string> summary;
    for (auto& r : regions) {
        std::fprintf(stderr, "timing region %s ...\n", r.name.c_str());
        measure(r, o);
    }

    std::printf("| region | inputs | function | ns/call | min | max | ratio | vs | goal |\n");
    std::printf("|---|---|---|---:|---:|---:|---:|---|---|\n");
    for (const auto& r : regions) {
        bool first = true;
        for (const auto& c : r.cases) {
            const double med = median(c.ns);
            const double lo = *std::min_element(c.ns.begin(), c.ns.end());
            const double hi = *std::max_element(c.ns.begin(), c.ns.end());
            // The ratio is the median of the per-round ratios: both rows of a round
            // were measured close together, so a slow phase of the machine (another
            // job, a clock change) moves both and cancels out.
            double ratio = 0.0;
            for (const auto& b : r.cases) {
                if (b.function != c.base || b.ns.size() != c.ns.size()) continue;
                std::vector<double> q(c.ns.size());
                for (std::size_t k = 0; k < q.size(); ++k) q[k] = c.ns[k] / b.ns[k];
                ratio = median(q);
            }
            std::string goal = "";
            if (c.goal > 0.0) {
                char buf[64];
                std::snprintf(buf, sizeof buf, "<= %.1f: %s", c.goal,
                              ratio <= c.goal ? "**pass**" : "**FAIL**");
                goal = buf;
                char line[256];
                std::snprintf(line, sizeof line, "| %s | %s | %.3f | <= %.1f | %s |", r.name.c_str(),
                              c.function.c_str(), ratio, c.goal, ratio <= c.goal ? "pass" : "FAIL");
                summary.push_back(line);
            }
            std::printf("| %s | %s | %s | %.1f | %.1f | %.1f | %.3f | %s | %s |\n",
                        first ? r.name.c_str() : "", first ? r.description.c_str() : "",
                        c.function.c_str(), med, lo, hi, ratio, c.base.c_str(), goal.c_str());
            first = false;
        }
    }
    std::printf("\n### Goals (%s)\n\n| region | function | ratio | goal | result |\n|---|---|---:|---|---|\n",
                g_latency ? "latency" : "throughput");
    for (const auto& s : summary) std::printf("%s\n", s.c_str());
    std::printf("\n");
    return 0;
}
