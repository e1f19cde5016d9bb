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

}  // namespace tumble::analysis
