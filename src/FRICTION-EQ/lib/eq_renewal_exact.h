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
   FRICTION-EQ package: exact solution of the non-interacting EQ model for
   rectangular thresholds P_c = uniform [a,b] (0 < a < b), contacts
   re-forming unstretched (R = delta(0)), relaxed start.

   Each contact is a renewal process whose lifetimes (slider displacement
   between breaks) are uniform on [a,b]; S_n, the sum of n lifetimes, has
   the Irwin-Hall density.  Then, exactly,

     <x^p>(X) = X^p J(X) + sum_{n>=1} int f_n(s) (X-s)^p J(X-s) ds,
     Gamma(X) = sum_{n>=1} f_n(X),

   with J the survival function of the lifetimes.  The integrands are
   piecewise polynomials, integrated exactly (Gauss-Legendre between the
   break points).  This is the independent reference for the master-
   equation solver and the EQ simulations (paper Sec. IV: "admits an exact
   solution").  Accurate to ~1e-13 for X <= 12 (cancellation in the
   Irwin-Hall sum grows with the number of renewals).

   Cost: the sums run over n < X/a, but f_n(s) <= t^(n-1) / ((n-1)! w)
   with t = (s - n a)/w (the density of a sum of n uniforms is below that
   of the unbounded simplex): once n - 1 > t the terms fall faster than
   geometrically, and they are cut where their bound drops below 1e-20 of
   the result.  The number of terms is then ~min(X/a, e X/w + 40): small
   for a -> 0 when w is not, growing as X/a only when a and w are both
   small (terms() tells; eq-me/eq/me refuse more than EXACT_MAX_TERMS).
------------------------------------------------------------------------- */

#ifndef FEQ_RENEWAL_EXACT_H
#define FEQ_RENEWAL_EXACT_H

namespace feq {

class RenewalUniform {
 public:
  RenewalUniform(double a, double b);
  double mean_stretch(double X) const { return moment(X, 1); }    // F / (N k_c)
  double second_moment(double X) const { return moment(X, 2); }
  double rate(double X) const;                                     // Gamma(X)
  double density(int n, double s) const;                           // f_n(s)
  // number of renewal terms the sums at X use (counting stops above cap)
  long terms(double X, long cap = EXACT_MAX_TERMS) const;
  // work of mean_stretch + second_moment + rate at X, in evaluations of a
  // term of an Irwin-Hall sum (0.17-0.3 us each)
  double work(double X) const;
  // decimal digits the alternating Irwin-Hall sums lose at X (log10 of
  // their largest term); counting stops above `stop`
  double lost_digits(double X, double stop = 30.0) const;

  // limits for callers (eq-me, eq/me): renewal terms per point, and
  // digits lost (long double keeps ~19: 7 leave F(X) good to ~1e-12)
  static constexpr long EXACT_MAX_TERMS = 2000;
  static constexpr double EXACT_MAX_LOST_DIGITS = 7.0;

 private:
  double a, b, w;
  double moment(double X, int p) const;
  double J(double y) const;
};

}    // namespace feq

#endif
