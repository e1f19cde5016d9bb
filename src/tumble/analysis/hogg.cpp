// SPDX-License-Identifier: MIT
// Hogg et al. (1966) axial diffusion in a rotating drum, as used by Kohring
// (section 3), and the fit of D to <z>(N). See hogg.hpp for conventions:
// N in revolutions, z and L in metres, D in m^2 per revolution,
// a = pi^2 D N / L^2.
#include "tumble/analysis/hogg.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "tumble/analysis/series.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {
namespace {

constexpr double pi2 = pi * pi;
constexpr double pi3 = pi * pi * pi;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

// Below a = 1 the sums are evaluated through images, above it through the
// Fourier series of the paper. Both take at most ~5 terms at the switch.
constexpr double series_from_a = 1.0;
// erfc(7) = 4e-23 and exp(-42) = 6e-19 (times 1/k^3 <= 1/343): terms beyond
// these are below double round-off of the leading 1/4.
constexpr double erfc_cut = 7.0;
constexpr double exp_cut = 42.0;

void check_arguments(double D, double N, double L) {
    if (!std::isfinite(D) || !std::isfinite(N) || !std::isfinite(L))
        throw Error("Hogg solution: D, N and L must be finite");
    if (D < 0.0) throw Error("Hogg solution: D must be >= 0 (m^2 per revolution)");
    if (N < 0.0) throw Error("Hogg solution: N must be >= 0 (revolutions)");
    if (L <= 0.0) throw Error("Hogg solution: the bed length L must be > 0 (m)");
}

// a = pi^2 D N / L^2, the dimensionless time of the slowest mode.
double mode_time(double D, double N, double L) { return pi2 * D * N / (L * L); }

// <z>/L as a function of a alone.
//
// Series (Kohring eq. avgfull), for a >= 1:
//   <z>/L = 8/pi^3 sum_{k=1,3,5..} (-1)^((k-1)/2) exp(-k^2 a) / k^3.
// Images, for a < 1. The drum's step problem with no-flux end caps equals a
// square wave of period 2L on the whole line, so C is a sum of error-function
// steps at z = 0, +-L, +-2L, ... Since d<z>/dN = -(2D/L) (C(L/2) - C(-L/2))
// (integrate dC/dN = D C'' against z, C' = 0 at the caps) and
//   C(L/2) - C(-L/2) = 1 - 2 sum_{j>=0} (-1)^j erfc(x_j),
//   x_j = (2j+1) L / (4 sqrt(D N)) = (2j+1) pi / (4 sqrt(a)),
// integrating in N with int_0^N erfc(c/sqrt(n)) dn = N g(c/sqrt(N)) gives
//   <z>/L = 1/4 - 2a/pi^2 + (4a/pi^2) sum_{j>=0} (-1)^j g(x_j),
//   g(x) = (1 + 2x^2) erfc(x) - (2/sqrt(pi)) x exp(-x^2)   (= 4 i^2erfc x).
// So <z> = L/4 - 2DN/L exactly until the front reaches the end caps.
double mean_position_scaled(double a) {
    if (a == 0.0) return 0.25;
    if (a < series_from_a) {
        const double x0 = 0.25 * pi / std::sqrt(a);
        double images = 0.0;
        double sign = 1.0;
        for (double x = x0; x < erfc_cut; x += 2.0 * x0, sign = -sign) {
            const double g = (1.0 + 2.0 * x * x) * std::erfc(x) -
                             2.0 / std::sqrt(pi) * x * std::exp(-x * x);
            images += sign * g;
        }
        return 0.25 - 2.0 * a / pi2 + 4.0 * a / pi2 * images;
    }
    double sum = 0.0;
    double sign = 1.0;
    for (double k = 1.0; k * k * a < exp_cut; k += 2.0, sign = -sign)
        sum += sign * std::exp(-k * k * a) / (k * k * k);
    return 8.0 / pi3 * sum;
}

// h(a) with d<z>/dD = -(2N/L) h(a); h = C(L/2) - C(-L/2), from 1 at a = 0 to 0.
//   series: h = 4/pi sum_k (-1)^((k-1)/2) exp(-k^2 a) / k,
//   images: h = 1 - 2 sum_j (-1)^j erfc(x_j).
double end_contrast(double a) {
    if (a == 0.0) return 1.0;
    if (a < series_from_a) {
        const double x0 = 0.25 * pi / std::sqrt(a);
        double images = 0.0;
        double sign = 1.0;
        for (double x = x0; x < erfc_cut; x += 2.0 * x0, sign = -sign)
            images += sign * std::erfc(x);
        return 1.0 - 2.0 * images;
    }
    double sum = 0.0;
    double sign = 1.0;
    for (double k = 1.0; k * k * a < exp_cut; k += 2.0, sign = -sign)
        sum += sign * std::exp(-k * k * a) / k;
    return 4.0 / pi * sum;
}

// C as a function of u = z/L in [-1/2, 1/2] and a.
//   series (Kohring eq. diffsol), a >= 1:
//     C = 1/2 + 2/pi sum_k exp(-k^2 a) sin(k pi u) / k;
//   images, a < 1, with w = sqrt(4 D N) / L = 2 sqrt(a) / pi:
//     C = erfc(-u/w)/2 + sum_{p>=1} (-1)^p [erfc((p-u)/w) - erfc((p+u)/w)] / 2.
double concentration_scaled(double u, double a) {
    if (a == 0.0) return u > 0.0 ? 1.0 : (u < 0.0 ? 0.0 : 0.5);
    if (a < series_from_a) {
        const double w = 2.0 * std::sqrt(a) / pi;
        double c = 0.5 * std::erfc(-u / w);
        double sign = -1.0;
        for (double p = 1.0; (p - std::abs(u)) / w < erfc_cut; p += 1.0, sign = -sign)
            c += sign * 0.5 * (std::erfc((p - u) / w) - std::erfc((p + u) / w));
        return c;
    }
    double sum = 0.0;
    for (double k = 1.0; k * k * a < exp_cut; k += 2.0)
        sum += std::exp(-k * k * a) * std::sin(k * pi * u) / k;
    return 0.5 + 2.0 / pi * sum;
}

std::string format(double value) {
    std::ostringstream out;
    out << std::setprecision(3) << value;
    return out.str();
}

std::string join(const std::vector<std::string>& reasons) {
    std::string text;
    for (const std::string& reason : reasons) text += (text.empty() ? "" : "; ") + reason;
    return text;
}

// ---- fitting ----------------------------------------------------------------

struct Series {
    const std::vector<double>& N;  // revolutions
    const std::vector<double>& z;  // metres
    double L;                      // metres
};

// Sum of squared residuals of the full series at D.
double sse_full(const Series& s, double D) {
    double sse = 0.0;
    for (std::size_t i = 0; i < s.N.size(); ++i) {
        const double r = s.z[i] - s.L * mean_position_scaled(mode_time(D, s.N[i], s.L));
        sse += r * r;
    }
    return sse;
}

// One-term model A exp(-pi^2 D N / L^2) with the amplitude profiled out:
// for given D the best A is linear least squares, A = sum z e / sum e^2.
struct OneTerm {
    double A;
    double sse;
};

OneTerm one_term_at(const Series& s, double D) {
    double ze = 0.0, ee = 0.0;
    for (std::size_t i = 0; i < s.N.size(); ++i) {
        const double e = std::exp(-mode_time(D, s.N[i], s.L));
        ze += s.z[i] * e;
        ee += e * e;
    }
    const double A = ee > 0.0 ? ze / ee : 0.0;
    double sse = 0.0;
    for (std::size_t i = 0; i < s.N.size(); ++i) {
        const double r = s.z[i] - A * std::exp(-mode_time(D, s.N[i], s.L));
        sse += r * r;
    }
    return {A, sse};
}

struct Minimum {
    double D;
    bool at_lower;  // the grid minimum sat on the smallest D tried
    bool at_upper;  // ... on the largest
};

// Minimises f(D) over [lo, hi], lo > 0: a grid with ratio <= 2 in D finds
// the basin (robust to any starting point, 13 decades in ~45 evaluations),
// golden section on ln D then narrows the bracket around the best grid point
// to 1e-9 in ln D.
template <class F>
Minimum minimise_log(F&& f, double lo, double hi) {
    const double span = std::log(hi / lo);
    const int points = std::max(3, static_cast<int>(std::ceil(span / std::log(2.0))) + 1);
    const double step = span / (points - 1);
    int best = 0;
    double best_value = inf;
    for (int i = 0; i < points; ++i) {
        const double value = f(lo * std::exp(i * step));
        if (value < best_value) {
            best_value = value;
            best = i;
        }
    }
    double a = std::log(lo) + std::max(best - 1, 0) * step;
    double b = std::log(lo) + std::min(best + 1, points - 1) * step;
    const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - ratio * (b - a), d = a + ratio * (b - a);
    double fc = f(std::exp(c)), fd = f(std::exp(d));
    while (b - a > 1e-9) {
        if (fc <= fd) {
            b = d, d = c, fd = fc;
            c = b - ratio * (b - a), fc = f(std::exp(c));
        } else {
            a = c, c = d, fc = fd;
            d = a + ratio * (b - a), fd = f(std::exp(d));
        }
    }
    const double x = fc <= fd ? c : d;
    return {std::exp(x), best == 0, best == points - 1};
}

// Gauss-Newton polish of the full-series D (one parameter, analytic
// Jacobian): D += sum r J / sum J^2, kept >= 0, step halved until the sum
// of squares does not grow. Brings noise-free fits to round-off.
double polish_full(const Series& s, double D) {
    double sse = sse_full(s, D);
    for (int iteration = 0; iteration < 20; ++iteration) {
        double rj = 0.0, jj = 0.0;
        for (std::size_t i = 0; i < s.N.size(); ++i) {
            const double a = mode_time(D, s.N[i], s.L);
            const double r = s.z[i] - s.L * mean_position_scaled(a);
            const double J = -2.0 * s.N[i] / s.L * end_contrast(a);
            rj += r * J;
            jj += J * J;
        }
        if (jj <= 0.0) break;
        double step = rj / jj;
        bool accepted = false;
        for (int halving = 0; halving < 30 && !accepted; ++halving, step *= 0.5) {
            const double trial = std::max(D + step, 0.0);
            const double trial_sse = sse_full(s, trial);
            if (trial_sse <= sse) {
                accepted = std::abs(trial - D) > 1e-13 * D;
                D = trial, sse = trial_sse;
                if (!accepted) return D;
            }
        }
        if (!accepted) break;
    }
    return D;
}

void check_series(const std::vector<double>& N, const std::vector<double>& z, double L) {
    if (N.empty()) throw Error("fit_diffusion: no samples");
    if (N.size() != z.size())
        throw Error("fit_diffusion: N and <z> have different lengths (" +
                    std::to_string(N.size()) + " and " + std::to_string(z.size()) + ")");
    if (!std::isfinite(L) || L <= 0.0) throw Error("fit_diffusion: bed length L must be > 0 (m)");
    for (std::size_t i = 0; i < N.size(); ++i) {
        if (!std::isfinite(N[i]) || N[i] < 0.0)
            throw Error("fit_diffusion: N must be finite and >= 0 (revolutions)");
        if (i > 0 && N[i] < N[i - 1])
            throw Error("fit_diffusion: N must be in time order (non-decreasing)");
        if (!std::isfinite(z[i])) throw Error("fit_diffusion: <z> must be finite");
    }
}

}  // namespace

