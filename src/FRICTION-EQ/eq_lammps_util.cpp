/* ----------------------------------------------------------------------
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
   FRICTION-EQ package for LAMMPS: shared helpers (see eq_lammps_util.h)
------------------------------------------------------------------------- */

#include "eq_lammps_util.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "lammps.h"
#include "pointers.h"
#include "utils.h"

#include <cerrno>
#include <cstdlib>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;

namespace {
double read_double(const std::string &tok)
{
  if (!utils::is_double(tok)) throw feq::SpecError("not a number");
  // LAMMPS 2021's is_double() checks the characters only ('1.5.2', '1e',
  // '+' pass): strtod must also consume the whole token
  char *end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);    // +-inf beyond the range
  if (end == tok.c_str() || *end != '\0') throw feq::SpecError("not a number");
  return v;
}
}    // namespace

feq::NumberParser EQUtil::number_parser(LAMMPS * /*lmp*/)
{
  return read_double;
}

double EQUtil::numeric(LAMMPS *lmp, const std::string &what, const std::string &tok)
{
  try {
    return read_double(tok);
  } catch (const feq::SpecError &) {
    lmp->error->all(FLERR, "{}: expected a number, got '{}'", what, tok);
  }
  return 0.0;
}

bigint EQUtil::bnumeric(LAMMPS *lmp, const std::string &what, const std::string &tok)
{
  if (!utils::is_integer(tok)) lmp->error->all(FLERR, "{}: expected an integer, got '{}'", what, tok);
  // 2021's is_integer() checks the characters only ('1-2', '+' pass)
  errno = 0;
  char *end = nullptr;
  const long long v = std::strtoll(tok.c_str(), &end, 10);
  if (end == tok.c_str() || *end != '\0')
    lmp->error->all(FLERR, "{}: expected an integer, got '{}'", what, tok);
  if (errno == ERANGE || v > static_cast<long long>(MAXBIGINT) ||
      v < -static_cast<long long>(MAXBIGINT))
    lmp->error->all(FLERR, "{}: integer {} is out of range", what, tok);
  return static_cast<bigint>(v);
}

namespace {
void bcast_string(std::string &s, MPI_Comm world)
{
  long n = static_cast<long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG, 0, world);
  s.resize(n);
  if (n > 0) MPI_Bcast(&s[0], static_cast<int>(n), MPI_CHAR, 0, world);
}
}    // namespace

feq::FileLoader EQUtil::file_loader(LAMMPS *lmp)
{
  return [lmp](const std::string &file) -> std::string {
    int me;
    MPI_Comm_rank(lmp->world, &me);
    std::string text, err;
    int ok = 1;
    if (me == 0) {
      const std::string path = utils::get_potential_file_path(file);
      try {
        // not found: the name as given, for the system's reason (no such
        // file, no permission, a directory)
        text = feq::load_file(path.empty() ? file : path);
      } catch (const feq::SpecError &e) {
        ok = 0;
        err = e.what();
      }
    }
    MPI_Bcast(&ok, 1, MPI_INT, 0, lmp->world);
    if (!ok) {
      bcast_string(err, lmp->world);
      throw feq::SpecError(err);
    }
    bcast_string(text, lmp->world);
    return text;
  };
}

/* ---------------------------------------------------------------------- */

EQUtil::Unwrap::Unwrap(Atom *atom, Domain *domain_, int dir_) :
    domain(domain_), x(atom->x), xdir(atom->x ? atom->x[0] + dir_ : nullptr), image(atom->image),
    dir(dir_)
{
  bits = dir == 0 ? 0 : (dir == 1 ? IMGBITS : IMG2BITS);
  prd = domain->prd[dir];
  triclinic = domain->triclinic != 0;
  // the box vector along dir has length prd[dir] in triclinic boxes too
  // (h[dir]): a wrap of the image count along dir moves the unwrapped
  // coordinate by 2 IMGMAX prd[dir] either way
  wrapfix = domain->periodicity[dir] != 0;
  wrap = 2.0 * IMGMAX * prd;
}

double EQUtil::Unwrap::unmap(int i) const
{
  double u[3];
  domain->unmap(x[i], image[i], u);
  return u[dir];
}
