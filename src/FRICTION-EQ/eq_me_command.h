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
   FRICTION-EQ package for LAMMPS: command eq/me

   eq/me threshold STYLE values [keyword values ...]

   Solves the master equation of the EQ model (paper Sec. II) with the same
   keywords as the eq-me tool, writes the requested tables, prints a
   summary and stores K* (in units of K_s), the static peak, the kinetic force, ... in
   internal-style variables (eq_me_kstar, ...) that an input script can
   use, e.g. to choose a driving spring below or above K*.
   See doc/src/eq_me.rst.
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(eq/me,EQMe);
// clang-format on
#else

#ifndef LMP_EQ_ME_COMMAND_H
#define LMP_EQ_ME_COMMAND_H

#include "command.h"

namespace LAMMPS_NS {

class EQMe : public Command {
 public:
  EQMe(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
