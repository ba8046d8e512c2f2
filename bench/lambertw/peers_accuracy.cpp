// SPDX-License-Identifier: Apache-2.0
//
// Accuracy of hcimpact's Lambert W against Boost.Math and GSL, on the
// mpmath reference of test/reference/lambertw.csv.
//
// Usage: bench_lambertw_peers [path/to/lambertw.csv]   (Markdown on stdout)
//
// CSV rows: region,func,x,ref_hi,ref_lo ('#' lines and a "region,..." header
// are skipped); func is w0, wm1, w0p1 or wm1p1; the reference is
// ref_hi + ref_lo at the exact double x (for w0p1/wm1p1, x is t).
//
// Error in ulps: |(y - ref_hi) - ref_lo| / ulp(ref), where ulp(ref) is the
// spacing of the doubles at the exact reference value ref = ref_hi + ref_lo:
//   nextafter(|ref_hi|, inf) - |ref_hi|, halved when |ref_hi| is a normal
//   power of two and |ref| < |ref_hi| (ref_lo of the opposite sign), because
//   the exact value then lies in the binade below; for ref = 0 the ulp is the
//   smallest subnormal 2^-1074; near DBL_MAX the spacing below is used.
// A result counts as "fail" when Boost throws, or when the result is NaN or
// infinite while the reference is finite; such points are left out of the
// max/median. Where the reference is NaN (argument outside the domain), a
// NaN or an exception is the right answer and counts as 0 ulp; a finite
// result there is a fail. Infinite references need an equal result.
//
// The 1+W forms: ours are called with t; the peers are evaluated the way a
// user without a 1+W function would: 1 + W(-exp(-1 - t)), z rounded to double.

#include <boost/math/special_functions/lambert_w.hpp>
#include <boost/version.hpp>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_lambert.h>
#include <gsl/gsl_version.h>

#include "hcimpact.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Row {
    std::string region, func;
    double x, ref_hi, ref_lo;
};

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}

bool parse_double(const std::string& s, double& v) {
    const std::string t = trim(s);
    if (t.empty()) return false;
    char* end = nullptr;
    v = std::strtod(t.c_str(), &end); // decimal, hex floats, nan, inf
    return end == t.c_str() + t.size();
}

bool read_csv(const std::string& path, std::vector<Row>& rows) {
    std::ifstream f(path);
    if (!f) {
        std::fprintf(stderr, "cannot open %s\n", path.c_str());
        return false;
    }
    std::string line;
    int lineno = 0;
    while (std::getline(f, line)) {
        ++lineno;
        const std::string t = trim(line);
        if (t.empty() || t[0] == '#') continue;
        std::vector<std::string> field;
        std::stringstream ss(t);
        std::string item;
        while (std::getline(ss, item, ',')) field.push_back(trim(item));
        if (field.size() >= 1 && field[0] == "region") continue; // header
        Row r;
        if (field.size() < 5 || !parse_double(field[2], r.x) || !parse_double(field[3], r.ref_hi) ||
            !parse_double(field[4], r.ref_lo)) {
            std::fprintf(stderr, "%s:%d: malformed row skipped: %s\n", path.c_str(), lineno, t.c_str());
            continue;
        }
        r.region = field[0];
        r.func = field[1];
        if (r.func != "w0" && r.func != "wm1" && r.func != "w0p1" && r.func != "wm1p1") {
            std::fprintf(stderr, "%s:%d: unknown func '%s' skipped\n", path.c_str(), lineno, r.func.c_str());
            continue;
        }
        rows.push_back(r);
    }
    return true;
}

// Spacing of the doubles at the exact value ref_hi + ref_lo (see the header).
double ulp_at(double hi, double lo) {
    const double a = std::fabs(hi);
    if (a == 0.0) return std::numeric_limits<double>::denorm_min();
    if (a == DBL_MAX) return a - std::nextafter(a, 0.0);
    double u = std::nextafter(a, HUGE_VAL) - a;
    int e = 0;
    const bool pow2 = std::frexp(a, &e) == 0.5;
    const bool below = lo != 0.0 && std::signbit(lo) != std::signbit(hi);
    if (pow2 && below && a > DBL_MIN) u *= 0.5;
    return u;
}

enum class Outcome { ok, fail };

