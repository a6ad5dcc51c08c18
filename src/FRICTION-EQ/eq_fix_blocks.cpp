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
   FRICTION-EQ package for LAMMPS: the package's block fixes' shared part
   (see eq_fix_blocks.h)
------------------------------------------------------------------------- */

#include "eq_fix_blocks.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "pair.h"
#include "respa.h"
#include "update.h"
#include "utils.h"

#include "eq_cite.h"
#include "eq_distribution.h"
#include "eq_keywords.h"
#include "eq_lammps_util.h"
#include "eq_link.h"
#include "eq_record_lammps.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;

namespace {
// the largest driving force, and its largest rate of growth (per time unit)
constexpr double DRIVE_MAX = 1e300;
}    // namespace

FixEQBlocks::FixEQBlocks(LAMMPS *lmp, int narg, char **arg) :
    FixEQPerAtom(lmp, narg, arg), idir(0), sitecol(0), dispcol(0), flagcol(0), ilevel_respa(0), nlevels_respa(0),
    drive_flag(0), kdrive(0.0), vstage(0.0), stage(0.0), nevaluation(0)
{
  EQCite::add(lmp);
  name = fmt::format("fix {} {}", id, style);
}

bool FixEQBlocks::parse_block_keyword(const std::string &kw, const std::vector<std::string> &args,
                                      size_t &iarg, const feq::NumberParser &number,
                                      double &stage0)
{
  if (kw == "dir") {
    idir = feq::parse_dir(args, iarg);
    return true;
  }
  if (kw == "drive") {
    kdrive = feq::parse_finite(args, iarg, "drive K", number);
    vstage = feq::parse_finite(args, iarg, "drive v", number);
    if (!(kdrive > 0.0)) throw feq::SpecError("drive: K must be > 0 (got " + args[iarg - 2] + ")");
    check_drive_rate(kdrive, vstage, "drive");
    drive_flag = 1;
    return true;
  }
  if (kw == "stage") {
    stage0 = feq::parse_finite(args, iarg, "stage X0", number);
    return true;
  }
  return false;
}

// the driving force grows at K v: that product of finite numbers must be
// finite (at most 1e300 force per time unit)
void FixEQBlocks::check_drive_rate(double k, double v, const char *what)
{
  if (!(k * std::fabs(v) <= DRIVE_MAX))
    throw feq::SpecError(fmt::format("{}: K = {} and v = {} make the driving force grow at K |v| = "
                                     "{:.6g} per time unit, beyond {:g}: lower K or v", what, k, v,
                                     k * std::fabs(v), DRIVE_MAX));
}

// the driving force K (X_s - X) of a block at its site must be finite
void FixEQBlocks::check_stage(double stage0)
{
  if (drive_flag && !(kdrive * std::fabs(stage0) <= DRIVE_MAX))
    error->all(FLERR, "Fix {} {} stage: X0 = {} with drive K = {} gives a driving force K X0 = "
                      "{:.6g} beyond {:g}: lower K or X0", id, style, stage0, kdrive,
               kdrive * std::fabs(stage0), DRIVE_MAX);
}

void FixEQBlocks::init_blocks()
{
  const bool respa = utils::strmatch(update->integrate_style, "^respa");
  if (respa) {
    nlevels_respa = static_cast<Respa *>(update->integrate)->nlevels;
    ilevel_respa = nlevels_respa - 1;
    if (respa_level >= 0) ilevel_respa = MIN(respa_level, ilevel_respa);
  }
  // the elastic field that couples the blocks this run (its init_style()
  // ran before and found its source)
  field.clear();
  int count = 0;
  Pair *pair = EQLink::elastic_pair(force, count);
  auto *elastic = pair ? dynamic_cast<EQElasticField *>(pair) : nullptr;
  if (elastic && count == 1 && elastic->field_source_instance() == instance_me)
    field.set(elastic, pair);
  if (field && respa && static_cast<Respa *>(update->integrate)->level_pair < 0)
    error->all(FLERR, "Fix {}: pair eq/elastic must be computed at one r-RESPA level "
                      "(run_style respa ... pair N); inner/middle/outer levels are not allowed",
               style);
}

const double *FixEQBlocks::field_h()
{
  if (!field) return nullptr;
  EQElasticField *f = EQLink::live_pair(field, force);
  if (!f)
    error->all(FLERR, "Fix {} {}: pair style eq/elastic, the field of its blocks at the start of "
                      "the run, was removed or replaced during the run (e.g. pair_style in run N "
                      "pre no every M); use pre yes", id, style);
  return f->field_view().h;
}

/* ----------------------------------------------------------------------
   displacements (blocks seen for the first time are set up)
------------------------------------------------------------------------- */

void FixEQBlocks::displacements(double *u)
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) {
      u[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    if (state[i][flagcol] == 0.0) init_block(i);
    u[i] = unwrap.displacement(i, state[i][sitecol], state[i][dispcol]);
  }
}