double hogg_mean_position(double D, double N, double L) {
    check_arguments(D, N, L);
    return L * mean_position_scaled(mode_time(D, N, L));
}

double hogg_mean_position_dD(double D, double N, double L) {
    check_arguments(D, N, L);
    // <z> depends on D N only, so d<z>/dD = (N/D) d<z>/dN = -(2N/L) h(a).
    return -2.0 * N / L * end_contrast(mode_time(D, N, L));
}

double hogg_one_term(double D, double N, double L) {
    check_arguments(D, N, L);
    // Kohring eq. (avgpos): 8L/pi^3 exp(-pi^2 D N / L^2), metres.
    return 8.0 * L / pi3 * std::exp(-mode_time(D, N, L));
}

double hogg_concentration(double z, double D, double N, double L) {
    check_arguments(D, N, L);
    if (!std::isfinite(z) || std::abs(z) > 0.5 * L * (1.0 + 1e-12))
        throw Error("hogg_concentration: z must lie in the bed, [-L/2, L/2]");
    const double u = std::clamp(z / L, -0.5, 0.5);
    return concentration_scaled(u, mode_time(D, N, L));
}

DiffusionFit fit_diffusion(const std::vector<double>& N, const std::vector<double>& z_mean,
                           double L) {
    check_series(N, z_mean, L);
    const Series s{N, z_mean, L};
    const std::size_t n = N.size();

    DiffusionFit fit;
    fit.points = n;
    fit.D = fit.D_stderr = fit.one_term_D = fit.one_term_D_stderr = fit.z0_one_term = nan;
    fit.residual_rms = nan;
    std::vector<std::string> reasons;
    if (n < 10)
        reasons.push_back("only " + std::to_string(n) + (n == 1 ? " sample" : " samples") +
                          "; at least 10 are needed");

    // Search range in D from the sampled revolutions: from a decay of 1e-8 of
    // the slowest mode over the whole series (indistinguishable from D = 0)
    // to a decay of exp(-40) by the first sample after the start.
    const double N_last = N.back();
    const auto first_positive = std::upper_bound(N.begin(), N.end(), 0.0);
    if (N_last <= N.front()) {
        reasons.push_back("all samples at the same N; no decay can be seen");
        fit.note = join(reasons);
        return fit;
    }
    const double N_step = *std::upper_bound(N.begin(), N.end(), N.front()) - N.front();
    const double D_lo = 1e-8 * L * L / (pi2 * N_last);
    const double D_hi = 40.0 * L * L / (pi2 * std::min(N_step, *first_positive));

    // Full series, L fixed, D >= 0.
    const Minimum full = minimise_log([&](double D) { return sse_full(s, D); }, D_lo, D_hi);
    double D = full.D;
    if (full.at_lower && sse_full(s, 0.0) <= sse_full(s, D)) D = 0.0;
    D = polish_full(s, D);

    std::vector<double> residual(n);
    double jj = 0.0, sse = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = mode_time(D, N[i], L);
        residual[i] = z_mean[i] - L * mean_position_scaled(a);
        const double J = -2.0 * N[i] / L * end_contrast(a);
        jj += J * J;
        sse += residual[i] * residual[i];
    }
    fit.D = D;
    fit.residual_rms = std::sqrt(sse / static_cast<double>(n));
    fit.correlation_samples = integrated_autocorrelation(residual);
    // Standard error. <z>(N) sampled many times per revolution carries noise
    // correlated over many samples (grains move together for a good part of
    // a revolution), so sigma^2 / sum J^2, which assumes n independent
    // residuals, is too small by the integrated autocorrelation time tau.
    // Inflating by tau (n_eff = n / tau) needs only the residuals, equals
    // (1 + rho)/(1 - rho) for AR(1) noise, and, unlike that lag-1 formula,
    // sums the measured correlations of whatever shape; J varies over
    // hundreds of samples, slowly against tau, which is what the factor
    // assumes. A moving-block bootstrap would need a block length from the
    // same autocorrelation analysis and ~100 refits per fit. Validated in
    // test_hogg.cpp: on AR(1) noise with tau = 3 to 100 samples the error is
    // 0.9-1.1 of the actual spread of D; an oscillation at the drum period
    // makes it err on the large side (measured 1.3-2.8x).
    const double sigma2 = n > 1 ? sse / static_cast<double>(n - 1) : nan;
    fit.D_stderr = jj > 0.0 ? std::sqrt(sigma2 / jj * fit.correlation_samples) : inf;

    // One-term model, A exp(-pi^2 D N / L^2), with the amplitude A free. The
    // paper reads D from the slope of ln<z> against N; a free intercept lets
    // the single exponential absorb the higher modes' 3 % at early N, where a
    // fixed 8L/pi^3 would bias D, and matches the full series once the early
    // revolutions are left out. Least squares on <z> itself (not ln<z>), so
    // noisy samples near or below zero are fine.
    const Minimum one =
        minimise_log([&](double Dt) { return one_term_at(s, Dt).sse; }, D_lo, D_hi);
    double D1 = one.D;
    if (one.at_lower && one_term_at(s, 0.0).sse <= one_term_at(s, D1).sse) D1 = 0.0;
    const OneTerm amplitude = one_term_at(s, D1);
    fit.one_term_D = D1;
    fit.z0_one_term = amplitude.A;
    {
        // Covariance of (A, D): sigma^2 (J^T J)^-1 with J = [e, -A pi^2 N / L^2 e].
        double ee = 0.0, ed = 0.0, dd = 0.0;
        std::vector<double> r1(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double e = std::exp(-mode_time(D1, N[i], L));
            const double jd = -amplitude.A * pi2 * N[i] / (L * L) * e;
            ee += e * e, ed += e * jd, dd += jd * jd;
            r1[i] = z_mean[i] - amplitude.A * e;
        }
        const double det = ee * dd - ed * ed;
        const double s2 = n > 2 ? amplitude.sse / static_cast<double>(n - 2) : nan;
        fit.one_term_D_stderr =
            det > 0.0 ? std::sqrt(s2 * ee / det * integrated_autocorrelation(r1)) : inf;
    }

    // Is D determined by these data?
    const double noise = fit.residual_rms;
    const double decay = L * (mean_position_scaled(mode_time(D, N.front(), L)) -
                              mean_position_scaled(mode_time(D, N_last, L)));
    std::size_t resolved = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (N[i] > N.front() && L * mean_position_scaled(mode_time(D, N[i], L)) > 3.0 * noise)
            ++resolved;
    if (full.at_upper) {
        reasons.push_back("<z> fell to zero before the first sample after N = " + format(N.front()) +
                          "; sample earlier or more often");
    } else if (decay <= 3.0 * noise) {
        reasons.push_back("no measurable decay: the fitted decay of <z> over the series, " +
                          format(decay) + " m, is not above 3 x the residual rms, " +
                          format(noise) + " m");
    } else if (resolved < 3) {
        reasons.push_back("the decay is not resolved: fewer than 3 samples after the first "
                          "stand above 3 x the residual rms (" + format(noise) + " m)");
    }
    const double relative = fit.D_stderr / D;
    if (!(relative <= 0.5))
        reasons.push_back("the relative standard error of D, " +
                          (std::isfinite(relative) ? format(100.0 * relative) + " %" : "unbounded") +
                          ", exceeds 50 %");
    fit.determined = reasons.empty();
    fit.note = join(reasons);
    return fit;
}