// Error of one result y (threw: the implementation raised an exception).
Outcome ulp_error(const Row& r, double y, bool threw, double& err) {
    err = 0.0;
    if (std::isnan(r.ref_hi)) {
        if (threw || std::isnan(y)) return Outcome::ok;
        return Outcome::fail;
    }
    if (threw || std::isnan(y)) return Outcome::fail;
    if (std::isinf(r.ref_hi)) return (y == r.ref_hi) ? Outcome::ok : Outcome::fail;
    if (std::isinf(y)) return Outcome::fail;
    err = std::fabs((y - r.ref_hi) - r.ref_lo) / ulp_at(r.ref_hi, r.ref_lo);
    return Outcome::ok;
}

// An evaluation: value, whether it threw, and whether the library flagged it.
struct Eval {
    double y = std::numeric_limits<double>::quiet_NaN();
    bool threw = false;
    bool flagged = false; // GSL returned a status other than GSL_SUCCESS
};

bool is_p1(const std::string& func) { return func == "w0p1" || func == "wm1p1"; }
bool is_w0(const std::string& func) { return func == "w0" || func == "w0p1"; }

Eval eval_ours(const Row& r) {
    Eval e;
    if (r.func == "w0") e.y = hcimpact_lambert_w0(r.x);
    else if (r.func == "wm1") e.y = hcimpact_lambert_wm1(r.x);
    else if (r.func == "w0p1") e.y = hcimpact_lambert_w0p1(r.x);
    else e.y = hcimpact_lambert_wm1p1(r.x);
    return e;
}

// The argument a peer sees: x itself, or z = -exp(-1 - t) rounded to double.
double peer_z(const Row& r) { return is_p1(r.func) ? -std::exp(-1.0 - r.x) : r.x; }

Eval eval_boost(const Row& r) {
    Eval e;
    const double z = peer_z(r);
    try {
        const double w = is_w0(r.func) ? boost::math::lambert_w0(z) : boost::math::lambert_wm1(z);
        e.y = is_p1(r.func) ? 1.0 + w : w;
    } catch (const std::exception&) {
        e.threw = true;
    }
    return e;
}

Eval eval_gsl(const Row& r) {
    Eval e;
    const double z = peer_z(r);
    gsl_sf_result res;
    const int status = is_w0(r.func) ? gsl_sf_lambert_W0_e(z, &res) : gsl_sf_lambert_Wm1_e(z, &res);
    e.flagged = status != GSL_SUCCESS;
    e.y = is_p1(r.func) ? 1.0 + res.val : res.val;
    return e;
}

struct Stats {
    std::vector<double> err;
    int fails = 0, flagged = 0;
    double worst = -1.0;
    const Row* worst_row = nullptr;
    double worst_y = 0.0;
    bool worst_is_fail = false;
    bool worst_threw = false;

    void add(const Row& r, const Eval& e) {
        double err_ulp = 0.0;
        if (e.flagged) ++flagged;
        if (ulp_error(r, e.y, e.threw, err_ulp) == Outcome::fail) {
            ++fails;
            if (!worst_is_fail) { // the first fail is the worst case shown
                worst_is_fail = true;
                worst_row = &r;
                worst_y = e.y;
                worst_threw = e.threw;
                worst = std::numeric_limits<double>::infinity();
            }
            return;
        }
        err.push_back(err_ulp);
        if (!worst_is_fail && err_ulp > worst) {
            worst = err_ulp;
            worst_row = &r;
            worst_y = e.y;
        }
    }
    double max() const { return err.empty() ? -1.0 : *std::max_element(err.begin(), err.end()); }
    double median() const {
        if (err.empty()) return -1.0;
        std::vector<double> v = err;
        std::sort(v.begin(), v.end());
        const std::size_t m = v.size() / 2;
        return (v.size() % 2) ? v[m] : 0.5 * (v[m - 1] + v[m]);
    }
};

std::string fmt_ulp(double u) {
    char b[48];
    if (u < 0.0) return "–";
    if (u == 0.0) return "0";
    if (u < 10.0) std::snprintf(b, sizeof b, "%.2f", u);
    else if (u < 1e4) std::snprintf(b, sizeof b, "%.0f", u);
    else std::snprintf(b, sizeof b, "%.1e", u);
    return b;
}

