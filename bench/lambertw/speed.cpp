// SPDX-License-Identifier: Apache-2.0
//
// Speed of the real Lambert W branches of hcimpact against Boost.Math and GSL,
// measured the way a user meets them (issue 17's protocol):
//
// * ours through the C API of the shared library, called from C++ as a user
//   program calls it (through its PLT); two more columns: the same code as a
//   static library (a copy of the library's objects with renamed symbols,
//   linked into this program) and a Fortran caller (bench/lambertw/
//   fortran_caller.f90, the module procedures through the shared library);
// * Boost as the header it is (inlined into the loop), GSL through its shared
//   library;
// * per region N = 65536 random inputs, put in a fresh random order before
//   every pass (the shuffle is not timed), so that the branch predictor cannot
//   learn the sequence; each pass is timed on its own with the CPU time of the
//   thread (CLOCK_THREAD_CPUTIME_ID);
// * regions that cross the boundaries between the internal paths;
// * throughput (y[i] = f(x[i])) and, with --latency, latency (each input made
//   to depend on the previous result); with --cache-pressure MB, every call is
//   accompanied by the read of one new 64-byte line of an MB-megabyte buffer,
//   which keeps evicting the tables from the caches;
// * rounds: in each round every implementation of a region is measured once
//   (order reversed every other round); the ratio of two rows is the median
//   of their per-round ratios, shown with its smallest and largest value.
//
// Timings depend on the machine and its load; they are never asserted.
// Output: Markdown on stdout. Options: see usage() below.

#include <boost/math/special_functions/lambert_w.hpp>
#include <boost/version.hpp>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_lambert.h>
#include <gsl/gsl_version.h>

#include "hcimpact.h"

#include <dlfcn.h>
#include <unistd.h>

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
#include <map>
#include <string>
#include <vector>

// The static copy of the library (bench/CMakeLists.txt renames its symbols with
// this prefix so that it can live next to the shared library in one program).
#ifdef HCIMPACT_BENCH_STATIC_COPY
extern "C" {
double hcbench_static_hcimpact_lambert_w0(double);
double hcbench_static_hcimpact_lambert_wm1(double);
double hcbench_static_hcimpact_lambert_w0p1(double);
double hcbench_static_hcimpact_lambert_wm1p1(double);
}
#endif

// The Fortran callers (fortran_caller.f90): one pass over x, as in pass_loop below.
extern "C" {
double hcimpact_bench_fortran_w0(std::int64_t n, const double* x, double* y, std::int64_t ring_mask,
                                 std::int32_t latency, std::int64_t chain_mask);
double hcimpact_bench_fortran_wm1(std::int64_t n, const double* x, double* y, std::int64_t ring_mask,
                                  std::int32_t latency, std::int64_t chain_mask);
double hcimpact_bench_fortran_w0p1(std::int64_t n, const double* x, double* y, std::int64_t ring_mask,
                                   std::int32_t latency, std::int64_t chain_mask);
double hcimpact_bench_fortran_wm1p1(std::int64_t n, const double* x, double* y, std::int64_t ring_mask,
                                    std::int32_t latency, std::int64_t chain_mask);
}

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
    // uniform in [0, n) (n small against 2^64: the bias is negligible here)
    std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

// The double nearest to -1/e (it lies 1.2e-17 below -1/e).
constexpr double kMinusInvE = -0x1.78b56362cef38p-2;

std::vector<double> log_uniform(SplitMix64& rng, std::size_t n, double lo, double hi) {
    std::vector<double> v(n);
    const double a = std::log(lo), b = std::log(hi);
    for (auto& x : v) x = std::min(hi, std::max(lo, std::exp(a + (b - a) * rng.uniform())));
    return v;
}

// uniform in the open interval (lo, hi)
std::vector<double> uniform_open(SplitMix64& rng, std::size_t n, double lo, double hi) {
    std::vector<double> v(n);
    for (auto& x : v) {
        do {
            x = lo + (hi - lo) * rng.uniform();
        } while (!(x > lo && x < hi));
    }
    return v;
}

// z = (double nearest -1/e) + d, d log-uniform in [dlo, dhi]; every such z
// lies above -1/e because d >= 1e-15 is more than the 1.2e-17 offset.
std::vector<double> near_branch(SplitMix64& rng, std::size_t n, double dlo, double dhi) {
    std::vector<double> v = log_uniform(rng, n, dlo, dhi);
    for (auto& x : v) x = kMinusInvE + x;
    return v;
}

