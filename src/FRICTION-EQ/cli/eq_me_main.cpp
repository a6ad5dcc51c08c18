/* ----------------------------------------------------------------------
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
   eq-me: command-line front end of the FRICTION-EQ master-equation solver

   eq-me threshold STYLE values [keyword values ...]

   keywords (same syntax as fix eq/contacts and the eq/me command):
     threshold uniform lo hi | gaussian mean sd | realistic xs | table file key
               (a table file is searched as named, then in $LAMMPS_POTENTIALS)
     reform    delta x0 | uniform lo hi | gaussian mean sd | none   (delta 0)
     stiffness constant | uniform lo hi | gaussian mean sd  (constant)
     dir x|y|z       accepted and ignored (as in fix eq/contacts)
     xmax X          largest slider displacement, rounded to a multiple of dx (8)
     dx h            stretch grid spacing = slider step           (1e-3)
     start relaxed|reform   Q(x;0) = delta(x) or R(x)             (relaxed)
     crossing exact|step    continuous ME, or the discrete model of
                            fix eq/contacts ... crossing step     (exact)
     richardson yes|no      combine dx and dx/2: (4 F_dx/2 - F_dx)/3
                            (yes with crossing exact, no with step)
     force FILE      table: X  F/(N kc)  sd(x)  Gamma  attached  skewness(x)
     steady FILE     table: x  Q_s(x)   (analytic stationary solution)
     snapshot X FILE table: x  Q(x;X)   (may be repeated)
     summary FILE    "name value" lines of the printed summary
     exact FILE      uniform thresholds, reform delta 0, relaxed start:
                     the exact renewal solution X <x> <x^2> Gamma (every
                     0.01 in X), and the maximum deviation of the ME from it
     substrate FILE KEYWORD uc
                     the substrate shape phi(u) = F(u)/(N kc) on [0, uc] of a
                     rigid lambda_c block, as a table for fix eq/substrate
   temperature, aging and delays (as fix eq/contacts; k_B = 1 here):
     thermal T eps_a omega   thermally activated breaking, theta = T / eps_a
     barrier p q             barrier (x_s/x_c)^p u^(3/2), prefactor u^q (0 0)
     aging none | log beta tau_a | exp beta tau_a   threshold growth with age
     delay none | fixed tau | exp tau               re-formation delay
     rest t_w                age of the contacts at X = 0
     velocity v              slider velocity (required with any of the above)
     kinetic FILE vlo vhi n  table: v  F_k  dF_k/dlnv  attached_fraction  Gamma_s
   With any of thermal (T > 0), aging, delay, rest the job is the renewal
   solution at velocity v (force: the transient from X = 0; summary:
   kinetic_force, kinetic_slope, static_peak, kstar, attached_fraction).
   See doc/src/eq_me.rst.
------------------------------------------------------------------------- */

#include "eq_me_job.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char **argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help") {
    std::cout << "usage: eq-me threshold STYLE values [keyword values ...]\n"
              << "keywords: " << feq::me_job_keywords() << "\n"
              << "threshold styles: " << feq::role_styles(feq::Role::THRESHOLD) << "\n"
              << "reform styles:    " << feq::role_styles(feq::Role::REFORM) << "\n"
              << "see doc/src/eq_me.rst\n";
    return args.empty() ? 2 : 0;
  }
  // table files: as named, else in $LAMMPS_POTENTIALS (as LAMMPS searches)
  auto load = [](const std::string &file) -> std::string {
    try {
      return feq::load_file(file);
    } catch (const feq::SpecError &) {
      const char *pot = std::getenv("LAMMPS_POTENTIALS");
      if (!pot || file.find('/') != std::string::npos) throw;
      return feq::load_file(std::string(pot) + "/" + file);
    }
  };
  try {
    const feq::MEJob job = feq::parse_me_job(args, feq::parse_number, load);
    const feq::MEReport rep = feq::run_me_job(job);
    std::fputs(rep.text.c_str(), stdout);
  } catch (const feq::SpecError &e) {
    std::cerr << "eq-me: ERROR: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
