// SPDX-License-Identifier: MIT
// Axial diffusion in a rotating drum: the Hogg et al. (1966) solution used by
// Kohring (section 3, eqs. for C_1(z,N) and <z>_1) and a fit of the diffusion
// coefficient D to a measured mean-position series <z>(N).
//
// Conventions (SPEC-NOTES, "The drum experiment"):
//  - time is the number of drum revolutions N (dimensionless, N = 0 when
//    rotation starts);
//  - z is the axial position measured from the centre of the bed, in metres,
//    z in [-L/2, L/2], L the length of the bed in metres;
//  - D is in m^2 per revolution;
//  - the component described is the one that starts in the half z > 0; the
//    other component mirrors it (<z>_2 = -<z>_1, C_2 = 1 - C_1).
// The diffusion equation dC/dN = D d^2C/dz^2 with no flux through the end
// caps and the step C(z,0) = [z > 0] as initial condition gives these.
// Write a = pi^2 D N / L^2 (dimensionless) throughout.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace tumble::analysis {

// Kohring eq. (avgfull), Hogg et al.:
//   <z>(N) = 8L/pi^3 sum_{n>=1} (-1)^(n+1)/(2n-1)^3 exp(-(2n-1)^2 a),
// in metres. Exactly L/4 at N = 0 and decreasing to 0. Accurate to full
// double precision for every a >= 0 (for a < 1 it is evaluated through the
// equivalent image solution, which converges in a few terms where the series
// needs thousands). Throws tumble::Error for D < 0, N < 0, L <= 0 or
// non-finite input.
double hogg_mean_position(double D, double N, double L);

// d<z>/dD of hogg_mean_position at (D, N, L), in m / (m^2/rev): the
// Jacobian of the fit. At D = 0 it is -2N/L (the early-time slope).
double hogg_mean_position_dD(double D, double N, double L);

// Kohring eq. (avgpos), the paper's one-term approximation
//   <z>(N) ~ 8L/pi^3 exp(-pi^2 D N / L^2),  metres.
// 32/pi^3 - 1 = 3.2 % above the full series at N = 0 ("about 3 %"), and
// equal to it to a relative exp(-8a)/27 once a is of order one.
double hogg_one_term(double D, double N, double L);

// Kohring eq. (diffsol), Hogg et al.:
//   C(z,N) = 1/2 + 2/pi sum_{n>=1} 1/(2n-1) exp(-(2n-1)^2 a) sin((2n-1) pi z / L),
// the local fraction (0..1) of the component that started at z > 0, for z in
// [-L/2, L/2] (metres). At N = 0 it is the exact step: 1 for z > 0, 0 for
// z < 0, 1/2 at z = 0. The component's mean position is
//   <z> = (2/L) int_{-L/2}^{L/2} z (C - 1/2) dz = hogg_mean_position.
// Throws tumble::Error for z outside the bed or the arguments
// hogg_mean_position rejects.
double hogg_concentration(double z, double D, double N, double L);

// Result of fit_diffusion. Lengths in metres, D in m^2 per revolution.
struct DiffusionFit {
    double D = 0.0;                   // least-squares D of the full series, L fixed
    double D_stderr = 0.0;            // its standard error, corrected for correlated residuals
    double one_term_D = 0.0;          // D of the one-term model A exp(-pi^2 D N / L^2), A free
    double one_term_D_stderr = 0.0;   // its standard error, corrected the same way
    double z0_one_term = 0.0;         // the fitted amplitude A (8L/pi^3 = 0.258 L in the paper)
    bool determined = false;          // D is usable (see note otherwise)
    std::string note;                 // why D is not determined; empty when it is
    std::size_t points = 0;           // number of (N, <z>) samples fitted
    double residual_rms = 0.0;        // rms of <z> - full model at D, metres
    double correlation_samples = 1.0; // integrated autocorrelation time of the full fit's
                                      // residuals, in samples (1 = white): the factor by
                                      // which the white-noise variance of D is inflated
};

// Fits D to a measured series <z>(N) of the component that started at z > 0.
// N: revolutions, non-negative and non-decreasing (time order: the residuals'
// autocorrelation is taken in this order, so samples should be evenly
// spaced); z_mean: metres; L: bed length in metres, held fixed.
//  - Full series: one free parameter D >= 0, least squares, found by a grid
//    on log D, golden-section refinement and Gauss-Newton polish.
//  - One-term model beside it, with amplitude A free (see hogg.cpp for why).
//    It is fitted on the same points; pass only the samples beyond the first
//    revolutions to use it the way the paper does.
//  - Standard errors: the least-squares error inflated by the residuals'
//    integrated autocorrelation time (hogg.cpp explains and justifies).
// Data too poor to determine D give determined = false and a note, not an
// exception; D is still the best fit (the top of the search range when <z>
// fell to zero before the first sample, NaN when nothing could be fitted). Throws tumble::Error for empty or mismatched input, L <= 0,
// negative, decreasing or non-finite N, or non-finite z.
DiffusionFit fit_diffusion(const std::vector<double>& N, const std::vector<double>& z_mean,
                           double L);

// The Hogg fit with the amplitude free and the
// start-up left out, optionally with a drift,
//   <z>(N) = A (4/L) hogg_mean_position(D, N, L) + v N,       N >= first_revolution,
// A in m (the effective <z>(0); 4A is an effective bed length), v in m per
// revolution (a steady motion of the component's centre that diffusion does
// not explain: segregation). Pinning A at L/4 biases D when the measured
// <z>(0) is off L/4 by dz0: in the linear regime (N << L^2/(pi^2 D)) the
// pinned slope through N = 0..T is off by 1.5 dz0 / T, so D by
// -0.75 dz0 L / T (test_hogg.cpp checks it). Note that in that regime a
// drift and a diffusion both only tilt a straight line: D and v are told
// apart only by the curvature that sets in at N ~ L^2/(pi^2 D), or with D
// held at an independent value (fixed_D, e.g. from the grains' MSD).
struct HoggFitOptions {
    double first_revolution = 1.0;  // leave out the start-up: fit N >= this
    bool drift = false;             // fit v as well
    double fixed_D = -1.0;          // >= 0: hold D at this value (m^2/rev); then only A (and v) are fitted
};

struct HoggFit {
    double D = 0.0, D_stderr = 0.0;                  // m^2/rev (stderr 0 when D is held)
    double amplitude = 0.0, amplitude_stderr = 0.0;  // A, m
    double drift = 0.0, drift_stderr = 0.0;          // v, m/rev (0 when not fitted)
    std::size_t points = 0;
    double residual_rms = 0.0;         // m
    double correlation_samples = 1.0;  // integrated autocorrelation time of the residuals, samples
    bool determined = false;           // D (or, with D held, v) is usable
    std::string note;                  // why not, when not
};

// Least squares; D on a log grid with golden-section refinement, A and v
// linear for each D. Standard errors from the Jacobian, inflated by the
// residuals' integrated autocorrelation time as in fit_diffusion. Not
// determined: fewer than 10 points, or a relative error of D (of v, with D
// held) above 50 %. Throws tumble::Error for input fit_diffusion rejects.
HoggFit fit_hogg(const std::vector<double>& N, const std::vector<double>& z_mean, double L,
                 const HoggFitOptions& options = {});

// A straight line y = a + b x by least squares, with the standard error of
// the slope b inflated by the residuals' integrated autocorrelation time:
// for a slow drift of a sampled quantity (e.g. <z>_1 + <z>_2 against N).
struct LineFit {
    double intercept = 0.0, slope = 0.0, slope_stderr = 0.0;
};
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace tumble::analysis
