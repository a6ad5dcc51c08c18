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
   FRICTION-EQ package for LAMMPS: fix eq/quasistatic (see the header)
------------------------------------------------------------------------- */

#include "fix_eq_quasistatic.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "group.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include "eq_cite.h"
#include "eq_lammps_util.h"
#include "eq_link.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
// relative tolerance of the breaking test while driving quasi-statically:
// the contact that sets the advance reaches its threshold up to rounding
constexpr double QS_TOLERANCE = 1.0e-13;
}    // namespace

FixEQQuasistatic::FixEQQuasistatic(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dxmax(0.0), xtotal(0.0), dx_last(0.0), idir(0)
{
  EQCite::add(lmp);
  name = fmt::format("fix {} eq/quasistatic", id);
  if (group->dynamic[igroup])
    error->all(FLERR, "Fix eq/quasistatic: group {} is dynamic; allowed: a static group",
               group->names[igroup]);
  if (narg < 4)
    error->all(FLERR, "Illegal fix eq/quasistatic command: expected 'fix ID group eq/quasistatic "
                      "contacts-ID [max dX]'");
  contacts_id = arg[3];
  int iarg = 4;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "max") == 0) {
      if (iarg + 1 >= narg) error->all(FLERR, "Fix eq/quasistatic max: missing value (a distance > 0)");
      dxmax = EQUtil::numeric(lmp, "Fix eq/quasistatic max", arg[iarg + 1]);
      if (!(dxmax > 0.0) || !std::isfinite(dxmax))
        error->all(FLERR, "Fix eq/quasistatic max: value must be finite and > 0 (got {})",
                   arg[iarg + 1]);
      iarg += 2;
    } else
      error->all(FLERR, "Fix eq/quasistatic: unknown keyword '{}'; allowed: max", arg[iarg]);
  }

  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
  time_integrate = 1;
  restart_global = 1;
}

int FixEQQuasistatic::setmask()
{
  return INITIAL_INTEGRATE;
}

double FixEQQuasistatic::driver_tolerance() const
{
  return QS_TOLERANCE;
}

void FixEQQuasistatic::init()
{
  contacts.clear();
  Fix *found = nullptr;
  EQEventSource *source = EQLink::fix_as<EQEventSource>(modify, contacts_id, &found);
  if (!found)
    error->all(FLERR, "Fix {} eq/quasistatic: fix ID {} does not exist; expected the ID of a fix "
                      "eq/contacts", id, contacts_id);
  if (!source)
    error->all(FLERR, "Fix {} eq/quasistatic: fix {} is a fix {}, not eq/contacts", id,
               contacts_id, found->style);
  contacts.set(source, found);
  contacts_label = source->eq_name();
  idir = source->event_dir();

  // the advance to the next break assumes that every contact moves with
  // the slider (then the field only changes by breaks)
  const int *mask = atom->mask;
  bigint missing = 0;
  const int cbit = source->event_groupbit();
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & cbit) && !(mask[i] & groupbit)) ++missing;
  bigint all = 0;
  MPI_Allreduce(&missing, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all > 0)
    error->all(FLERR, "Fix eq/quasistatic: group {} leaves {} contacts of fix {} (group {}) "
                      "behind; the advance to the next break assumes that every contact moves "
                      "with the slider: use a group that contains group {}",
               group->names[igroup], all, contacts_id, group->names[found->igroup],
               group->names[found->igroup]);
  if (!utils::strmatch(update->integrate_style, "^verlet"))
    error->all(FLERR, "Fix eq/quasistatic requires run_style verlet");
  check_integrators();
}

/* ----------------------------------------------------------------------
   this fix sets the slider's positions: no other fix may move its atoms
   (fix move, nve, rigid, ...: the advance to the next break would be off
   by their motion)
------------------------------------------------------------------------- */

void FixEQQuasistatic::check_integrators()
{
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int k = 0; k < modify->nfix; k++) {
    Fix *other = modify->fix[k];
    if (other == this || !other->time_integrate) continue;
    bigint shared = 0, all = 0;
    for (int i = 0; i < nlocal; i++)
      if ((mask[i] & groupbit) && (mask[i] & other->groupbit)) ++shared;
    MPI_Allreduce(&shared, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (all > 0)
      error->all(FLERR, "Fix {} eq/quasistatic and fix {} {} both move {} atoms: fix "
                        "eq/quasistatic advances the slider exactly to the next break and must be "
                        "the only fix that moves its atoms; unfix one of them", id, other->id,
                 other->style, all);
  }
}

// the contacts of this run, if they are still the fix found at init
EQEventSource *FixEQQuasistatic::contacts_now()
{
  EQEventSource *c = EQLink::live_fix(contacts, modify);
  if (!contacts)
    error->all(FLERR, "Fix {} eq/quasistatic was defined during a run (run N pre no every M) and "
                      "not set up with its fix eq/contacts {}: use pre yes", id, contacts_id);
  if (!c)
    error->all(FLERR, "Fix {} eq/quasistatic: {}, the contacts it drives, was removed or replaced "
                      "during the run (e.g. unfix in run N pre no every M); use pre yes, or define "
                      "the fixes anew between runs", id, contacts_label);
  return c;
}

/* ----------------------------------------------------------------------
   advance to the next event (the state is that after the last step's
   breaks and avalanches)
------------------------------------------------------------------------- */

void FixEQQuasistatic::initial_integrate(int /*vflag*/)
{
  double dx = contacts_now()->next_event();
  if (!std::isfinite(dx)) {
    if (dxmax > 0.0) dx = dxmax;
    else
      error->all(FLERR, "Fix eq/quasistatic: no attached contact left in fix {}; nothing can "
                        "break (use the max keyword to keep driving)", contacts_id);
  }
  if (dxmax > 0.0 && dx > dxmax) dx = dxmax;
  double **x = atom->x;
  double **v = atom->v;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int d = idir;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) {
      x[i][d] += dx;
      v[i][0] = v[i][1] = v[i][2] = 0.0;
    }
  xtotal += dx;
  dx_last = dx;
}

double FixEQQuasistatic::compute_scalar()
{
  return xtotal;
}

double FixEQQuasistatic::compute_vector(int n)
{
  return n == 0 ? xtotal : dx_last;
}

void FixEQQuasistatic::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    int size = sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(&xtotal, sizeof(double), 1, fp);
  }
}

void FixEQQuasistatic::restart(char *buf)
{
  xtotal = reinterpret_cast<double *>(buf)[0];
}
