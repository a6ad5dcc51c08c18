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
   FRICTION-EQ: interaction kernel k(r) between contacts (LAMMPS-free).

   The elastic interaction of the EQ model (Braun et al., Secs. III-IV):
   when contacts i and j have stretches x_i and x_j, the force that decides
   whether i breaks is f_i = k_i x_i + sum_j k_ij (x_i - x_j).

   crossover:  k(r) = ftilde / r             for r <= lambda_c
               k(r) = ftilde lambda_c^2 / r^3 for r >  lambda_c
   table:      k(r, phi) = k0(r) + k2(r) cos(2 phi), phi being the angle
               between the in-plane vector r_ij and the sliding direction;
               r k0 and r k2 interpolated linearly in r, k = 0 beyond the
               last point, k = k(r_1) r_1 / r below the first.
------------------------------------------------------------------------- */

#ifndef FEQ_KERNEL_H
#define FEQ_KERNEL_H

#include <string>
#include <vector>

namespace feq {

class Kernel {
 public:
  enum Kind { NONE, CROSSOVER, TABLE };

  Kind kind = NONE;
  double ftilde = 0.0, lambda = 0.0;    // crossover
  std::vector<double> r, k0, k2;        // table (k2 empty: isotropic)
  std::string source;                   // "crossover" or "FILE KEYWORD"

  bool anisotropic() const { return kind == TABLE && !k2.empty(); }
  // largest distance with a nonzero kernel (infinite for crossover)
  double range() const;
  // k(r) at distance r > 0; cos2phi = cos(2 phi) (ignored when isotropic)
  double eval(double rr, double cos2phi = 0.0) const
  {
    if (kind == CROSSOVER) return rr <= lambda ? ftilde / rr : ftilde * lambda * lambda / (rr * rr * rr);
    return eval_table(rr, cos2phi);
  }

 private:
  double eval_table(double rr, double cos2phi) const;
};

// k = ftilde / r below lambda_c, ftilde lambda_c^2 / r^3 beyond; throws
// SpecError (eq_distribution.h) for ftilde < 0 or lambda_c <= 0
Kernel make_crossover(double ftilde, double lambda);

// Section KEYWORD of a table file (text), in the package's format:
//   KEYWORD
//   N <n> [aniso]
//   1 r_1 k0_1 [k2_1]
//   ...
// r strictly increasing and > 0.  Throws SpecError naming file and line.
Kernel read_kernel_table(const std::string &text, const std::string &path,
                         const std::string &keyword);

}    // namespace feq

#endif
