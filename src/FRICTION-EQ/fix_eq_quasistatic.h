/* -*- c++ -*- ----------------------------------------------------------
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

#include <string>

namespace LAMMPS_NS {

class FixEQQuasistatic : public Fix {
 public:
  FixEQQuasistatic(class LAMMPS *, int, char **);
  ~FixEQQuasistatic() override;
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  std::string contacts_id;
  class EQEventSource *contacts;
  double dxmax;      // largest advance per step (0: none)
  double xtotal;     // slider displacement since the fix was defined
  double dx_last;    // advance of the last step
  int idir;
  void release();
};

}    // namespace LAMMPS_NS

#endif
#endif
