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
   FRICTION-EQ package for LAMMPS: how a style finds its partners
   (eq_field.h) and checks them before each use.

   A partner is found in init() (a fix by its ID, the field as the one
   pair style eq/elastic, also as a sub-style of pair hybrid) and held for
   that run as its address and its Fix/Pair instance number (instance_me,
   unique for the life of the process).  Before each use during the run
   the style finds it again and compares both: a partner removed or
   replaced meanwhile (run N pre no every M "unfix ..."), even one whose
   successor got the same address, is told apart and named in an error
   instead of being accessed.  Nothing of a held partner is read without
   that check; the next init() finds the partners afresh.
   Include from .cpp files only.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_LINK_H
#define LMP_EQ_LINK_H

#include "eq_field.h"

#include "fix.h"
#include "force.h"
#include "modify.h"
#include "pair.h"

#include <string>

namespace LAMMPS_NS {
namespace EQLink {

  // the fix with this ID as interface T; nullptr when there is none, or
  // when it is not a T (then *found is the fix, else nullptr)
  template <class T> T *fix_as(Modify *modify, const std::string &id, Fix **found = nullptr)
  {
    const int ifix = modify->find_fix(id);
    Fix *f = ifix >= 0 ? modify->fix[ifix] : nullptr;
    if (found) *found = f;
    return f ? dynamic_cast<T *>(f) : nullptr;
  }

  // the pair style eq/elastic: force->pair itself or a sub-style of pair
  // hybrid (or hybrid/overlay, hybrid/scaled); count: how many there are
  inline Pair *elastic_pair(Force *force, int &count)
  {
    count = 0;
    if (!force->pair || !force->pair_style) return nullptr;
    if (std::string(force->pair_style) == "eq/elastic") {
      count = 1;
      return force->pair;
    }
    // pair_match(word, 1, k) gives the k-th sub-style of that name, or the
    // only one whatever k is
    Pair *first = force->pair_match("eq/elastic", 1, 1);
    if (!first) return nullptr;
    count = 1;
    for (int k = 2;; ++k) {
      Pair *p = force->pair_match("eq/elastic", 1, k);
      if (!p || p == first) break;
      ++count;
    }
    return first;
  }

  // the held fix, if it is still defined and still the same instance;
  // nullptr otherwise (nothing of the held address is read before it is
  // found among the defined fixes)
  template <class T> T *live_fix(const EQHeld<T> &held, Modify *modify)
  {
    if (!held) return nullptr;
    for (int i = 0; i < modify->nfix; i++)
      if (modify->fix[i] == held.address()) return held.same(dynamic_cast<T *>(modify->fix[i]));
    return nullptr;
  }

  // the held pair style eq/elastic, if it is still the one defined
  template <class T> T *live_pair(const EQHeld<T> &held, Force *force)
  {
    if (!held) return nullptr;
    int count = 0;
    Pair *p = elastic_pair(force, count);
    return (count == 1 && p == held.address()) ? held.same(dynamic_cast<T *>(p)) : nullptr;
  }

}    // namespace EQLink
}    // namespace LAMMPS_NS

#endif