void shuffle(std::vector<double>& v, SplitMix64& rng) {
    for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng.below(i)]);
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

// Throughput passes store y[i mod 4096] = f(x[i]): a store per call, as a user
// filling an array has, without a result array as large as the inputs.
constexpr std::size_t kRing = 4096;

// --cache-pressure MB: one new 64-byte line of this buffer is read per call
std::vector<double> g_pressure;

// One pass over n inputs. (An earlier version summed f(x[i]) into one
// accumulator: around a call the compiler keeps it in memory, and every call
// then waited for a store-to-load round trip, ~3.4 ns here, which hid the work
// of any function behind a call and of no inlined one.)
template <class F>
double pass_loop(const double* x, std::size_t n, double* y, F f) {
    __asm__ __volatile__("" : : "r"(x), "r"(y) : "memory");
    double s = 0.0;
    if (!g_latency) {
        if (g_pressure.empty()) {
            for (std::size_t i = 0; i < n; ++i) y[i & (kRing - 1)] = f(x[i]);
        } else {
            const double* q = g_pressure.data();
            const std::size_t qmask = g_pressure.size() - 1;
            std::size_t j = 0;
            double acc = 0.0;
            for (std::size_t i = 0; i < n; ++i) {
                y[i & (kRing - 1)] = f(x[i]);
                acc += q[j];
                j = (j + 8) & qmask;
            }
            s = acc;
        }
    } else {
        const std::uint64_t mask = g_zero_mask;
        double v = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            std::uint64_t xb, vb;
            std::memcpy(&xb, &x[i], sizeof xb);
            std::memcpy(&vb, &v, sizeof vb);
            xb |= vb & mask;
            double xi;
            std::memcpy(&xi, &xb, sizeof xi);
            v = f(xi);
            s += v;
        }
    }
    __asm__ __volatile__("" : : "r"(y) : "memory");
    return s;
}

using PassFn = std::function<double(const double*, std::size_t, double*)>;

template <class F>
PassFn make_pass(F f) {
    return [f](const double* x, std::size_t n, double* y) { return pass_loop(x, n, y, f); };
}

using FortranPass = double (*)(std::int64_t, const double*, double*, std::int64_t, std::int32_t,
                               std::int64_t);

PassFn make_fortran_pass(FortranPass p) {
    return [p](const double* x, std::size_t n, double* y) {
        return p(static_cast<std::int64_t>(n), x, y, static_cast<std::int64_t>(kRing - 1),
                 g_latency ? 1 : 0, static_cast<std::int64_t>(g_zero_mask));
    };
}

// One timed implementation on one region.
struct Case {
    std::string row;   // "W0", "W-1", "1+W0", "1+W-1", or "" (floor rows)
    std::string impl;  // "ours", "static", "fortran", "boost", "gsl", "empty", "log"
    std::vector<double>* x = nullptr; // its inputs (shuffled in place before every pass)
    PassFn pass;
    long passes = 1;
    std::vector<double> ns; // ns/call of each round
};

struct Region {
    std::string name;
    std::string inputs;   // what the inputs are
    std::string crosses;  // which internal paths of ours the region spans
    bool t_region = false;
    std::vector<double> x; // z, or t for the 1+W forms
    std::vector<double> z; // t-regions: z = -exp(-1 - t) rounded, the peers' input
    std::vector<Case> cases;
};

