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
   FRICTION-EQ package: master equation (ME) of the EQ model, paper Sec. II

     [d/dX + d/dx + P(x)] Q(x;X) = R(x) Gamma(X),
     Gamma(X) = int P(x) Q(x;X) dx,   P(x) = P_c(x) / J_c(x),
     F(X) = N k_c int x Q(x;X) dx.

   Scheme (class MasterEquation): the stretch grid x_j = j dx moves with
   the characteristics (one grid step per slider step dX = dx), so the
   transport term is exact.  Over one step the probability mass at x_j
   survives with the exact ratio S_j = J_c(x_j + dx) / J_c(x_j); the mass
   that breaks is re-injected into R(x) laid on the grid with hat-function
   weights (mass and mean exact), shifted by the exact mean remaining
   displacement after the break within the step.  Probability is
   conserved by construction (broken mass = re-injected mass); F(X) on
   the grid converges at second order in dx (measured in the tests and in
   doc/src/eq_me.rst; first order in the exit of a kink of P_c).

   steady_state() evaluates the analytic stationary solution (Eq. mf.eq07)
   by Gauss-Legendre quadrature, independently of the time stepper.
------------------------------------------------------------------------- */

#ifndef FEQ_MASTER_EQUATION_H
#define FEQ_MASTER_EQUATION_H

#include "eq_distribution.h"

#include <vector>

namespace feq {

enum class MEStart {
  RELAXED,    // Q(x;0) = delta(x): all contacts unstretched
  REFORM      // Q(x;0) = R(x)
};

// How a break within a slider step is treated (mirrors fix eq/contacts):
//  EXACT: the contact re-forms at the moment of the break (the continuous
//         master equation, second-order scheme);
//  STEP:  the contact re-forms at the end of the step with stretch r
//         (the cellular-automaton EQ convention of `crossing step`); the
//         scheme then reproduces that discrete model exactly, for any dx.
enum class Crossing { EXACT, STEP };

class MasterEquation {
 public:
  // R == nullptr: contacts never re-form (debonding)
  MasterEquation(DistributionPtr Pc, DistributionPtr R, double dx, double tail = 1e-17,
                 Crossing crossing = Crossing::EXACT);

  void start(MEStart how);
  void step();    // X -> X + dx

  double attached() const;        // int Q dx (1 unless contacts never re-form)
  double mean_stretch() const;    // int x Q dx  = F / (N k_c)
  double second_moment() const;   // int x^2 Q dx
  double third_moment() const;    // int x^3 Q dx
  double rate() const { return last_rate; }    // Gamma over the last step
  const std::vector<double> &grid() const { return x; }
  std::vector<double> density() const;    // Q(x_j;X) = (probability at x_j) / dx

 private:
  DistributionPtr Pc, R;
  double dx;
  long nstep;
  std::vector<double> x, m, brk, theta, w;
  long jlo, jhi;        // active range of m (inclusive); empty when jlo > jhi
  long wlo, whi;        // support of the re-injection weights
  double w_rebreak;     // sum_k w_k (1 - S_k): re-formed mass that breaks at once
  Crossing crossing;
  double last_rate;

  // Contacts re-formed with a negative stretch r cannot break before
  // their stretch reaches |r| (their threshold is drawn above |r|, as in
  // fix eq/contacts): they are "held" in a delay line per re-forming
  // grid point k and join the grid at |r_k|.  Ages are counted in steps;
  // the moments of the age keep the force sums O(1) per queue and step.
  struct Held {
    long k, release, len;     // birth point, grid point of |r_k|, steps to get there
    std::vector<double> ring; // mass by birth step modulo len
    double M, A1, A2, A3;     // sum m, m a, m a^2, m a^3 (a = age in steps)
  };
  std::vector<Held> held;
  std::vector<char> is_held;  // per grid point: re-forming there is held

  void extend(long lo, long hi);
  void hold(Held &h, double mass, long age);
};

struct MEOptions {
  double dx = 1e-3;
  double Xmax = 8.0;
  MEStart start = MEStart::RELAXED;
  Crossing crossing = Crossing::EXACT;
  std::vector<double> snapshots;    // X at which Q(x;X) is stored
};

struct MEResult {
  double dx = 0.0;
  std::vector<double> X, F, sd, Gamma, attached;    // F = <x> = F/(N k_c)
  std::vector<double> skew;    // skewness of one contact's force: decides
                               // whether an N-contact mean is near-normal
  std::vector<double> x;                             // stretch grid
  std::vector<double> snapX;
  std::vector<std::vector<double>> snapQ;
  double max_mass_error = 0.0;    // max |int Q - attached| (rounding only)
};

MEResult solve_master_equation(DistributionPtr Pc, DistributionPtr R, const MEOptions &opt);

// Richardson's combination of a solution at dx (res, changed) with one at
// dx/2 (fine): F = (4 F_fine - F)/3 at the common points, sd, attached and
// skewness those of the finer grid.  False (res unchanged) when fine is not
// on the same X range at half the step.
bool combine_richardson(MEResult &res, const MEResult &fine);

struct SteadyState {
  double Gamma = 0.0;           // breaks per contact per unit slider displacement
  double F = 0.0;               // kinetic force F_k / (N k_c)
  double lifetime = 0.0;        // mean slider displacement between breaks
  std::vector<double> x, Q;     // Q_s(x)
};

// Analytic stationary solution by quadrature; requires R (contacts re-form).
SteadyState steady_state(const Distribution &Pc, const Distribution &R, int npoints = 2001);

struct Extremum {
  double value = 0.0;
  double X = 0.0;
  bool found = false;    // false: no maximum / no drop of F within [0, xmax]
};

// K*/K_s = max_X -dF/dX / (N k_c)  (forward differences at step midpoints);
// 0 (found = false) when F never decreases within [0, xmax]
Extremum critical_stiffness(const MEResult &r);
// first maximum of F(X)/(N k_c) on the grid (static friction peak);
// found = false when F still increases at xmax
Extremum static_peak(const MEResult &r);

// Composite Gauss-Legendre quadrature of f over [a,b] split at the given
// break points, each piece in `panels` panels of 10 nodes.
double integrate(const std::function<double(double)> &f, double a, double b,
                 const std::vector<double> &breaks = {}, int panels = 64);

}    // namespace feq

#endif
