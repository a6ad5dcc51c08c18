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
   FRICTION-EQ package: substrate force of a lambda_c block in the FK-ME
   model (paper Sec. V B).  LAMMPS-free.

   The force of the substrate on a block displaced by u from its site is
   F_s(u) = k_c phi(u), with a shape phi given on one period [0, u_c) and
   prolonged periodically (the block's contacts all re-form after a slip
   of u_c):

     sawtooth  phi(v) = v                                 (Eq. crack.eqi08)
     smooth    phi(v) = tanh(v) + 1.5 exp(-v) sin(3 v)    (Fig. crack.A03ab)
     table     phi linear between tabulated points (v_k, phi_k) on [0, u_c],
               e.g. F(X)/(N k_c) of the master equation of a rigid block

   The potential V(u) = int_0^u phi is continuous; it grows by the work
   W = int_0^{u_c} phi per period (the energy the slip dissipates), so
   F_s = k_c dV/du everywhere except at the jumps of phi at multiples of
   u_c.
------------------------------------------------------------------------- */

#ifndef FEQ_SUBSTRATE_H
#define FEQ_SUBSTRATE_H

#include "eq_thermal.h"

#include <cstdint>
#include <string>
#include <vector>

namespace feq {

class SubstrateShape {
 public:
  enum Kind { SAWTOOTH, SMOOTH, TABLE };

  static SubstrateShape sawtooth(double uc);
  static SubstrateShape smooth(double uc);
  // points v_0 = 0 < v_1 < ... < v_{n-1} = u_c with values phi_k; throws
  // SpecError (eq_distribution.h) naming the label on bad points
  static SubstrateShape table(const std::vector<double> &v, const std::vector<double> &phi,
                              const std::string &label);

  Kind kind() const { return kind_; }
  double period() const { return uc; }
  std::string describe() const { return text; }

  // phi(u) for any u (periodic); phi jumps at u = n u_c (value from the right)
  double phi(double u) const;
  // V(u) = int_0^u phi (continuous, n W + V(u - n u_c))
  double potential(double u) const;
  // index n of the period of u and the position r = u - n u_c within it,
  // 0 <= r < u_c (also where rounding puts u - floor(u/u_c) u_c at u_c)
  void reduce(double u, double &n, double &r) const;
  // phi and its integral from 0 within one period, 0 <= r <= u_c
  double phi_in(double r) const { return phi0(r); }
  double potential_in(double r) const { return V0(r); }
  // work per period W = V(u_c)
  double work() const { return W; }
  // largest phi on a period (the block's threshold force / k_c) and where
  double max_phi() const { return phimax; }
  double argmax_phi() const { return vmax; }

 private:
  Kind kind_ = SAWTOOTH;
  double uc = 1.0, W = 0.0, phimax = 0.0, vmax = 0.0;
  std::string text;
  std::vector<double> tv, tphi, tV;    // table points and V at them

