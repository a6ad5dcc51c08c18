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
   FRICTION-EQ package for LAMMPS: the per-atom bookkeeping shared by the
   package's fixes (fix eq/contacts, fix eq/substrate): a state of ncol
   doubles per atom that grows with the atom arrays, migrates with its
   atom between ranks, goes into restart files and is the fix's per-atom
   output array (the pattern of fix spring/self and fix STORE).  A new atom
   starts with a row of zeros; each fix gives that row its meaning.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_FIX_PERATOM_H
#define LMP_EQ_FIX_PERATOM_H

#include "fix.h"

#include <string>

namespace LAMMPS_NS {

class FixEQPerAtom : public Fix {
 public:
  FixEQPerAtom(class LAMMPS *, int, char **);
  ~FixEQPerAtom() override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

 protected:
  int ncol;          // doubles per atom
  double **state;    // nmax x ncol, also array_atom
  // a row restored from a restart file (finite values): what the fix
  // checks of its meaning (an error naming the atom when it is off)
  virtual void check_restored(int /*i*/) {}
  // what makes the number of values per atom differ between runs, for
  // the error when a restart file holds `stored` values ("" if nothing)
  virtual std::string layout_hint(long /*stored*/) const { return ""; }
  // a reference position (anchor, site) restored for atom i at most 1e9
  // times the scale of its coordinates away from it along dir: beyond
  // that, differences with it lose their digits (a garbled value); an
  // error names what it is
  void check_reach(int i, int dir, double ref, const char *what);
  // allocate for the current atoms, register the callbacks, set the
  // per-atom output (noutput columns, the first ones of the state) and
  // the restart/exchange flags; rows of the current atoms are zeroed
  void peratom_setup(int ncol, int noutput);

 private:
  int callbacks;
};

}    // namespace LAMMPS_NS

#endif
