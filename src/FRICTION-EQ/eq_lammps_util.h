/* -*- c++ -*- ----------------------------------------------------------
   FRICTION-EQ package for LAMMPS: helpers shared by the package's styles
   to feed the LAMMPS-free kernels (number parsing with LAMMPS' rules,
   table files read once and broadcast).
------------------------------------------------------------------------- */

#ifndef LMP_EQ_LAMMPS_UTIL_H
#define LMP_EQ_LAMMPS_UTIL_H

#include "eq_distribution.h"

namespace LAMMPS_NS {
class LAMMPS;

namespace EQUtil {
  // numbers as utils::numeric reads them; a non-number throws feq::SpecError
  // so that the message can name the keyword
  feq::NumberParser number_parser(LAMMPS *lmp);
  // table files: rank 0 finds the file (current folder, then LAMMPS'
  // potential search path), reads it and broadcasts its contents or the
  // error, so all ranks agree (no rank waits for another that failed)
  feq::FileLoader file_loader(LAMMPS *lmp);
}    // namespace EQUtil

}    // namespace LAMMPS_NS

#endif
