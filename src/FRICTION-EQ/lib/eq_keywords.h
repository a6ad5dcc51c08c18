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
   FRICTION-EQ package: the keywords the package's commands share, parsed
   in one place (dir, crossing, start, reform_as, reverse, integrator, and
   finite numbers).  LAMMPS-free; a bad value throws SpecError with the
   message the commands print after their own name, e.g. "dir: unknown
   value 'w'; allowed: x, y, z".
------------------------------------------------------------------------- */

#ifndef FEQ_KEYWORDS_H
#define FEQ_KEYWORDS_H

#include "eq_distribution.h"

#include <cmath>
#include <string>
#include <vector>

namespace feq {

// the value of keyword kw at args[iarg] as its index in words; iarg moves on
inline int parse_choice(const std::vector<std::string> &args, size_t &iarg, const std::string &kw,
                        const std::vector<std::string> &words)
{
  std::string allowed;
  for (const auto &w : words) allowed += (allowed.empty() ? "" : ", ") + w;
  if (iarg >= args.size()) throw SpecError(kw + ": missing value; allowed: " + allowed);
  const std::string &v = args[iarg++];
  for (size_t k = 0; k < words.size(); ++k)
    if (v == words[k]) return static_cast<int>(k);
  throw SpecError(kw + ": unknown value '" + v + "'; allowed: " + allowed);
}

// the sliding direction: 0, 1, 2 for x, y, z
inline int parse_dir(const std::vector<std::string> &args, size_t &iarg)
{
  return parse_choice(args, iarg, "dir", {"x", "y", "z"});
}

// a finite number for `what` (e.g. "drive K"); iarg moves on
inline double parse_finite(const std::vector<std::string> &args, size_t &iarg,
                           const std::string &what, const NumberParser &number)
{
  if (iarg >= args.size()) throw SpecError(what + ": missing value");
  const std::string &tok = args[iarg++];
  double v;
  try {
    v = number(tok);
  } catch (const SpecError &) {
    throw SpecError(what + ": expected a number, got '" + tok + "'");
  }
  if (!std::isfinite(v)) throw SpecError(what + ": expected a finite number, got '" + tok + "'");
  return v;
}

}    // namespace feq

#endif
