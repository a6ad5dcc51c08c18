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
   FRICTION-EQ package: numbers in the kernels' messages (LAMMPS-free).
------------------------------------------------------------------------- */

#ifndef FEQ_TEXT_H
#define FEQ_TEXT_H

#include <sstream>
#include <string>

namespace feq {

// v with `digits` significant digits (ostream's default float format)
inline std::string format_number(double v, int digits)
{
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}    // namespace feq

#endif
