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
   FRICTION-EQ package: one lambda_c-block of the far zone (paper Sec.
   "Far zone: Meso/macroscale friction", Eqs. crack.eq03x-crack.eq07, and
   "Elastic screening length", Eqs. scr.eq01-scr.eq05).

   Block n carries the distribution Q_n(u; X_n) of the stretchings of its
   N_lambda contacts; it obeys the master equation as the block moves,

     [d/dX + d/du + P_eps(u)] Q(u;X) = R(u) Gamma(X),
     Gamma(X) = int P_eps(u) Q(u;X) du,
     F_n = N_lambda k_c int u Q(u;X) du                       (crack.eq07)

   and the fix applies -F_n to the block.  This kernel advances Q of one
   block over an arbitrary displacement increment (usually small and
   positive, sometimes zero or negative).  The class MesoModel is
   immutable and shared by all blocks of a fix; the state of a block is a
   flat, position-independent array of width() doubles (it migrates
   between MPI ranks and goes into restart files: it may be memcpy'd).

   Physics conventions
   -------------------
   * Breaking (EQ model): a contact breaks when its stretch u reaches its
     threshold x_s ~ P_c; it re-forms at once with a stretch r ~ R, and its
     new threshold is drawn above |r| (as fix eq/contacts does).  R null
     ("reform none"): broken contacts are detached for good.
   * Memory: a contact cannot break below the largest stretch it has seen
     (its threshold is conditioned above it).  Breaking is one-sided, as in
     the master equation (thresholds are positive, P(u) = 0 for u <= 0):
     a backward move breaks nothing.  NOTE: fix eq/contacts breaks on
     |u| >= x_s.  The two agree while no backward excursion drives a
     contact to u <= -x_s; e.g. for realistic thresholds and excursions of
     0.6-0.8 x_c, 2-3% of the contacts break on the negative side in
     eq/contacts and <u> differs by up to 0.01.
   * Screening (scr.eq01-scr.eq05): forces in the block are scaled by
     (1 + eps), i.e. thresholds effectively by 1/(1 + eps), eps >= 0.  The
     breaking rate is (1+eps) P((1+eps) u), P = P_c/J_c, J_c = 1 - cdf of
     P_c: over a move from stretch s0 to s1 (beyond the largest stretch
     seen) a contact survives with J_c((1+eps) s1) / J_c((1+eps) s0).  The
     paper writes P((1+eps) u) without the Jacobian (1+eps); with it, the
     steady state for R = delta(0) is exactly the paper's Gamma =
     (1+eps)/<x_s>, and constant eps is exactly the plain model with
     thresholds x_s/(1+eps).  eps is frozen within one call; with eps
     varying from call to call the kernel integrates the master equation
     with the rate (1+eps(X)) P((1+eps(X)) u) exactly (piecewise constant
     in X): like the ME, a change of eps at fixed X breaks nothing (a
     threshold picture, (1+eps) k u >= k x_s, would break contacts when eps
     jumps up).

   Scheme
   ------
   Contacts are stored by their ANCHOR A = X - u (the block displacement
   at which the contact would be unstretched), on the grid A_j = j du.
   Anchors do not move when the block moves, so transport is exact for
   any increment.  Let H = max X so far (high-water mark).  Re-formations
   happen only at a new running maximum, so every contact at anchor A has
   seen exactly the largest stretch H - A (contacts re-formed with r < 0
   are "held", below), and its threshold is conditioned above it.  Hence:
   * a move to X1 <= H breaks nothing: O(1), only X changes;
   * a move beyond H is split at the grid points p_g = g du into
     sub-steps [s0, s1] inside one grid cell; in each, the mass at anchor
     A_j survives with the exact ratio J((1+eps)(X1-A_j))/J((1+eps)(H-A_j))
     and the broken mass B, with the exact mean remaining displacement
     rho = sum_j m_j int_{s0}^{s1} (1 - J(s)/J(s0)) ds / B after the break,
     re-forms at the anchor (X1 - rho) - r_k for every grid value r_k = k du
     of R (R laid on the grid with hat weights w_k: mass and mean exact),
     spread over the two neighbouring anchors with hat weights (mass and
     mean anchor exact).  Re-formed contacts whose threshold lies within
     the rest of the sub-step break again (fraction 1 - J(r_k+rho)/J(r_k));
     that mass re-forms once more, at remaining displacement 2 rho/3 (the
     exact value for breaks spread evenly over the sub-step).  Probability
     is conserved by construction (broken = re-injected).  With dX = du
     and no re-breaks this is the master-equation solver's scheme (same
     results to rounding).  Crossing STEP: every break of a move re-forms
     at its end X1 with stretch r (rho = 0, no re-breaks), the
     cellular-automaton convention of fix eq/contacts.
   * Held contacts: a contact re-formed with r < 0 at X_b has its threshold
     above |r|: it cannot break before its stretch reaches |r|, i.e. before
     H reaches A + |r| = X_b + 2|r|, where its conditioning (threshold >
     |r| = H - A) equals that of the grid mass at A; there it merges into
     the grid.  Until then it contributes the force k (X - A).  All held
     lines k < 0 share the same per-cell re-injection (the hat split does
     not depend on k), so they are stored as one record (lower, upper
     mass) per grid cell of the last 2K+2 cells (K = max |k|): O(K)
     memory instead of O(K^2), O(#held lines) work per grid crossing.
     Every r_k < 0 is held (for |r_k| below all thresholds this changes
     nothing), so the result does not depend on eps.
   * X and the anchors are stored relative to an integer base index that
     is moved every REBASE = 1024 cells (X - base du exactly by fma), so
     nothing loses precision at X ~ 1e7 beyond the rounding of X itself.
     Running sums (mass, mass * anchor index) give the mean stretch in
     O(1); they are recomputed from the arrays at each rebase.
   * J_c and its integral are tabulated on the effective stretch y =
     (1+eps) u with spacing du/4 (cubic through 4 exact values per
     interval, exact integral of the cubic; intervals with a kink of P_c
     strictly inside fall back to the exact functions).  Table error
     ~ (du/12)^4 max|d4 J/dy4| / 24: measured 2.5e-13 (realistic 1),
     6.9e-12 (gaussian 1 0.2), 3e-16 (uniform) at du = 0.01, far below
     the scheme's O(du^2).

   Memory per block: width() = 16 + (nt + 4) + 2 (2K + 2) doubles (the
   last term only when R has negative support), nt = max(ceil(top/du),
   k_max + 1), top = upper end of P_c (isf(1e-17) when unbounded: 6.56
   for realistic 1), k_max du and -K du the largest and smallest grid
   values of R (R cut at its 1e-17 quantiles, as in the ME solver).
   E.g. du = 0.01: uniform [0.75,1.25] with R = delta(0) 145; realistic 1
   with delta(0) 676, with uniform(-0.3,0.2) 800, with gaussian(0.05,0.1)
   1000 doubles.
   Cost of a move beyond H: per sub-step one pass over the anchors that
   can break (two table lookups and one division each) plus O(#grid
   values of R); moves at or below H: O(1).

   Accuracy (measured, see test_eq_meso.cpp): second order in du for any
   increments.  Thresholds uniform [0.75,1.25], R = delta(0), relaxed
   start, rigid motion with increments 0.37 du, max over all X reached in
   [0, 8] of |F - F_exact| / (N_lambda k_c) (RenewalUniform):
       du = 0.02    3.04e-4   (0.761 du^2)
       du = 0.01    7.80e-5   (0.780 du^2)
       du = 0.005   1.96e-5   (0.783 du^2)
   (increments 3.3 du: 2.8e-4, 6.9e-5, 1.8e-5; with dX = du it equals the
   ME solver to 2e-14).
   Cost per block-move, du = 0.01, increments 0.37 du, g++ -O2, one core
   of a shared 2-core AMD EPYC VM under load (timings +-20%):
       uniform [0.75,1.25], R = delta(0):      ~1.0 us  (~68 anchor updates)
       realistic 1, R = delta(0):              ~12 us   (~900 anchor updates)
       realistic 1, R = gaussian(0.05,0.1):    ~15 us
       uniform, R = gaussian(0.05,0.1):        ~2.3 us
       a move at or below H (incl. mean_stretch): ~6 ns
   The cost of a forward move grows as 1/du (anchors per pass).

   Grid validation ('grid' keyword): du <= MESO_GRID_SD_FRACTION * sd(P_c)
   with MESO_GRID_SD_FRACTION = 0.25.  Measured relative error of F (max over
   X in [0, 8 <x_s>], vs the ME at dx = sd/200) is 0.02 (du/sd)^2 for
   R = delta(0) (uniform, gaussian and realistic thresholds alike) and
   0.04 (du/sd)^2 with re-breaks (realistic, R = gaussian(0.05,0.1)):
   at the limit 1.1e-3 ... 2.7e-3; beyond it the threshold distribution
   is resolved by fewer than 4 cells per sd.  And width() <= MESO_MAX_WIDTH =
   65536 doubles (512 KiB per block).
------------------------------------------------------------------------- */

#ifndef FEQ_MESO_H
#define FEQ_MESO_H

#include "eq_distribution.h"
#include "eq_master_equation.h"    // Crossing, MEStart

#include <memory>
#include <utility>
#include <vector>

namespace feq {

// grid validation: du <= MESO_GRID_SD_FRACTION * sd(P_c), width() <=
// MESO_MAX_WIDTH doubles (see the header comment)
constexpr double MESO_GRID_SD_FRACTION = 0.25;
constexpr int MESO_MAX_WIDTH = 65536;

// The default grid: MESO_GRID_DEFAULT_SD standard deviations of the
// thresholds that matter.  With screening the forces are scaled by
// 1 + eps, in the steady state of a lattice by 1 + eps0 = 1/(1 - Pi0)
// (Pi0 = sum_m Pi_mn), so the thresholds that matter are x_s (1 - Pi0),
// and so is their standard deviation: meso_default_grid(Pc, Pi0) =
// MESO_GRID_DEFAULT_SD sd(P_c) (1 - Pi0), the same number of cells per
// screened standard deviation (8) as the unscreened default has per
// standard deviation.  0 for thresholds of zero width; throws
// std::invalid_argument unless 0 <= pi0 < 1.  Measured (fix eq/meso,
// examples/bench/README.md): chain and square lattice, uniform
// thresholds, Pi0 = 0.93 and 0.97, after 600 x_c: error of the steady
// eps 1.1e-6 ... 2.5e-6 on this grid, 4e-4 ... 1.7e-3 on sd/8 of the
// unscreened thresholds; the cost per unit of sliding grows as
// 1/(1 - Pi0).
constexpr double MESO_GRID_DEFAULT_SD = 0.125;
double meso_default_grid(const Distribution &Pc, double pi0 = 0.0);

// The smallest safe rate window of screened blocks (fix eq/meso keyword
// 'window'), MESO_WINDOW_COEFF <x_s> (<x_s>/sd)^2.  The screening feeds
// the windowed breaking rate back into the breaking: for a window below
// a critical one the steady state of a screened lattice is unstable and
// the blocks break in synchronized bursts instead (eps far from the
// steady value, relaxation oscillations).  The critical window is a
// property of the (continuous) model, not of the time step or the grid:
// measured on a chain with a pinned block, steps of x_c/211 and grids of
// 4 cells per screened sd, Pi0 = 0.05 ... 0.97, it is at most
// 0.4-0.5 x_c for uniform [0.75, 1.25] x_c (sd/x_c = 0.144), 0.5-1 x_c
// for gaussian sd/x_c = 0.1 and 0.05-0.2 x_c for gaussian sd/x_c = 0.25,
// i.e. 0.0083-0.01 x_c (x_c/sd)^2; larger steps are more stable.  The
// coefficient 0.015 leaves a margin of 1.45 or more over the unstable
// windows measured.
constexpr double MESO_WINDOW_COEFF = 0.015;
double meso_min_window(const Distribution &Pc);

// the grid spacing du is unusable for the thresholds (its message starts
// with "grid:"); fix eq/meso names its default grid as the cause when the
// user did not set one
class GridError : public SpecError {
 public:
  using SpecError::SpecError;
};

class MesoModel {
 public:
  // Pc: breaking thresholds; R: re-forming stretches (nullptr: contacts
  // never re-form); du: anchor grid spacing (keyword 'grid').
  // Throws GridError for a coarse or absurdly fine grid (and for
  // thresholds of zero width), SpecError for a missing or negative
  // threshold distribution, for re-forming stretches beyond the
  // thresholds, and for start REFORM without R.
  MesoModel(DistributionPtr Pc, DistributionPtr R, double du,
            Crossing crossing = Crossing::EXACT, MEStart start = MEStart::RELAXED);

  // largest du accepted for thresholds Pc; smallest du for which width()
  // stays below MESO_MAX_WIDTH
  static double max_grid(const Distribution &Pc);
  double min_grid() const;
  // the same model (thresholds, R, crossing, start) on the grid du: a
  // block's state of one grid is not a state of the other (init() a fresh
  // block on it); throws as the constructor
  std::unique_ptr<MesoModel> regrid(double du) const;

  int width() const { return nwidth; }    // doubles per block state

  // fresh block at displacement X0: Q = delta(0) (RELAXED) or R (REFORM)
  void init(double *state, double X0) const;
  // move the block from its stored X to X1 with screening factor eps
  // (>= 0); returns the probability mass broken in this move (broken
  // contacts per contact).  X1 == stored X: returns 0 and leaves the state
  // untouched bitwise (rate() keeps describing the last move that
  // changed X).  Throws std::invalid_argument for a non-finite X1 or
  // eps < 0 (errors of the caller, not of the input).
  double advance(double *state, double X1, double eps = 0.0) const;

  // observables, all O(1) except where noted
  double position(const double *state) const;        // X
  double high_water(const double *state) const;      // H = max X so far
  double mean_stretch(const double *state) const;    // int u Q du = F/(N_lambda k_c)
  double attached(const double *state) const;        // int Q du (grid + held)
  double held(const double *state) const;            // held part of attached()
  double detached(const double *state) const;        // broken for good (R null)
  double rate(const double *state) const;            // Gamma = broken / |dX| of the last move
                                                     // (0 after a move that stays below H)
  // |attached + detached - 1| summed from the arrays, O(width)
  double normalization_error(const double *state) const;
  // false when the state was not made by init() of a model of this shape
  bool valid(const double *state) const;
  // Q(u) on the anchor grid: u ascending, q = probability / du (held
  // contacts included), O(width + K * #held lines)
  void density(const double *state, std::vector<double> &u, std::vector<double> &q) const;

  // model information
  double grid() const { return du; }
  double top() const { return ytop; }    // stretch beyond which J_c = 0
  int anchors() const { return ncap; }   // main ring capacity
  int held_span() const { return kheld; }    // K (0: no held contacts)
  // tabulated J_c(y) (exposed for tests)
  double survival(double y) const;

 private:
  DistributionPtr Pc, R;
  double du, inv_du;
  Crossing crossing;
  MEStart start;
  double ylow, ytop;    // J = 1 for y <= ylow, 0 for y >= ytop
  double rsup_lo, rsup_hi;    // support of R (0 when R null)
  long nt;              // anchors with stretch >= nt du (at the cell start) are broken
  int ncap;             // main ring capacity
  int kheld;            // K
  int nrec;             // record ring capacity (2K + 2, or 0)
  int nwidth;
  double inv_ncap, inv_nrec;
  double tag;

  struct Line {
    long k;       // r = k du
    double w;     // weight (sum 1)
  };
  std::vector<Line> lines;    // r >= 0: re-form onto the grid
  std::vector<Line> hlines;   // r < 0: held
  double hold_w = 0.0, hold_wc = 0.0;    // sum w, sum w |k| of held lines

  // table of J (and its integral G, G(0) = 0) on y_i = i dy
  double dy, inv_dy, gtop;
  long ntab;
  std::vector<double> tab;            // 9 per interval: J cubic (4), G quartic (5)
  std::vector<unsigned char> exact;   // 1: a kink of P_c inside the interval

  void lookup(double y, double &J, double &G) const;
  double J(double y) const;
  double width_bound(double d) const;

  // construction steps
  void check_inputs() const;
  void set_reform_support();
  std::vector<std::pair<long, double>> reform_weights() const;
  void set_reform_lines();
  void set_state_layout();
  void set_survival_table();

  // state helpers
  double forward(double *s, double X1, double eps) const;
  void pass(double *s, long g, long base, double hr, double end, double a, double &B,
            double &W) const;
  double reinject(double *s, long g, long base, double end, double rho, double B, double a) const;
  void extend(double *s, long lo, long hi) const;
  void add_main(double *s, long j, long base, double v) const;
  void add_record(double *s, long g, long base, double lo, double up) const;
  void cross(double *s, long G, long base) const;
  void rebase(double *s) const;
  double held_mass(const double *s, double *s1, long base) const;
};

}    // namespace feq

#endif