std::string fmt_g(double v) {
    char b[48];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

const char* kImpl[] = {"ours", "Boost", "GSL"};

} // namespace

int main(int argc, char** argv) {
    const std::string path = (argc > 1) ? argv[1] : "test/reference/lambertw.csv";
    gsl_set_error_handler_off(); // GSL must report, never abort
    std::vector<Row> rows;
    if (!read_csv(path, rows)) return 1;
    if (rows.empty()) {
        std::fprintf(stderr, "%s: no data rows\n", path.c_str());
        return 1;
    }

    // groups (func, region) in the order: func w0, wm1, w0p1, wm1p1, then
    // the regions in the order they first appear in the file
    const std::vector<std::string> funcs = {"w0", "wm1", "w0p1", "wm1p1"};
    std::vector<std::pair<std::string, std::string>> groups;
    std::map<std::pair<std::string, std::string>, std::vector<const Row*>> members;
    for (const auto& f : funcs) {
        for (const auto& r : rows) {
            if (r.func != f) continue;
            const auto key = std::make_pair(r.func, r.region);
            if (members.find(key) == members.end()) groups.push_back(key);
            members[key].push_back(&r);
        }
    }

    std::map<std::pair<std::string, std::string>, Stats> stats[3];
    for (const auto& key : groups) {
        for (const Row* r : members[key]) {
            stats[0][key].add(*r, eval_ours(*r));
            stats[1][key].add(*r, eval_boost(*r));
            stats[2][key].add(*r, eval_gsl(*r));
        }
    }

    std::printf("### Accuracy against the mpmath reference (%s, %zu points)\n\n", path.c_str(), rows.size());
    std::printf("Boost %d.%d.%d (lambert_w0/lambert_wm1, double, default policy), GSL %s "
                "(gsl_sf_lambert_W0_e/Wm1_e, error handler off). Error in ulps of the exact "
                "reference; \"fail\" = exception, or NaN/inf where the reference is finite "
                "(not in max/median). 1+W forms: ours from t, the peers as "
                "1 + W(-exp(-1-t)) with z rounded to double.\n\n",
                BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, BOOST_VERSION % 100, GSL_VERSION);

    std::printf("| func | region | n | ours max | ours median | ours fail | Boost max | Boost median | "
                "Boost fail | GSL max | GSL median | GSL fail |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    int gsl_flag_total = 0;
    for (const auto& key : groups) {
        std::printf("| %s | %s | %zu", key.first.c_str(), key.second.c_str(), members[key].size());
        for (int k = 0; k < 3; ++k) {
            const Stats& s = stats[k][key];
            std::printf(" | %s | %s | %d", fmt_ulp(s.max()).c_str(), fmt_ulp(s.median()).c_str(), s.fails);
        }
        gsl_flag_total += stats[2][key].flagged;
        std::printf(" |\n");
    }
    std::printf("\nGSL returned an error status for %d of the points", gsl_flag_total);
    if (gsl_flag_total > 0) {
        std::printf(" (");
        bool first = true;
        for (const auto& key : groups) {
            const int n = stats[2][key].flagged;
            if (n == 0) continue;
            std::printf("%s%s/%s: %d", first ? "" : ", ", key.first.c_str(), key.second.c_str(), n);
            first = false;
        }
        std::printf("; their values are still scored)");
    }
    std::printf(".\n\n");

    std::printf("#### Worst case per (func, region, implementation)\n\n");
    std::printf("| func | region | impl | x (t for 1+W) | result | reference (hi) | ulp |\n");
    std::printf("|---|---|---|---:|---:|---:|---:|\n");
    for (const auto& key : groups) {
        for (int k = 0; k < 3; ++k) {
            const Stats& s = stats[k][key];
            if (s.worst_row == nullptr) continue;
            const bool threw = s.worst_is_fail && s.worst_threw;
            std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", key.first.c_str(), key.second.c_str(),
                        kImpl[k], fmt_g(s.worst_row->x).c_str(),
                        threw ? "exception" : fmt_g(s.worst_y).c_str(), fmt_g(s.worst_row->ref_hi).c_str(),
                        s.worst_is_fail ? "fail" : fmt_ulp(s.worst).c_str());
        }
    }
    std::printf("\n");
    return 0;
}
