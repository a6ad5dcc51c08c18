/* -*- c++ -*- ----------------------------------------------------------
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

 private:
  double a, b, w;
  double moment(double X, int p) const;
  double J(double y) const;
};

}    // namespace feq

#endif