  double phi0(double r) const;    // on [0, u_c)
  double V0(double r) const;      // int_0^r phi0
  void finish();                  // W, max
};

// The table section written for a substrate shape: 'KEYWORD', 'N n', blank,
// then "k v_k phi_k" lines (the format fix eq/contacts reads for thresholds)
std::string substrate_table_text(const std::string &keyword, const std::vector<double> &v,
                                 const std::vector<double> &phi, const std::string &comment);

/* ----------------------------------------------------------------------
   Velocity strengthening of a sliding block (fix eq/substrate ... rate A
   v0): at T > 0 the block law of the master equation becomes F_k(v, T),
   whose rise with the velocity is an extra, velocity-dependent friction
   of a moving block.  Its regularised logarithm (rate-and-state friction)

     F_rate(w) = A asinh(w / (2 v0)),   w = the block's velocity,

   is odd in w, A ln(w/v0) + A v0^2/w^2 + O(v0^4/w^4) for w >> v0 (slope
   dF/dln w -> A) and A w/(2 v0) (1 - w^2/(24 v0^2) + ...) for |w| << v0:
   viscous damping gamma = A/(2 v0).  The force on the block is -F_rate.
------------------------------------------------------------------------- */

class RateLaw {
 public:
  // the largest |F_rate| at a finite velocity is A (ln 2 + ln DBL_MAX -
  // ln(2 v0)) <= A * 1455 (v0 >= the smallest double): A is limited to
  // 1e300 / 711 so that forces stay finite
  static constexpr double A_MAX = 1e300 / 711.0;
  RateLaw() = default;
  // A >= 0 (force), v0 > 0 (velocity), both finite; throws SpecError
  // naming "rate A" or "rate v0"
  RateLaw(double A, double v0);
  // A > 0: the term is applied (A = 0 leaves the forces untouched)
  bool active() const { return A_ > 0.0; }
  double amplitude() const { return A_; }
  double v0() const { return v0_; }
  // F_rate(w), the magnitude of the force opposing the velocity w
  double force(double w) const;
  // dF_rate/dw = A / sqrt(w^2 + 4 v0^2) (> 0, largest at w = 0)
  double slope(double w) const;
  // dF_rate/dln|w| = w dF_rate/dw (-> A for |w| >> v0)
  double log_slope(double w) const { return w * slope(w); }
  // the viscous damping of the linear regime, A / (2 v0)
  double linear_gamma() const { return A_ / (2.0 * v0_); }

 private:
  double A_ = 0.0, v0_ = 1.0;
};

/* ----------------------------------------------------------------------
   Thermally activated hops of a block between the wells of a sawtooth
   substrate whose contacts break at both ends of the well (fix
   eq/substrate ... reverse break thermal ...).  A block in the well with
   origin a (stretch s = u - a, |s| < u_c) leaves it at the rate of
   fix eq/contacts' law (eq_thermal.h) with the block's stretch and
   threshold in units of force: x = k_c d s, x_s = k_c d u_c, x_c = k_c u_c,
   i.e. u = 1 - |s|/u_c and a barrier scale d^p.  Each life in a well has
   a hazard budget, Exp(1) drawn from (seed, tag, life, STREAM_BUDGET);
   the block hops when the hazard accumulated since it entered the well
   reaches it: a moves by u_c in the direction of s (as when s reaches
   +-u_c at T = 0, where it also moves), and a new life begins.
------------------------------------------------------------------------- */

// one change of well within a step: at the fraction theta of the step,
// direction sign (+1: forward), by the hazard (thermal) or by reaching
// the end of the well
struct WellChange {
  double theta = 1.0;
  int sign = 1;
  bool thermal = false;
};

// the per-block state of the hops
struct HopState {
  double anchor = 0.0;    // well origin a
  double budget = 0.0;    // hazard the current life can still take
  double life = 0.0;      // wells entered since the block was set up (counter key)
  double hops = 0.0;      // of them by the hazard
};

class BlockHops {
 public:
  static constexpr int MAX_CHANGES = 64;    // per block and step
  BlockHops() : model(ThermalSpec()) {}
  // uc: the period; seed > 0: key of the budgets
  BlockHops(const ThermalSpec &spec, double uc, uint64_t seed);
  const ThermalModel &thermal() const { return model; }

  // the Exp(1) budget of life `life` of block `tag`
  double budget(uint64_t tag, uint64_t life) const;
  // hop rate at stretch s, threshold factor d (0 at T = 0)
  double rate(double s, double d) const { return model.rate(s * d, uc * d); }

  // one step of duration dt over which the block moves linearly from u0
  // to u1 (|u0 - anchor| < uc at the start).  exact: each change at the
  // fraction of the step where it happens (the threshold crossing by
  // linear interpolation, the hop where the budget runs out, for a rate
  // that grows exponentially over the piece); else at the end of the
  // step.  Returns the number of changes written to `changes` (at most
  // MAX_CHANGES; more throws SpecError).  dt = 0: no hazard, crossings only
  int step(uint64_t tag, double u0, double u1, double d, double dt, bool exact, HopState &st,
           WellChange *changes) const;

 private:
  ThermalModel model;
  double uc = 1.0;
  uint64_t seed = 1;
  void new_life(uint64_t tag, HopState &st) const;
};

}    // namespace feq

#endif