struct Options {
    std::size_t n = 65536;
    double min_ms = 20.0;
    int repeats = 11;
    bool fixed_order = false;
    double pressure_mb = 0.0;
    std::vector<std::string> only; // region names to run (empty: all)
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return (v.size() % 2) ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// `passes` passes, each over the inputs in a fresh random order (unless
// --fixed-order); returns the seconds of the passes alone.
double run_case(Case& c, long passes, bool fixed_order, SplitMix64& order_rng, std::vector<double>& y) {
    double seconds = 0.0, s = 0.0;
    for (long p = 0; p < passes; ++p) {
        if (!fixed_order) shuffle(*c.x, order_rng);
        const double t0 = now_seconds();
        s += c.pass(c.x->data(), c.x->size(), y.data());
        const double t1 = now_seconds();
        seconds += t1 - t0;
    }
    for (double v : y) s += v;
    g_sink = g_sink + s;
    return seconds;
}

void measure(Region& r, const Options& o) {
    const double min_s = o.min_ms * 1e-3;
    std::vector<double> y(kRing, 0.0);
    SplitMix64 order_rng(0x6f72646572ULL ^ std::hash<std::string>{}(r.name));
    for (auto& c : r.cases) {
        run_case(c, 1, o.fixed_order, order_rng, y); // warm-up
        const double one = std::max(run_case(c, 1, o.fixed_order, order_rng, y), 1e-7);
        c.passes = std::max(1L, static_cast<long>(std::ceil(1.1 * min_s / one)));
    }
    const std::size_t m = r.cases.size();
    for (int k = 0; k < o.repeats; ++k) {
        for (std::size_t j = 0; j < m; ++j) {
            Case& c = r.cases[(k % 2) ? m - 1 - j : j];
            const double s = run_case(c, c.passes, o.fixed_order, order_rng, y);
            c.ns.push_back(s * 1e9 / (static_cast<double>(c.passes) * static_cast<double>(c.x->size())));
        }
    }
}

// ---------------------------------------------------------------------------
// Implementations (Boost is header-only and inlined; ours and GSL's are calls
// into shared libraries, as a user gets them)
// ---------------------------------------------------------------------------

const auto ours_w0 = [](double z) { return hcimpact_lambert_w0(z); };
const auto ours_wm1 = [](double z) { return hcimpact_lambert_wm1(z); };
const auto ours_w0p1 = [](double t) { return hcimpact_lambert_w0p1(t); };
const auto ours_wm1p1 = [](double t) { return hcimpact_lambert_wm1p1(t); };
#ifdef HCIMPACT_BENCH_STATIC_COPY
const auto static_w0 = [](double z) { return hcbench_static_hcimpact_lambert_w0(z); };
const auto static_wm1 = [](double z) { return hcbench_static_hcimpact_lambert_wm1(z); };
const auto static_w0p1 = [](double t) { return hcbench_static_hcimpact_lambert_w0p1(t); };
const auto static_wm1p1 = [](double t) { return hcbench_static_hcimpact_lambert_wm1p1(t); };
#endif
const auto boost_w0 = [](double z) { return boost::math::lambert_w0(z); };
const auto boost_wm1 = [](double z) { return boost::math::lambert_wm1(z); };
const auto gsl_w0 = [](double z) { return gsl_sf_lambert_W0(z); };
const auto gsl_wm1 = [](double z) { return gsl_sf_lambert_Wm1(z); };
const auto unit_log = [](double x) { return std::log(std::fabs(x)); };

// A call of a function that returns its argument: the cost of the loop and the call
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((noipa))
#elif defined(__GNUC__)
__attribute__((noinline))
#endif
double empty_called(double z) {
    __asm__ __volatile__("" : "+x"(z));
    return z;
}

// Goals of issue 17 (throughput, every region, against Boost as the header it is)
constexpr double kGoalW0 = 0.6, kGoalWm1 = 0.5, kGoalP1 = 0.7;

double goal_of(const std::string& row) {
    if (row == "W0") return kGoalW0;
    if (row == "W-1") return kGoalWm1;
    return kGoalP1;
}

// Boost throws on domain/overflow errors with the default policy: make sure
// none of the timed inputs can, before timing anything.
bool check_domain(const Region& r, bool w0, bool wm1) {
    const std::vector<double>& v = r.t_region ? r.z : r.x;
    for (double z : v) {
        try {
            if (w0) (void)boost::math::lambert_w0(z);
            if (wm1) (void)boost::math::lambert_wm1(z);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "region %s: Boost throws for z = %.17g: %s\n", r.name.c_str(), z, e.what());
            return false;
        }
    }
    return true;
}

void add_case(Region& r, const std::string& row, const std::string& impl, std::vector<double>* x, PassFn p) {
    Case c;
    c.row = row;
    c.impl = impl;
    c.x = x;
    c.pass = std::move(p);
    r.cases.push_back(std::move(c));
}

bool wanted(const Options& o, const std::string& name) {
    return o.only.empty() || std::find(o.only.begin(), o.only.end(), name) != o.only.end();
}

