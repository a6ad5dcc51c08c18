/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   LAMMPS development team: developers@lammps.org

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: FRICTION-EQ developers
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   FRICTION-EQ package: master equation of independent contacts on a
   rigid slider at constant velocity v with thermally activated breaking,
   threshold aging and a re-formation delay (eq_thermal.h).  LAMMPS-free.
   Units: k_c = 1, stretches in the units of the thresholds, times in
   those of 1/omega, tau, tau_a, t_w (all the same unit).

   One life.  A contact formed with stretch r0 and age a0 has, after the
   slider moved by y, the stretch x = r0 + y, the age t = a0 + y/v and the
   threshold x_s0 A(t).  It breaks at once when |x| reaches x_s0 A(t),
   at y*(x_s0) (unique: A is concave), and before that with the hazard
   H(y; x_s0) = (1/v) int_0^y nu(r0 + eta, x_s0 A(a0 + eta/v)) d eta.
   With thresholds P_c conditioned on x_s0 > |r0| (as fix eq/contacts
   draws them), the survival is

     S(y) = int_{x_s0 > s(y)} P_c(x_s0) exp(-H(y; x_s0)) dx_s0 / P(x_s0 > |r0|),
     s(y) = |r0 + y| / A(a0 + y/v)   (the threshold reached at y).

   Steady state (renewal process; spec notes (c)).  Lives of the re-formed
   contacts (r0 = reform stretch, a0 = 0), separated by a delay of mean
   vtau:  <L> = int S dy,  F_k/(N k_c) = int (r0 + y) S dy / (<L> + vtau),
   Gamma_s = 1/(<L> + vtau), attached fraction n_a = <L> Gamma_s.  Both
   integrals are taken per threshold: int dx_s0 P_c(x_s0) int_0^{y*}
   (1, x) e^{-H} dy (adaptive Gauss-Kronrod over x_s0, and for each x_s0
   adaptive Gauss-Legendre panels along y that carry H with them, each
   adding at most 2 to H); converged to ~1e-14 relative (tolerances 100
   times looser or 3 times tighter change F_k by 3e-15).

   Transient (renewal equation).  All contacts formed at X = 0 with the
   stretch `start` and the age t_w (first life S_1), later lives S; the
   breaking rate Gamma, the re-forming rate Gamma_r (Gamma convolved with
   the delay distribution) and the moments of the stretch obey

     Gamma(X)  = f_1(X) + int_0^X Gamma_r(X') f(X - X') dX',   f = -S',
     <x^p>(X)  = (start + X)^p S_1(X) + int_0^X Gamma_r(X') (r0 + X - X')^p S(X - X') dX',

   solved on cells of width dx with the re-formations spread uniformly over
   each cell (the kernels are exact cell averages of S and x^p S): the
   same-cell breaks and delays make each cell a 2x2 linear solve; the
   probability is conserved by construction and the long-X limit is the
   steady state above exactly; F(X) is second order in dx (Richardson:
   1e-12 to 2e-9 at dx = 1e-3 where F is smooth or its kinks lie on the
   grid, 3e-8 to 3e-7 with kinks off the grid: T = 0 with aging or a
   fixed delay).  At T > 0, S and S_1 are piecewise Chebyshev
   interpolants (degree 16, split until the coefficients fall below
   1e-11) of the direct quadrature above (over x_s0 at fixed y: P_c
   against an interpolant of 1 - e^-H), an order of the integrals
   independent of the per-threshold one of the steady state; at T = 0,
   S(y) = P(x_s0 > s(y)) exactly.
------------------------------------------------------------------------- */

#ifndef FEQ_THERMAL_STEADY_H
#define FEQ_THERMAL_STEADY_H

#include "eq_distribution.h"
#include "eq_master_equation.h"
#include "eq_thermal.h"

#include <limits>
#include <memory>
#include <vector>

namespace feq {

// the problem: contacts on a rigid slider at constant velocity
struct ThermalSlider {
  DistributionPtr Pc;    // thresholds x_s0 at age 0
  ThermalSpec spec;      // theta, omega, p, q, xc, aging, delay, rest (= t_w)
  double v = 1.0;        // slider velocity
  bool reform = true;    // false: contacts never re-form (no steady state)
  double r0 = 0.0;       // stretch of a re-formed contact (reform delta r0)
  double start = 0.0;    // stretch of the contacts at X = 0 (their age: spec.rest)
  double delay_length() const;    // v tau (mean), 0 without delay
};

// The lives of contacts formed with stretch r0 and age a0 (see above).
class ContactLife {
 public:
  ContactLife(const ThermalSlider &s, double r0, double age0);
  const ThermalSpec &params() const { return model.params(); }
  double initial_stretch() const { return r0; }

  double breakpoint(double xs0) const;        // y*(x_s0)
  double threshold_at(double y) const;        // s(y)
  double exponent(double y, double xs0) const;    // H(y; x_s0), y <= y*(x_s0)
  double survival(double y) const;            // S(y) by direct quadrature
  // int_0^{y*} e^{-H} dy and int_0^{y*} (r0 + y) e^{-H} dy for one threshold
  void moments(double xs0, double &L, double &M) const;
  // S(y) = 0 for y >= ymax() (the break point of the largest threshold)
  double ymax() const { return ytop; }
  // the y where S has kinks: the break points of the ends and kinks of P_c
  std::vector<double> kinks() const;
  // the thresholds, conditioned on x_s0 > |r0|: [lo, hi] (tails cut at
  // 1e-18) split at the kinks of P_c, and the normalisation P(x_s0 > |r0|)
  const std::vector<double> &threshold_pieces() const { return pieces; }
  double weight_norm() const { return norm; }
  bool point_thresholds() const { return point; }

 private:
  DistributionPtr Pc;
  ThermalModel model;
  double v, r0, age0;
  std::vector<double> pieces;
  double norm, ytop;
  bool point;

  double factor(double y) const { return model.factor(age0 + y / v); }
  // the slide over which the threshold's aging is fastest at formation,
  // v (tau_a + age0) (infinite without aging)
  double aging_length() const
  {
    return model.params().aging == AgingLaw::NONE ? std::numeric_limits<double>::infinity()
                                                  : v * (model.params().tau_a + age0);
  }
  double rate(double y, double xs0) const { return model.rate(r0 + y, xs0 * factor(y)) / v; }
  double zone_start(double xs0, double ys) const;
  double rate_noise(double y, double xs0) const;
  double exponent_kinked(double y, double xs0) const;
};

struct ThermalSteady {
  double F = 0.0;           // F_k / (N k_c)
  double Gamma = 0.0;       // Gamma_s: breaks per contact per unit displacement
  double lifetime = 0.0;    // <L>: mean slider displacement of a life
  double attached = 0.0;    // n_a = <L> Gamma_s
};

// Needs contacts that re-form (s.reform).
ThermalSteady thermal_steady_state(const ThermalSlider &s);
// dF_k/d ln v at s.v (4-point central differences in ln v, step 0.05)
double kinetic_slope(const ThermalSlider &s);

struct KineticPoint {
  double v, F, slope, attached, Gamma;
};
// n velocities log-spaced on [vlo, vhi] (n = 1: vlo)
std::vector<KineticPoint> kinetic_table(const ThermalSlider &s, double vlo, double vhi, int n);

// The uniform load factor eps0 of screened blocks in steady sliding at
// s.v (fix eq/meso; spec note (e)): eps0 = Pi0 x_c Gamma(eps0), where
// Gamma(eps) = r((1 + eps) v)/v, r(w) = w Gamma_s(w) the breaks per
// contact and unit time of contacts loaded at w and x_c the mean
// threshold.  Solved for w0 = (1 + eps0) v as a root above v of h(w) = 1 -
// v/w - Pi0 x_c Gamma_s(w) (h(v) < 0): the first sign change on steps of 1
// in ln w from v (the smallest root unless h crosses 0 twice within one
// step; a scan of 285 cases with aging and delays found one sign change
// each), bisected in ln w to rounding.  At T = 0 without aging or delay
// Gamma_s = 1/x_c and eps0 = Pi0/(1 - Pi0).  Throws SpecError where h
// stays <= 0 up to w = e^60 v.
double screened_load_factor(const ThermalSlider &s, double pi0);

// A piecewise Chebyshev interpolant (degree 16, points of the second
// kind, barycentric evaluation) of a function on contiguous pieces.
class PiecewiseChebyshev {
 public:
  static constexpr int DEGREE = 16;
  // appends the pieces of f on [a, b] (after those already there): halves
  // a piece until its two highest coefficients are below tol or it is
  // narrower than min_width
  void build(const std::function<double(double)> &f, double a, double b, double tol,
             double min_width);
  double operator()(double x) const;    // x within the pieces
  bool empty() const { return lo.empty(); }
  const std::vector<double> &starts() const { return lo; }
  double end() const { return hi.empty() ? 0.0 : hi.back(); }
  double last_value() const { return values.back()[0]; }    // f at end()

 private:
  std::vector<double> lo, hi;                 // pieces [lo, hi]
  std::vector<std::vector<double>> values;    // f at their Chebyshev points
  double interpolate(size_t piece, double x) const;
};

// The survival S(y) of a ContactLife as piecewise Chebyshev interpolants
// on [0, ymax] (cut where S < NEGLIGIBLE; S is monotone); at T = 0 S
// itself (cheap and exact).
class SurvivalTable {
 public:
  explicit SurvivalTable(const ContactLife &life);
  static constexpr double TOLERANCE = 1e-11;    // on the Chebyshev coefficients
  static constexpr double NEGLIGIBLE = 1e-25;   // S below: the table ends
  double operator()(double y) const;
  double end() const { return yend; }    // S = 0 (below NEGLIGIBLE) beyond
  // (1/(b-a)) int_a^b (r0 + y)^p S(y) dy for p = 0..3
  void cell_moments(double a, double b, double r0, double m[4]) const;
  size_t pieces() const { return breaks.size(); }

 private:
  ContactLife life;
  bool direct;                   // T = 0: no interpolant
  PiecewiseChebyshev cheb;
  std::vector<double> breaks;    // starts of the smooth pieces of S
  double yend;
};

// F(X) etc. from the fresh start (see above) on X = 0, dx, ..., Xmax;
// columns as solve_master_equation (F, sd, Gamma, attached, skew; no
// stretch grid).  The survival tables are built once, for any dx.
class ThermalTransient {
 public:
  explicit ThermalTransient(const ThermalSlider &s);
  MEResult solve(double dx, double Xmax) const;
  // richardson: F from dx and dx/2, (4 F_dx/2 - F_dx)/3 (the scheme is
  // second order); the other columns from dx/2
  MEResult solve(double dx, double Xmax, bool richardson) const;
  const SurvivalTable &first_life() const { return *S1; }
  const SurvivalTable *later_lives() const { return S.get(); }    // null: no re-forming

 private:
  ThermalSlider slider;
  std::shared_ptr<const SurvivalTable> S, S1;    // later lives (null: no re-forming), first
};

// ThermalTransient(s).solve(dx, Xmax, richardson).  The size (cells times
// kernel cells) is checked by the caller (thermal_kernel_cells).
MEResult thermal_transient(const ThermalSlider &s, double dx, double Xmax, bool richardson = false);
// the number of kernel cells the transient needs at dx (the longest life)
double thermal_kernel_cells(const ThermalSlider &s, double dx);

}    // namespace feq

#endif