namespace {

// Inverse of a small symmetric positive-definite matrix (Gauss-Jordan);
// empty if it is singular.
std::vector<std::vector<double>> inverse(std::vector<std::vector<double>> a) {
    const std::size_t n = a.size();
    std::vector<std::vector<double>> b(n, std::vector<double>(n, 0.0));
    for (std::size_t i = 0; i < n; ++i) b[i][i] = 1.0;
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < n; ++r)
            if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
        if (!(std::abs(a[pivot][c]) > 0.0)) return {};
        std::swap(a[c], a[pivot]), std::swap(b[c], b[pivot]);
        const double d = a[c][c];
        for (std::size_t k = 0; k < n; ++k) a[c][k] /= d, b[c][k] /= d;
        for (std::size_t r = 0; r < n; ++r)
            if (r != c) {
                const double f = a[r][c];
                for (std::size_t k = 0; k < n; ++k) a[r][k] -= f * a[c][k], b[r][k] -= f * b[c][k];
            }
    }
    return b;
}

// For a given D, the linear parameters of <z> = A g(N) + v N (g = 4 <z>_Hogg / L,
// 1 at N = 0) by least squares, and the sum of squared residuals.
struct Linear {
    double A = 0.0, v = 0.0, sse = 0.0;
};

Linear linear_at(const Series& s, double D, bool drift) {
    double gg = 0.0, gn = 0.0, nn = 0.0, gz = 0.0, nz = 0.0;
    for (std::size_t i = 0; i < s.N.size(); ++i) {
        const double g = 4.0 * mean_position_scaled(mode_time(D, s.N[i], s.L));
        gg += g * g, gn += g * s.N[i], nn += s.N[i] * s.N[i], gz += g * s.z[i], nz += s.N[i] * s.z[i];
    }
    Linear f;
    if (drift) {
        const double det = gg * nn - gn * gn;
        if (det > 0.0) f.A = (gz * nn - nz * gn) / det, f.v = (gg * nz - gn * gz) / det;
    } else if (gg > 0.0) {
        f.A = gz / gg;
    }
    for (std::size_t i = 0; i < s.N.size(); ++i) {
        const double r = s.z[i] - f.A * 4.0 * mean_position_scaled(mode_time(D, s.N[i], s.L)) - f.v * s.N[i];
        f.sse += r * r;
    }
    return f;
}

}  // namespace