// A deque: cases point at their region's inputs, so regions must never move.
bool build_regions(const Options& o, std::deque<Region>& regions) {
    const std::size_t n = o.n;
    std::uint64_t seed = 0x6863696D70616374ULL; // "hcimpact"

    struct ZSpec {
        const char* name;
        const char* inputs;
        const char* crosses;
        bool w0, wm1;
        std::function<std::vector<double>(SplitMix64&)> gen;
    };
    const std::vector<ZSpec> zspecs = {
        {"near", "z = -1/e + d, d log-uniform in [1e-15, 1e-2]",
         "tables wa/wb by z + 1/e_hi over its binades 2^-50 to 2^-7 (before issue 17: the branch-point series, p^6 and p^8 forms, and wa/wb)", true, true,
         [n](SplitMix64& g) { return near_branch(g, n, 1e-15, 1e-2); }},
        {"neg", "z uniform in (-1/e, 0)",
         "W0: wa (z <= -1/4), wc and its Taylor row (|z| < 2^-9); W-1: wb, we (yb with probability 3e-6)", true, true,
         [n](SplitMix64& g) { return uniform_open(g, n, kMinusInvE, 0.0); }},
        {"pos", "z log-uniform in [1e-10, e]", "the table wd and its Taylor row (z < 2^-9)", true, false,
         [n](SplitMix64& g) { return log_uniform(g, n, 1e-10, std::exp(1.0)); }},
        {"large", "z log-uniform in [e, 1e300]", "the table wd and the table ya by ln z (at 2^10)", true, false,
         [n](SplitMix64& g) { return log_uniform(g, n, std::exp(1.0), 1e300); }},
        {"wm1tail", "z = -s, s log-uniform in [1e-300, 0.3]",
         "the table yb by -ln(-z), we (from 2^-20) and wb (from 1/4)", false, true,
         [n](SplitMix64& g) {
             auto v = log_uniform(g, n, 1e-300, 0.3);
             for (auto& x : v) x = -x;
             return v;
         }},
    };
    for (const auto& s : zspecs) {
        SplitMix64 rng(seed++);
        if (!wanted(o, s.name)) continue;
        regions.push_back(Region{s.name, s.inputs, s.crosses, false, s.gen(rng), {}, {}});
        Region& r = regions.back();
        if (!check_domain(r, s.w0, s.wm1)) return false;
        auto add = [&r](const std::string& row, const std::string& impl, PassFn p) {
            add_case(r, row, impl, &r.x, std::move(p));
        };
        if (s.w0) {
            add("W0", "ours", make_pass(ours_w0));
#ifdef HCIMPACT_BENCH_STATIC_COPY
            add("W0", "static", make_pass(static_w0));
#endif
            if (g_pressure.empty()) add("W0", "fortran", make_fortran_pass(hcimpact_bench_fortran_w0));
            add("W0", "boost", make_pass(boost_w0));
            add("W0", "gsl", make_pass(gsl_w0));
        }
        if (s.wm1) {
            add("W-1", "ours", make_pass(ours_wm1));
#ifdef HCIMPACT_BENCH_STATIC_COPY
            add("W-1", "static", make_pass(static_wm1));
#endif
            if (g_pressure.empty()) add("W-1", "fortran", make_fortran_pass(hcimpact_bench_fortran_wm1));
            add("W-1", "boost", make_pass(boost_wm1));
            add("W-1", "gsl", make_pass(gsl_wm1));
        }
        add("", "empty", make_pass(empty_called));
        add("", "log", make_pass(unit_log));
    }

    // t-regions: the 1+W forms, with Boost and GSL W0 on the corresponding z as the base
    struct TSpec {
        const char* name;
        const char* inputs;
        const char* crosses;
        double lo, hi;
    };
    const std::vector<TSpec> tspecs = {
        {"tnear", "t log-uniform in [1e-15, 1e-2] (z + 1/e ~ t/e)",
         "tables ta/tb by t over its binades 2^-50 to 2^-7 (before issue 17: the series in s = sqrt(2t) below 2^-13, ta/tb above)", 1e-15, 1e-2},
        {"tfar", "t log-uniform in [1e-2, 700] (z down to -1e-304)",
         "1+W0: the table ta and its top row 1 (t >= 64); 1+W-1: the table tb", 1e-2, 700.0},
    };
    for (const auto& s : tspecs) {
        SplitMix64 rng(seed++);
        if (!wanted(o, s.name)) continue;
        regions.push_back(Region{s.name, s.inputs, s.crosses, true, log_uniform(rng, n, s.lo, s.hi), {}, {}});
        Region& r = regions.back();
        r.z.resize(r.x.size());
        for (std::size_t i = 0; i < r.x.size(); ++i) r.z[i] = -std::exp(-1.0 - r.x[i]);
        if (!check_domain(r, true, false)) return false;
        auto add = [&r](const std::string& row, const std::string& impl, std::vector<double>* x, PassFn p) {
            add_case(r, row, impl, x, std::move(p));
        };
        add("1+W0", "ours", &r.x, make_pass(ours_w0p1));
        add("1+W-1", "ours", &r.x, make_pass(ours_wm1p1));
#ifdef HCIMPACT_BENCH_STATIC_COPY
        add("1+W0", "static", &r.x, make_pass(static_w0p1));
        add("1+W-1", "static", &r.x, make_pass(static_wm1p1));
#endif
        if (g_pressure.empty()) {
            add("1+W0", "fortran", &r.x, make_fortran_pass(hcimpact_bench_fortran_w0p1));
            add("1+W-1", "fortran", &r.x, make_fortran_pass(hcimpact_bench_fortran_wm1p1));
        }
        // the base of both 1+W rows: W0 on z(t)
        add("z(t)", "boost", &r.z, make_pass(boost_w0));
        add("z(t)", "gsl", &r.z, make_pass(gsl_w0));
        add("", "empty", &r.x, make_pass(empty_called));
        add("", "log", &r.x, make_pass(unit_log));
    }
    return true;
}

