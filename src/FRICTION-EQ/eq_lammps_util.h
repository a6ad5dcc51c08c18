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
   FRICTION-EQ package for LAMMPS: helpers shared by the package's styles
   to feed the LAMMPS-free kernels (number parsing with LAMMPS' rules,
   table files read once and broadcast, unwrapped coordinates).
------------------------------------------------------------------------- */

#ifndef LMP_EQ_LAMMPS_UTIL_H
#define LMP_EQ_LAMMPS_UTIL_H

#include "eq_distribution.h"

#include "lmptype.h"

#include <cmath>
#include <string>

// a branch taken rarely (the slow path of a hot loop): the compiler keeps
// the loop's sums in registers and spills them around the call of the
// slow path only
// and a hint that memory at p will be read soon (nothing where unknown)
#if defined(__GNUC__)
#define FEQ_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define FEQ_PREFETCH(p) __builtin_prefetch(p)
#else
#define FEQ_UNLIKELY(x) (x)
#define FEQ_PREFETCH(p) ((void) (p))
#endif

namespace LAMMPS_NS {
class LAMMPS;
class Atom;
class Domain;

namespace EQUtil {
  // Numbers of the package's commands.  A token is a number when
  // utils::is_double() accepts it and strtod reads all of it (LAMMPS
  // 2021's is_double() only checks the characters: '1.5.2' passes it);
  // it is read with strtod, so a value
  // beyond the range of a double is +-inf in every LAMMPS version (from
  // 2026 on utils::numeric() stops with a message of its own that names
  // neither command nor keyword): the callers check the range and name
  // their keyword.
  // A non-number throws feq::SpecError("not a number").
  feq::NumberParser number_parser(LAMMPS *lmp);
  // a number for `what` (e.g. "Fix eq/contacts: kc"); a non-number stops
  // with "<what>: expected a number, got '<tok>'"
  double numeric(LAMMPS *lmp, const std::string &what, const std::string &tok);
  // an integer (utils::is_integer() form) for `what`, else the same kind of error
  bigint bnumeric(LAMMPS *lmp, const std::string &what, const std::string &tok);
  // table files: rank 0 finds the file (current folder, then LAMMPS'
  // potential search path), reads it and broadcasts its contents or the
  // error, so all ranks agree (no rank waits for another that failed)
  feq::FileLoader file_loader(LAMMPS *lmp);

  // Unwrapped coordinates along one direction: x + n L from the image
  // flags (orthogonal boxes), domain->unmap() for triclinic ones.  Made
  // where it is used (it holds the atom arrays of that moment).
  //
  // LAMMPS keeps each image count in IMGBITS bits (IMGMAX = 512 unless
  // built with -DLAMMPS_BIGBIG): after IMGMAX periodic crossings the count
  // wraps and the unwrapped coordinate along dir jumps by
  // 2 IMGMAX box lengths (the box vector along dir: also in triclinic
  // boxes, where a wrap of a perpendicular count would move it by 2 IMGMAX
  // tilts; that takes 512 box lengths of drift across dir and is not
  // undone).  What is stored as an unwrapped coordinate (a contact's
  // anchor, a block's site) then lies in the frame of the old count:
  //   - a stretch (x_u - anchor) is small: stretch() undoes the jump;
  //   - a displacement (x_u - site) grows without bound (a block that
  //     slides far): displacement() continues it from its value at the
  //     last evaluation and moves the site into the current frame.
  class Unwrap {
   public:
    Unwrap(Atom *atom, Domain *domain, int dir);
    double operator()(int i) const
    {
      if (triclinic) return unmap(i);
      return orthogonal_coordinate(i);
    }
    // operator() in an orthogonal box, with no call: for loops that keep
    // their sums in registers (orthogonal() says whether it applies)
    bool orthogonal() const { return !triclinic; }
    double orthogonal_coordinate(int i) const
    {
      const int n = int((image[i] >> bits) & IMGMASK) - IMGMAX;
      return xdir[3 * i] + n * prd;
    }
    // a stretch x_u - anchor, known to be far below IMGMAX box lengths:
    // a jump by whole wrap lengths is undone
    double stretch(double s) const
    {
      if (wrapfix && std::fabs(s) > 0.5 * wrap) s -= wrap * std::round(s / wrap);
      return s;
    }
    // stretch(s) returns s unchanged for |s| below this (infinite where
    // the coordinate has no wrap)
    double stretch_reach() const { return wrapfix ? 0.5 * wrap : HUGE_VAL; }
    // a displacement x_u - site of atom i that can grow without bound,
    // from prev, its value at the last evaluation (the atom moved by less
    // than IMGMAX box lengths since): where the image count wrapped in
    // between, site moves by the same whole wrap lengths (into the frame
    // of the current count), so that the displacement continues and every
    // later evaluation at these positions gives the same number
    double displacement(int i, double &site, double prev) const
    {
      double u = (*this)(i) - site;
      if (wrapfix && std::fabs(u - prev) > 0.5 * wrap) {
        site += wrap * std::round((u - prev) / wrap);
        u = (*this)(i) - site;
      }
      return u;
    }
   private:
    Domain *domain;
    double **x;
    const double *xdir;    // &x[0][dir]: LAMMPS' x is one block of 3 nmax doubles
    const imageint *image;
    int dir, bits;
    double prd, wrap;
    bool triclinic, wrapfix;
    double unmap(int i) const;
  };
}    // namespace EQUtil

}    // namespace LAMMPS_NS

#endif
