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
------------------------------------------------------------------------- */

#ifndef FEQ_ME_JOB_H
#define FEQ_ME_JOB_H

#include "eq_distribution.h"
#include "eq_master_equation.h"

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
