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
   FRICTION-EQ package for LAMMPS: command eq/me (see eq_me_command.h)
------------------------------------------------------------------------- */

#include "eq_me_command.h"

#include "comm.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "utils.h"
#include "variable.h"

#include "eq_cite.h"
#include "eq_lammps_util.h"
#include "eq_me_job.h"

#include <cmath>
#include <mpi.h>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

void EQMe::command(int narg, char **arg)
{
  EQCite::add(lmp);
  if (narg < 1)
    error->all(FLERR, "Illegal eq/me command: expected 'eq/me threshold <style> <values> "
                      "[keyword values ...]'");
  const std::vector<std::string> args(arg, arg + narg);
  feq::MEJob job;
  try {
    job = feq::parse_me_job(args, EQUtil::number_parser(lmp), EQUtil::file_loader(lmp));
    // theta = k_B T / eps_a of the thermal keyword, in the units of the input
    job.boltz = force->boltz;
    if (job.thermal_on()) job.thermal_spec();    // throws when theta is not finite
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "eq/me {}", e.what());
  }

  // rank 0 writes the tables: it checks them before the solve, and every
  // rank stops with its message
  std::string bad;
  if (comm->me == 0) {
    try {
      feq::check_me_outputs(job);
    } catch (const feq::SpecError &e) {
      bad = e.what();
    }
  }
  int nbad = static_cast<int>(bad.size());
  MPI_Bcast(&nbad, 1, MPI_INT, 0, world);
  if (nbad > 0) {
    bad.resize(nbad);
    MPI_Bcast(&bad[0], nbad, MPI_CHAR, 0, world);
    error->all(FLERR, "eq/me {}", bad);
  }

  // every rank solves (deterministic, cheap); rank 0 writes the tables
  feq::MEReport rep;
  try {
    rep = feq::run_me_job(job, comm->me == 0);
  } catch (const feq::SpecError &e) {
    error->one(FLERR, "eq/me {}", e.what());
  }
  if (comm->me == 0) utils::logmesg(lmp, rep.text);

  // results as internal variables; a result this job does not have (no
  // static peak within xmax, no steady state without re-forming) deletes
  // the variable of an earlier eq/me, so that no stale value is used
  const char *names[] = {"kstar",         "kstar_X",       "static_peak",      "static_peak_X",
                         "kinetic_force", "steady_rate",   "force_at_xmax",    "kinetic_slope",
                         "attached_fraction"};
  for (const char *n : names) {
    const std::string name = std::string("eq_me_") + n;
    const int ivar = input->variable->find(name.c_str());
    if (ivar >= 0 && !input->variable->internalstyle(ivar))
      error->all(FLERR, "eq/me: variable {} exists and is not of style internal", name);
    const auto it = rep.values.find(n);
    if (it == rep.values.end() || !std::isfinite(it->second)) {
      if (ivar >= 0) input->variable->set(name + " delete");
      continue;
    }
    if (ivar >= 0) input->variable->internal_set(ivar, it->second);
    else input->variable->set(fmt::format("{} internal {:.17g}", name, it->second));
  }
}
