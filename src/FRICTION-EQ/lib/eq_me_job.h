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
   FRICTION-EQ package: one master-equation "job" as requested by keywords.
   Shared by the eq-me command-line tool and the LAMMPS command eq/me, so
   that both accept the same syntax, write the same tables and report the
   same numbers.  LAMMPS-free.

   keywords:
     threshold uniform lo hi | gaussian mean sd | realistic xs | table file key
     reform    delta x0 | uniform lo hi | gaussian mean sd | none  (delta 0)
     stiffness constant | uniform lo hi | gaussian mean sd  (constant): F
               is reported for k_i = kc f, i.e. scaled by <f>
     dir x|y|z              accepted for symmetry with fix eq/contacts
     xmax X                 (8, rounded to a multiple of dx)
     dx h                   (1e-3)
     start relaxed|reform   (relaxed)
     crossing exact|step    (exact)
     richardson yes|no      (yes with crossing exact, no with crossing step)
     force FILE | steady FILE | snapshot X FILE | summary FILE | exact FILE
     substrate FILE KEYWORD uc   the block's substrate shape phi(u) = F(u)/(N k_c)
                            on [0, uc] as a table section for fix eq/substrate
   temperature, aging, delays (eq_thermal.h; the syntax of fix eq/contacts):
     thermal T eps_a omega  theta = k_B T / eps_a (k_B = MEJob::boltz)
     barrier p q            exponents of the barrier (0 0)
     aging none | log beta tau_a | exp beta tau_a
     delay none | fixed tau | exp tau
     rest t_w               age of the contacts at X = 0
     velocity v             slider velocity (required with any of the above)
     kinetic FILE vlo vhi n table of F_k(v) at n log-spaced velocities
   With thermal (T > 0), aging, delay or rest the job is solved by
   eq_thermal_steady (renewal equation and steady-state quadrature) at the
   velocity v; without them by the master-equation solver as before.
------------------------------------------------------------------------- */

#ifndef FEQ_ME_JOB_H
#define FEQ_ME_JOB_H

#include "eq_distribution.h"
#include "eq_master_equation.h"
#include "eq_thermal.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace feq {

struct MEJob {
  DistributionSpec threshold, reform, stiffness;
  MEOptions opt;
  bool richardson = true;    // set from "auto" after parsing
  std::string force_file, steady_file, summary_file, exact_file;
  std::string substrate_file, substrate_key;    // FK-ME substrate table
  double substrate_uc = 0.0;
  std::vector<std::pair<double, std::string>> snapshots;
  double xmax_requested = 0.0;    // before rounding to a multiple of dx

  // temperature, aging, delay: thermal.theta is set by thermal_spec()
  ThermalSpec thermal;
  double temperature = 0.0, eps_a = 1.0;
  double boltz = 1.0;       // k_B: 1 in eq-me, force->boltz in eq/me (set after parsing)
  double velocity = 0.0;    // 0: not given
  std::string kinetic_file;
  double kinetic_vlo = 0.0, kinetic_vhi = 0.0;
  int kinetic_n = 0;

  // any of thermal (T > 0), aging, delay (tau > 0), rest (t_w > 0): the
  // job is solved by the renewal equation at the velocity v
  bool thermal_on() const
  {
    return temperature > 0.0 || thermal.aging != AgingLaw::NONE ||
        (thermal.delay != DelayKind::NONE && thermal.tau > 0.0) || thermal.rest > 0.0;
  }
  // thermal with theta = boltz T / eps_a and xc = <x_s>; SpecError naming
  // thermal when theta is not finite
  ThermalSpec thermal_spec() const;
};

// Parses keyword/value pairs; throws SpecError naming the keyword.  Also
// checks the sizes of the solution (grid points, steps, exact renewal
// terms) before anything is allocated.
MEJob parse_me_job(const std::vector<std::string> &args, const NumberParser &number,
                   const FileLoader &load = {});

struct MEReport {
  std::map<std::string, double> values;    // kstar, kinetic_force, ...
  std::string text;                        // human-readable summary
};

// Solves, writes the requested files (when write_files) and returns the
// summary.  Throws SpecError on output problems (checked before solving).
MEReport run_me_job(const MEJob &job, bool write_files = true);

// Throws SpecError "<keyword>: cannot write file '...'" for the first
// output file that cannot be written; changes nothing on disk.
void check_me_outputs(const MEJob &job);

const char *me_job_keywords();

}    // namespace feq

#endif
