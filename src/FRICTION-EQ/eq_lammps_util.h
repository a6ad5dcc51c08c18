/* -*- c++ -*- ----------------------------------------------------------
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
  class Unwrap {
   public:
    Unwrap(Atom *atom, Domain *domain, int dir);
    double operator()(int i) const
    {
      if (triclinic) return unmap(i);
      const int n = int((image[i] >> bits) & IMGMASK) - IMGMAX;
      return x[i][dir] + n * prd;
    }
    // a difference of unwrapped coordinates (a stretch, a displacement):
    // LAMMPS keeps the image count in IMGBITS bits, after IMGMAX periodic
    // crossings it wraps and the unwrapped coordinate jumps by 2 IMGMAX
    // box lengths; no such difference can be that large: undo the jump
    double fix(double s) const
    {
      if (wrapfix && std::fabs(s) > 0.5 * wrap) s -= wrap * std::round(s / wrap);
      return s;
    }

   private:
    Domain *domain;
    double **x;
    const imageint *image;
    int dir, bits;
    double prd, wrap;
    bool triclinic, wrapfix;
    double unmap(int i) const;
  };
}    // namespace EQUtil

}    // namespace LAMMPS_NS

#endif