/* ----------------------------------------------------------------------
   what the field reads: the displacements now, and the force evaluations
   begun (the positions may have moved)
------------------------------------------------------------------------- */

const double *FixEQBlocks::source_coordinates()
{
  if (static_cast<int>(qbuf.size()) < atom->nmax) qbuf.resize(atom->nmax);
  displacements(qbuf.data());
  return qbuf.data();
}

void FixEQBlocks::setup_pre_force(int /*vflag*/)
{
  ++nevaluation;
}

void FixEQBlocks::pre_force(int /*vflag*/)
{
  ++nevaluation;
}

void FixEQBlocks::min_pre_force(int /*vflag*/)
{
  ++nevaluation;
}

void FixEQBlocks::setup_pre_force_respa(int /*vflag*/, int /*ilevel*/)
{
  ++nevaluation;
}

void FixEQBlocks::pre_force_respa(int /*vflag*/, int /*ilevel*/, int /*iloop*/)
{
  ++nevaluation;
}

// the field reports on its run (or on this part of it: run N every M).
// The link stays for the parts of a run that follow without a new init()
// (pre no); it is checked before each use and found afresh in init()
void FixEQBlocks::post_run()
{
  if (EQElasticField *f = EQLink::live_pair(field, force)) f->field_report();
}

/* ----------------------------------------------------------------------
   the stage advances with the positions, before the forces of the step
   (a sum of v dt: a restarted run continues it bit for bit)
------------------------------------------------------------------------- */

void FixEQBlocks::post_integrate()
{
  if (drive_flag) stage += vstage * update->dt;
}

// r-RESPA: with the steps of the level the forces are applied at, so that
// every force evaluation sees the stage at the time of its positions (the
// outermost level: once per step by v dt, as without r-RESPA)
void FixEQBlocks::post_integrate_respa(int ilevel, int /*iloop*/)
{
  if (ilevel == ilevel_respa && drive_flag)
    stage += vstage * static_cast<Respa *>(update->integrate)->step[ilevel];
}

/* ----------------------------------------------------------------------
   fix_modify ID velocity v: stage velocity from now on
------------------------------------------------------------------------- */

int FixEQBlocks::modify_velocity(int narg, char **arg)
{
  if (strcmp(arg[0], "velocity") != 0) return 0;
  if (narg < 2)
    error->all(FLERR, "Illegal fix_modify {} velocity command: expected 'fix_modify {} velocity v'",
               id, id);
  if (!drive_flag)
    error->all(FLERR, "Fix_modify {} velocity: fix {} has no stage (add the drive keyword)", id, id);
  const double value = EQUtil::numeric(lmp, fmt::format("Fix_modify {} velocity", id), arg[1]);
  if (!std::isfinite(value))
    error->all(FLERR, "Fix_modify {} velocity: v must be finite (got {})", id, arg[1]);
  try {
    check_drive_rate(kdrive, value, "velocity");
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix_modify {} {}", id, e.what());
  }
  vstage = value;
  return 2;
}

/* ----------------------------------------------------------------------
   global restart: the stage (position now, velocity now, i.e. including a
   change by fix_modify velocity) so that a restarted run continues the
   driving protocol, whether the writing fix had a stage at all, and the
   signature of what the stored blocks were made with (shaping, set by the
   derived fix): a re-specified fix with another of these stops with an
   error naming it
------------------------------------------------------------------------- */

void FixEQBlocks::write_restart(FILE *fp)
{
  EQRecord::write(lmp, fp, {stage, vstage, static_cast<double>(drive_flag)}, shaping);
}

// the stage position and velocity of the file replace the command's stage
// X0 and drive v only when both the writing fix and this one have driving
// springs; the stiffness K is always the command's
void FixEQBlocks::restart(char *buf)
{
  const std::vector<double> list = EQRecord::read(lmp, this, buf, 3, shaping, "blocks");
  if (!std::isfinite(list[0]) || !std::isfinite(list[1]) || !(list[2] == 0.0 || list[2] == 1.0))
    error->all(FLERR, "Fix {} {}: the restart file's record of this fix is unusable: stage {}, "
                      "velocity {}, drive flag {} (a corrupt file)", id, style, list[0], list[1],
               list[2]);
  const bool file_drive = list[2] != 0.0;
  if (!drive_flag) {
    if (file_drive && comm->me == 0)
      error->warning(FLERR, "Fix {}: the restart file has driving springs, this fix has none (no "
                            "drive keyword): the stage is not restored", style);
    return;
  }
  if (!file_drive) {
    if (comm->me == 0)
      utils::logmesg(lmp, "fix {}: the restart file has no driving springs: the stage starts at "
                          "X0 = {} with v = {} of this command\n", style, stage, vstage);
    return;
  }
  stage = list[0];
  vstage = list[1];
  if (comm->me == 0)
    utils::logmesg(lmp, "fix {}: stage restored from the restart file: X_s = {}, v = {}\n", style,
                   stage, vstage);
}