HoggFit fit_hogg(const std::vector<double>& N_all, const std::vector<double>& z_all, double L,
                 const HoggFitOptions& o) {
    check_series(N_all, z_all, L);
    std::vector<double> N, z;
    for (std::size_t i = 0; i < N_all.size(); ++i)
        if (N_all[i] >= o.first_revolution) N.push_back(N_all[i]), z.push_back(z_all[i]);
    HoggFit fit;
    fit.points = N.size();
    fit.D = fit.D_stderr = fit.amplitude = fit.amplitude_stderr = fit.residual_rms = nan;
    const std::size_t n = N.size();
    const std::size_t parameters = (o.fixed_D >= 0.0 ? 1 : 2) + (o.drift ? 1 : 0);
    if (n < 10 || N.back() <= N.front()) {
        fit.note = "only " + std::to_string(n) + " samples at N >= " + format(o.first_revolution) +
                   " spanning a time; at least 10 are needed";
        return fit;
    }
    const Series s{N, z, L};
    double D = o.fixed_D;
    if (D < 0.0) {
        const double D_lo = 1e-8 * L * L / (pi2 * N.back());
        const double D_hi = 40.0 * L * L / (pi2 * N.front());
        D = minimise_log([&](double Dt) { return linear_at(s, Dt, o.drift).sse; }, D_lo, D_hi).D;
    }
    const Linear lin = linear_at(s, D, o.drift);
    fit.D = D;
    fit.amplitude = lin.A;
    fit.drift = lin.v;

    // Jacobian columns: d<z>/dA = g, d<z>/dD = A (4/L) d<z>_Hogg/dD, d<z>/dv = N.
    std::vector<std::vector<double>> J;
    std::vector<double> residual(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double a = mode_time(D, N[i], L);
        std::vector<double> row{4.0 * mean_position_scaled(a)};
        if (o.fixed_D < 0.0) row.push_back(lin.A * 4.0 / L * (-2.0 * N[i] / L * end_contrast(a)));
        if (o.drift) row.push_back(N[i]);
        residual[i] = z[i] - lin.A * row[0] - lin.v * N[i];
        J.push_back(std::move(row));
    }
    std::vector<std::vector<double>> JtJ(parameters, std::vector<double>(parameters, 0.0));
    for (const auto& row : J)
        for (std::size_t p = 0; p < parameters; ++p)
            for (std::size_t q = 0; q < parameters; ++q) JtJ[p][q] += row[p] * row[q];
    fit.residual_rms = std::sqrt(lin.sse / static_cast<double>(n));
    fit.correlation_samples = integrated_autocorrelation(residual);
    const double sigma2 = lin.sse / static_cast<double>(n - parameters) * fit.correlation_samples;
    const auto covariance = inverse(JtJ);
    auto stderr_of = [&](std::size_t p) { return covariance.empty() ? inf : std::sqrt(sigma2 * covariance[p][p]); };
    fit.amplitude_stderr = stderr_of(0);
    fit.D_stderr = o.fixed_D < 0.0 ? stderr_of(1) : 0.0;
    fit.drift_stderr = o.drift ? stderr_of(parameters - 1) : 0.0;

    const double relative = o.fixed_D < 0.0 ? fit.D_stderr / fit.D : fit.drift_stderr / std::abs(fit.drift);
    if (o.fixed_D < 0.0 && !(relative <= 0.5))
        fit.note = "the relative standard error of D, " +
                   (std::isfinite(relative) ? format(100.0 * relative) + " %" : "unbounded") + ", exceeds 50 %";
    fit.determined = fit.note.empty();
    return fit;
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
    if (x.size() != y.size() || x.size() < 3) throw Error("fit_line: need at least 3 (x, y) pairs of equal count");
    const double n = static_cast<double>(x.size());
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
    const double det = n * sxx - sx * sx;
    LineFit f;
    if (!(det > 0.0)) throw Error("fit_line: all x are equal");
    f.slope = (n * sxy - sx * sy) / det;
    f.intercept = (sy - f.slope * sx) / n;
    std::vector<double> r(x.size());
    double sse = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        r[i] = y[i] - f.intercept - f.slope * x[i];
        sse += r[i] * r[i];
    }
    f.slope_stderr = std::sqrt(sse / (n - 2.0) * n / det * integrated_autocorrelation(r));
    return f;
}

}  // namespace tumble::analysis
