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
   FRICTION-EQ package for LAMMPS: the paper every style of the package
   implements, registered with LAMMPS' citation mechanism (CiteMe): runs
   that use the package print it (screen, log, log.cite).  Include from
   .cpp files only.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_CITE_H
#define LMP_EQ_CITE_H

#include "citeme.h"
#include "lammps.h"

namespace LAMMPS_NS {
namespace EQCite {

  static const char PAPER[] =
      "FRICTION-EQ package (earthquake-like model of friction, master equation): "
      "https://doi.org/10.1007/s11249-012-9913-z\n\n"
      "@Article{Braun2012,\n"
      " author = {O. M. Braun and M. Peyrard and D. V. Stryzheus and E. Tosatti},\n"
      " title = {Collective Effects at Frictional Interfaces},\n"
      " journal = {Tribology Letters},\n"
      " year = 2012,\n"
      " volume = 48,\n"
      " number = 1,\n"
      " pages = {11--25},\n"
      " doi = {10.1007/s11249-012-9913-z}\n"
      "}\n\n";

  inline void add(LAMMPS *lmp)
  {
    if (lmp->citeme) lmp->citeme->add(PAPER);
  }

}    // namespace EQCite
}    // namespace LAMMPS_NS

#endif