// ---------------------------------------------------------------------------
// Report
// ---------------------------------------------------------------------------

const Case* find_case(const Region& r, const std::string& row, const std::string& impl) {
    for (const auto& c : r.cases)
        if (c.row == row && c.impl == impl) return &c;
    return nullptr;
}

struct RatioStats {
    double median = 0.0, lo = 0.0, hi = 0.0;
    bool ok = false;
};

RatioStats ratio(const Case* a, const Case* b) {
    RatioStats s;
    if (!a || !b || a->ns.size() != b->ns.size() || a->ns.empty()) return s;
    std::vector<double> q(a->ns.size());
    for (std::size_t k = 0; k < q.size(); ++k) q[k] = a->ns[k] / b->ns[k];
    s.median = median(q);
    s.lo = *std::min_element(q.begin(), q.end());
    s.hi = *std::max_element(q.begin(), q.end());
    s.ok = true;
    return s;
}

std::string ns_text(const Case* c) {
    if (!c) return "–";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", median(c->ns));
    return buf;
}

std::string ratio_text(const RatioStats& s, bool range) {
    if (!s.ok) return "–";
    char buf[64];
    if (range)
        std::snprintf(buf, sizeof buf, "%.2f (%.2f–%.2f)", s.median, s.lo, s.hi);
    else
        std::snprintf(buf, sizeof buf, "%.2f", s.median);
    return buf;
}

std::string cpu_description() {
    std::ifstream f("/proc/cpuinfo");
    std::string line, model = "unknown CPU", family, number, flags;
    while (std::getline(f, line)) {
        const auto p = line.find(':');
        if (p == std::string::npos) continue;
        const std::string key = line.substr(0, line.find_last_not_of(" \t", p - 1) + 1);
        const std::string value = (p + 2 <= line.size()) ? line.substr(p + 2) : "";
        if (key == "model name" && model == "unknown CPU") model = value;
        if (key == "cpu family" && family.empty()) family = value;
        if (key == "model" && number.empty()) number = value;
        if (key == "flags" && flags.empty()) flags = value;
    }
    std::string s = model;
    if (!family.empty()) s += " (family " + family + ", model " + number + ")";
    s += ", " + std::to_string(sysconf(_SC_NPROCESSORS_ONLN)) + " logical CPUs";
    if ((" " + flags + " ").find(" hypervisor ") != std::string::npos) s += ", virtual machine";
    const long l2 = sysconf(_SC_LEVEL2_CACHE_SIZE);
    if (l2 > 0) s += ", L2 " + std::to_string(l2 / 1024) + " KiB per core";
    return s;
}

