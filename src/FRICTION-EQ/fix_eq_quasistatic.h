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
   FRICTION-EQ package for LAMMPS: fix eq/quasistatic

   fix ID group eq/quasistatic contacts-ID [max dX]

   Quasi-static (adiabatic) driving of a rigid slider: each time step
   moves the atoms of the group along the sliding direction of fix
   eq/contacts exactly to the next breaking event (the global minimum over
   contacts and ranks of the advance that brings a contact's force to its
   threshold), so F(X) carries no step error and every step is an event.
   See doc/src/fix_eq_quasistatic.rst.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(eq/quasistatic,FixEQQuasistatic);
// clang-format on
#else

#ifndef LMP_FIX_EQ_QUASISTATIC_H
#define LMP_FIX_EQ_QUASISTATIC_H

#include "fix.h"

#include "eq_field.h"

#include <string>

namespace LAMMPS_NS {

class FixEQQuasistatic : public Fix, public EQEventDriver {
 public:
  FixEQQuasistatic(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // EQEventDriver: the contacts' breaking test lands exactly on the event
  const char *eq_name() const override { return name.c_str(); }
  int eq_instance() const override { return instance_me; }
  const char *driver_target() const override { return contacts_id.c_str(); }
  double driver_tolerance() const override;

 private:
  std::string name;           // "fix ID eq/quasistatic"
  std::string contacts_id;
  std::string contacts_label;        // "fix ID eq/contacts", for messages after it is gone
  EQHeld<EQEventSource> contacts;    // the event source of this run
  double dxmax;      // largest advance per step (0: none)
  double xtotal;     // slider displacement since the fix was defined
  double dx_last;    // advance of the last step
  int idir;
  EQEventSource *contacts_now();
  void check_integrators();
};

}    // namespace LAMMPS_NS

#endif
#endif