// Which file provides hcimpact_lambert_w0 to this program: the shared library
// (the protocol's main column) or the program itself (a static build).
std::string provider_of_ours() {
    Dl_info info;
    std::memset(&info, 0, sizeof info);
    if (dladdr(reinterpret_cast<void*>(&hcimpact_lambert_w0), &info) == 0 || !info.dli_fname)
        return "unknown";
    std::string f = info.dli_fname;
    const auto slash = f.rfind('/');
    if (slash != std::string::npos) f = f.substr(slash + 1);
    if (f.find(".so") != std::string::npos) return "the shared library " + f;
    return "linked statically into " + f + " (configure with -DBUILD_SHARED_LIBS=ON for the protocol's main column)";
}

void usage(const char* argv0) {
    std::fprintf(stderr,
                 "usage: %s [--n N] [--min-ms MS] [--repeats R] [--quick] [--wall] [--latency]\n"
                 "          [--fixed-order] [--cache-pressure MB] [--regions a,b,...]\n"
                 "  --n N              inputs per region (default 65536)\n"
                 "  --min-ms MS        CPU time of one measurement (default 20)\n"
                 "  --repeats R        rounds (default 11)\n"
                 "  --quick            N = 4096, 5 ms, 3 rounds (smoke test)\n"
                 "  --wall             elapsed time instead of the thread's CPU time\n"
                 "  --latency          each input depends on the previous result\n"
                 "  --fixed-order      the same order every pass (the old, flattering protocol)\n"
                 "  --cache-pressure MB  read one new cache line of an MB-megabyte buffer per call\n"
                 "  --regions LIST     only these regions (near, neg, pos, large, wm1tail, tnear, tfar)\n",
                 argv0);
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
        } else if (a == "--cache-pressure" && has_value) {
            o.pressure_mb = std::strtod(argv[++i], nullptr);
        } else if (a == "--regions" && has_value) {
            std::string list = argv[++i];
            std::size_t start = 0;
            while (start <= list.size()) {
                const std::size_t comma = list.find(',', start);
                const std::string name = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
                if (!name.empty()) o.only.push_back(name);
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
        } else if (a == "--latency") {
            g_latency = true;
        } else if (a == "--wall") {
            g_wall_clock = true;
        } else if (a == "--fixed-order") {
            o.fixed_order = true;
        } else if (a == "--quick") {
            o.n = 4096;
            o.min_ms = 5.0;
            o.repeats = 3;
        } else {
            usage(argv[0]);
            return 2;
        }
    }
    if (o.n < 2 || o.repeats < 1 || !(o.min_ms > 0.0) || !(o.pressure_mb >= 0.0)) {
        usage(argv[0]);
        return 2;
    }
    if (o.pressure_mb > 0.0) {
        if (g_latency) {
            std::fprintf(stderr, "--cache-pressure is a throughput variant; drop --latency\n");
            return 2;
        }
        // a power of two of doubles, at least the requested size
        std::size_t count = 8;
        while (static_cast<double>(count) * sizeof(double) < o.pressure_mb * 1048576.0) count *= 2;
        g_pressure.assign(count, 1.0);
    }
    gsl_set_error_handler_off(); // GSL must report, never abort

    std::deque<Region> regions;
    if (!build_regions(o, regions)) return 1;
    if (regions.empty()) {
        std::fprintf(stderr, "no region selected\n");
        return 2;
    }

    const char* mode = g_latency ? "latency" : (g_pressure.empty() ? "throughput" : "throughput under cache pressure");
    std::printf("### Speed, %s\n\n", mode);
    std::printf("Machine: %s. Compiler: GCC %s; Boost %d.%d.%d; GSL %s.\n", cpu_description().c_str(), __VERSION__,
                BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, BOOST_VERSION % 100, GSL_VERSION);
    std::printf("Ours: %s.\n\n", provider_of_ours().c_str());
    std::printf("N = %zu random inputs per region, %s; each pass timed alone (%s), "
                "a measurement >= %g ms of passes; %d rounds, every implementation of a region once per round.\n\n",
                o.n,
                o.fixed_order ? "the same order every pass (--fixed-order: NOT the protocol)"
                              : "in a fresh random order before every pass (the shuffle is not timed)",
                g_wall_clock ? "elapsed time" : "CPU time of the thread", o.min_ms, o.repeats);
    if (g_latency)
        std::printf("Latency: each input depends on the previous result (a few cycles of integer operations per "
                    "call, the same for every implementation), so calls cannot overlap.\n\n");
    else
        std::printf("Throughput: y[i mod 4096] = f(x[i]) over the inputs; the calls are independent and may "
                    "overlap in the processor.%s\n\n",
                    g_pressure.empty()
                        ? ""
                        : (" Cache pressure: every call also reads the next 64-byte line of a " +
                           std::to_string(g_pressure.size() * sizeof(double) / 1048576) +
                           " MiB buffer (the Fortran column is left out).").c_str());
    std::printf("Columns: ns/call (median of the rounds) of ours through the C API of the shared library "
                "(\"ours\"), of the same code linked statically (\"static\"), of a Fortran caller of the "
                "module procedures (\"Fortran\"), of Boost (header, inlined) and GSL; then ratios, each the "
                "median of the per-round ratios (for ours/Boost with the smallest and largest of them). "
                "The 1+W forms take t; their base is W0 of Boost or GSL on z = -exp(-1-t) rounded to "
                "double. Goals (issue 17): ours W0 <= %.1fx Boost W0, ours W-1 <= %.1fx Boost W-1, each "
                "1+W form <= %.1fx Boost W0 on z(t).\n\n",
                kGoalW0, kGoalWm1, kGoalP1);

    for (auto& r : regions) {
        std::fprintf(stderr, "timing region %s ...\n", r.name.c_str());
        measure(r, o);
    }

    std::printf("| region | inputs | internal paths crossed |\n|---|---|---|\n");
    for (const auto& r : regions)
        std::printf("| %s | %s | %s |\n", r.name.c_str(), r.inputs.c_str(), r.crosses.c_str());
    std::printf("\n");

    std::printf("| region | function | ours | static | Fortran | Boost | GSL | ours/Boost (range) | ours/GSL | "
                "static/Boost | Fortran/Boost | goal |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    std::vector<std::string> summary;
    for (const auto& r : regions) {
        const std::vector<std::string> rows =
            r.t_region ? std::vector<std::string>{"1+W0", "1+W-1"} : std::vector<std::string>{"W0", "W-1"};
        for (const auto& row : rows) {
            const Case* ours = find_case(r, row, "ours");
            if (!ours) continue;
            const std::string base_row = r.t_region ? "z(t)" : row;
            const Case* st = find_case(r, row, "static");
            const Case* ft = find_case(r, row, "fortran");
            const Case* bo = find_case(r, base_row, "boost");
            const Case* gs = find_case(r, base_row, "gsl");
            const RatioStats vs_boost = ratio(ours, bo);
            const double goal = goal_of(row);
            char goal_text[64];
            std::snprintf(goal_text, sizeof goal_text, "<= %.1f: %s", goal,
                          vs_boost.ok && vs_boost.median <= goal ? "**met**" : "**missed**");
            std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.name.c_str(),
                        row.c_str(), ns_text(ours).c_str(), ns_text(st).c_str(), ns_text(ft).c_str(),
                        ns_text(bo).c_str(), ns_text(gs).c_str(), ratio_text(vs_boost, true).c_str(),
                        ratio_text(ratio(ours, gs), false).c_str(), ratio_text(ratio(st, bo), false).c_str(),
                        ratio_text(ratio(ft, bo), false).c_str(), goal_text);
            char line[256];
            std::snprintf(line, sizeof line, "| %s | %s | %s | <= %.1f | %s |", r.name.c_str(), row.c_str(),
                          ratio_text(vs_boost, true).c_str(), goal,
                          vs_boost.ok && vs_boost.median <= goal ? "met" : "missed");
            summary.push_back(line);
        }
    }
    std::printf("\nFloor, ns/call: a call of an empty function (the loop and the call), and log(|x|) of the "
                "C library on the same inputs, as a unit of cost.\n\n| region | empty call | log |\n|---|---:|---:|\n");
    for (const auto& r : regions)
        std::printf("| %s | %s | %s |\n", r.name.c_str(), ns_text(find_case(r, "", "empty")).c_str(),
                    ns_text(find_case(r, "", "log")).c_str());
    std::printf("\n#### Goals (%s): ours through the shared library against Boost%s\n\n"
                "| region | function | ratio (range over rounds) | goal | result |\n|---|---|---:|---|---|\n",
                mode, (g_latency || !g_pressure.empty()) ? " (the goals are set for plain throughput; "
                                                            "shown here for comparison)" : "");
    for (const auto& s : summary) std::printf("%s\n", s.c_str());
    std::printf("\n");
    return 0;
}
