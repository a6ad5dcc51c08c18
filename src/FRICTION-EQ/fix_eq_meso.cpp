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
   FRICTION-EQ package for LAMMPS: fix eq/meso

   lambda_c blocks of the far zone (Braun, Peyrard, Stryzheus, Tosatti,
   "Collective effects at frictional interfaces", Eqs. crack.eq03x-
   crack.eq07, screening scr.eq01-scr.eq05).  Each block's distribution of
   contact stretches lives in its per-atom state and is advanced by the
   LAMMPS-free kernel lib/eq_meso with the block's own displacement
   increment; this fix adapts it to LAMMPS atoms, forces, output,
   exchange and restart, and computes the screening from the neighbouring
   blocks' breaking rates.
------------------------------------------------------------------------- */

#include "fix_eq_meso.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair.h"
#include "respa.h"
#include "update.h"
#include "utils.h"

#include "eq_distribution.h"
#include "eq_keywords.h"
#include "eq_lammps_compat.h"
#include "eq_lammps_util.h"
#include "eq_record_lammps.h"
#include "eq_meso.h"
#include "eq_meso_thermal.h"
#include "eq_record.h"
#include "eq_thermal.h"
#include "eq_thermal_steady.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
const char *KEYWORDS =
    "threshold, reform, grid, dir, crossing, start, drive, stage, screen, window, check, thermal, "
    "barrier, labels, delay, aging, rest";
// global vector: sum F, <Gamma>, <eps>, <X>, sum drive force, N, X_s,
// normalization error of the last check, largest Pi0
enum { V_FORCE, V_RATE, V_EPS, V_DISP, V_FDRIVE, V_COUNT, V_STAGE, V_NORM, V_PI0, NVEC };
// a block's Q may lose this much probability (rounding) before it is an error
constexpr double NORM_TOLERANCE = 1e-9;
constexpr int CHECK_DEFAULT = 1000;
enum { COMM_RATE = 1 };
}    // namespace

/* ---------------------------------------------------------------------- */

// what the command says besides what the fix keeps
struct FixEQMeso::Args {
  feq::DistributionSpec threshold, reform;
  bool have_threshold = false;
  double du = 0.0, stage0 = 0.0;
  feq::Crossing crossing = feq::Crossing::EXACT;
  feq::MEStart start = feq::MEStart::RELAXED;
  feq::ThermalKeywords thermal;
  bool have_thermal = false, have_barrier = false, have_delay = false,
       have_aging = false, have_rest = false;
  int labels = 0;    // 0: not given
};

FixEQMeso::FixEQMeso(LAMMPS *lmp, int narg, char **arg) :
    FixEQBlocks(lmp, narg, arg), thermal_kernel(0), hstep(0.0), respa_step(0.0), in_setup(0),
    nlambda(0.0), kc(0.0), xc(0.0), screen_flag(0), kappa(0.0),
    lambda_c(0.0), rcut(0.0), window(0.0), list(nullptr), pi0_max(0.0), threshold_sd(0.0),
    grid_warned(0), grid_default(0), grid_fresh(1), window_safe(0.0), window_warned(0), eps_warned(0),
    pi0_local(0.0),
    list_stamp(-1), screened(0), ran(0), restored(0), comm_mode(0), check_every(CHECK_DEFAULT), norm_max(0.0),
    neval(0), reduced_eval(-1), out(nullptr)
{
  sitecol = M_SITE;
  dispcol = M_DISP;
  flagcol = M_FLAG;
  for (double &v : local_sum) v = 0.0;
  for (double &v : global_sum) v = 0.0;
  Args a;
  parse(narg, arg, a);
  try {
    make_model(a);
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/meso {}", e.what());
  }
  const bigint nblocks = check(a);
  xc = a.threshold.dist->mean();
  // with screening, windows below window_safe leave the steady state
  // unstable (lib meso_min_window): the default is x_c or that
  window_safe = feq::meso_min_window(*a.threshold.dist);
  if (window == 0.0) window = screen_flag && kappa > 0.0 ? std::max(xc, window_safe) : xc;
  stage = a.stage0;

  if (comm->me == 0)
    utils::logmesg(lmp, "fix eq/meso: {} blocks along {} of N_lambda = {} contacts (k_c = {}); "
                        "thresholds {} (<x_s> = {:.6g}); reform {}; grid {:.6g} ({} doubles per "
                        "block); {}{}{}\n",
                   nblocks, "xyz"[idir], nlambda, kc, a.threshold.text, xc, a.reform.text,
                   model->grid(), M_HEAD + model->width(),
                   screen_flag ? fmt::format("screening kappa = {}, lambda_c = {}, rcut = {}",
                                             kappa, lambda_c, rcut)
                               : std::string("no screening"),
                   drive_flag ? fmt::format("; driving springs K = {} to a stage at {} moving at {}",
                                            kdrive, a.stage0, vstage)
                              : std::string(),
                   thermal_kernel
                       ? fmt::format("; {} (theta = k_B T/eps_a = {:.6g}), {} threshold panels",
                                     a.thermal.text(), a.thermal.temperature * force->boltz /
                                     a.thermal.eps_a,
                                     static_cast<const feq::ThermalMesoModel &>(*model).labels())
                       : std::string());

  restart_global = 1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = NVEC;
  global_freq = 1;
  extscalar = 1;
  extvector = -1;
  extlist = new int[NVEC]{1, 0, 0, 0, 1, 1, 0, 0, 0};
  respa_level_support = 1;
  comm_forward = 2;
  peratom_setup(M_HEAD + model->width(), NOUT);
  // the default grid is chosen for the screening at the first run: the
  // width of a block's state may change then (after comm's init)
  if (grid_default && screen_flag) maxexchange_dynamic = 1;

  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (atom->mask[i] & groupbit) init_block(i);
  // the outputs before the first run: those of the blocks at their sites
  apply(false, nullptr);
}

// Nlambda kc, then the keywords (messages name the keyword and the
// allowed values)
void FixEQMeso::parse(int narg, char **arg, Args &a)
{
  if (narg < 7)
    error->all(FLERR, "Illegal fix eq/meso command: expected 'fix ID group eq/meso Nlambda kc "
                      "threshold <style> <values> [keyword values ...]'");
  if (!atom->tag_enable) error->all(FLERR, "Fix eq/meso requires atom IDs (atom_modify id yes)");
  nlambda = EQUtil::numeric(lmp, "Fix eq/meso: Nlambda", arg[3]);
  if (!(nlambda > 0.0) || !std::isfinite(nlambda))
    error->all(FLERR, "Fix eq/meso: Nlambda (contacts per block) must be finite and > 0 (got {})",
               arg[3]);
  kc = EQUtil::numeric(lmp, "Fix eq/meso: kc", arg[4]);
  if (!(kc > 0.0) || !std::isfinite(kc))
    error->all(FLERR, "Fix eq/meso: kc must be finite and > 0 (got {})", arg[4]);

  const std::vector<std::string> args(arg, arg + narg);
  const feq::NumberParser number = EQUtil::number_parser(lmp);
  a.reform.dist = feq::make_delta(0.0);
  a.reform.text = "delta 0";
  size_t iarg = 5;
  try {
    while (iarg < args.size()) {
      const std::string &kw = args[iarg++];
      if (parse_block_keyword(kw, args, iarg, number, a.stage0)) continue;
      if (kw == "threshold") {
        a.threshold = feq::parse_distribution(feq::Role::THRESHOLD, args, iarg, number,
                                              EQUtil::file_loader(lmp));
        a.have_threshold = true;
      } else if (kw == "reform") {
        a.reform = feq::parse_distribution(feq::Role::REFORM, args, iarg, number,
                                           EQUtil::file_loader(lmp));
      } else if (kw == "grid") {
        a.du = feq::parse_finite(args, iarg, "grid du", number);
        if (!(a.du > 0.0)) throw feq::SpecError("grid: du must be > 0 (got " + args[iarg - 1] + ")");
      } else if (kw == "crossing") {
        a.crossing = feq::parse_choice(args, iarg, kw, {"exact", "step"}) == 0
            ? feq::Crossing::EXACT
            : feq::Crossing::STEP;
      } else if (kw == "start") {
        a.start = feq::parse_choice(args, iarg, kw, {"relaxed", "reform"}) == 0
            ? feq::MEStart::RELAXED
            : feq::MEStart::REFORM;
      } else if (kw == "screen") {
        parse_screen(args, iarg);
      } else if (feq::parse_thermal_keyword(kw, args, iarg, number, a.thermal)) {
        if (kw == "thermal") a.have_thermal = true;
        else if (kw == "barrier") a.have_barrier = true;
        else if (kw == "delay") a.have_delay = true;
        else if (kw == "aging") a.have_aging = true;
        else a.have_rest = true;
      } else if (kw == "labels") {
        if (iarg >= args.size()) throw feq::SpecError("labels: missing value (threshold panels)");
        const std::string &tok = args[iarg++];
        const bigint n = utils::is_integer(tok) ? EQUtil::bnumeric(lmp, "Fix eq/meso labels", tok)
                                                : 0;
        if (n < 1 || n > 4096)
          throw feq::SpecError("labels: expected an integer from 1 to 4096 (threshold panels), "
                               "got '" + tok + "'");
        a.labels = static_cast<int>(n);
      } else if (kw == "window") {
        window = feq::parse_finite(args, iarg, "window w", number);
        if (!(window > 0.0)) throw feq::SpecError("window: w must be > 0 (got " + args[iarg - 1] + ")");
      } else if (kw == "check") {
        if (iarg >= args.size()) throw feq::SpecError("check: missing value (steps, 0: never)");
        const std::string &tok = args[iarg++];
        if (!utils::is_integer(tok)) throw feq::SpecError("check: expected an integer, got '" + tok + "'");
        const bigint n = EQUtil::bnumeric(lmp, "Fix eq/meso check", tok);
        if (n < 0 || n > MAXSMALLINT)
          throw feq::SpecError("check: steps must be an integer >= 0 (0: never; got " + tok + ")");
        check_every = static_cast<int>(n);
      } else {
        throw feq::SpecError("unknown keyword '" + kw + "'; allowed: " + KEYWORDS);
      }
    }
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/meso {}", e.what());
  }
  if (!a.have_threshold)
    error->all(FLERR, "Fix eq/meso: the threshold keyword is required; allowed styles: {}",
               feq::role_styles(feq::Role::THRESHOLD));
  // the thermal kernel (lib/eq_meso_thermal) keeps the contacts' ages and
  // the delay pool: at T > 0, and at T = 0 with aging or a delay (theta = 0:
  // no thermal breaks); otherwise the athermal kernel (lib/eq_meso)
  const feq::ThermalSpec &ts = a.thermal.spec;
  const bool hot = a.have_thermal && a.thermal.temperature > 0.0;
  const bool aged = a.have_aging && ts.aging != feq::AgingLaw::NONE && ts.beta > 0.0;
  const bool delayed = a.have_delay && ts.delay != feq::DelayKind::NONE && ts.tau > 0.0;
  thermal_kernel = hot || aged || delayed ? 1 : 0;
  if (a.have_barrier && !hot)
    error->all(FLERR, "Fix eq/meso barrier: needs thermal with T > 0 (the barrier shapes the "
                      "thermal rate)");
  // (the ages shape only aged thresholds: rest without aging changes nothing)
  if (a.have_rest && !thermal_kernel && ts.rest > 0.0)
    error->all(FLERR, "Fix eq/meso rest: needs aging, delay or thermal with T > 0 (the thermal "
                      "kernel keeps the contacts' ages; at T = 0 without aging they change "
                      "nothing)");
  if (a.labels && !thermal_kernel)
    error->all(FLERR, "Fix eq/meso labels: needs thermal with T > 0, aging or delay (the "
                      "threshold panels of the thermal kernel)");
  // without screening eps = 0 and the default grid serves both kernels;
  // with it the thermal kernel's eps0 depends on the velocity: the
  // default grid needs the velocity of drive (screened_grid(), at the set-up
  // of a run while the blocks are fresh: a restart file may bring the grid)
  thermal_keyword = hot ? "thermal" : aged ? "aging" : "delay";
  thermal_cause = hot ? "at T > 0" : aged ? "with threshold aging" : "with a formation delay";
}

// screen kappa lambda_c rcut
void FixEQMeso::parse_screen(const std::vector<std::string> &args, size_t &iarg)
{
  const feq::NumberParser number = EQUtil::number_parser(lmp);
  kappa = feq::parse_finite(args, iarg, "screen kappa", number);
  lambda_c = feq::parse_finite(args, iarg, "screen lambda_c", number);
  rcut = feq::parse_finite(args, iarg, "screen rcut", number);
  if (!(kappa >= 0.0)) throw feq::SpecError("screen: kappa must be >= 0 (got " + args[iarg - 3] + ")");
  if (!(lambda_c > 0.0)) throw feq::SpecError("screen: lambda_c must be > 0 (got " + args[iarg - 2] + ")");
  if (!(rcut > 0.0)) throw feq::SpecError("screen: rcut must be > 0 (got " + args[iarg - 1] + ")");
  screen_flag = 1;
}

// the delay in the restart signature: "" without one (the records of
// runs without it are as before)
static std::string delay_record(const feq::ThermalSpec &spec)
{
  if (spec.delay == feq::DelayKind::NONE || !(spec.tau > 0.0)) return "";
  return fmt::format("|delay {} {:.17g}", spec.delay == feq::DelayKind::FIXED ? "fixed" : "exp",
                     spec.tau);
}

// the threshold aging in the restart signature: "" without it (the
// records of runs without it are as before).  The rest age is not in it:
// it only sets up blocks the fix defines, restored blocks keep their ages
static std::string aging_record(const feq::ThermalSpec &spec)
{
  if (spec.aging == feq::AgingLaw::NONE || !(spec.beta > 0.0)) return "";
  return fmt::format("|aging {} {:.17g} {:.17g}", spec.aging == feq::AgingLaw::LOG ? "log" : "exp",
                     spec.beta, spec.tau_a);
}

// the blocks' master equation on its grid (default: 1/8 of the
// thresholds' standard deviation; a grid the user did not set is not
// named as the cause when it fails), and what the per-block state
// depends on (restart check)
void FixEQMeso::make_model(Args &a)
{
  grid_default = a.du == 0.0 ? 1 : 0;
  const double sd = std::sqrt(std::max(0.0, a.threshold.dist->variance()));
  threshold_sd = sd;
  thresholds = a.threshold.dist;
  // the thermal kernel's (theta = k_B T/eps_a with LAMMPS' k_B; 0 at T = 0)
  const feq::ThermalSpec spec =
      thermal_kernel ? a.thermal.finish(force->boltz, a.threshold.dist->mean()) : feq::ThermalSpec();
  const int labels = a.labels ? a.labels : feq::MESO_THERMAL_LABELS;
  fixed_tau = spec.delay == feq::DelayKind::FIXED ? spec.tau : 0.0;
  if (thermal_kernel && screen_flag && grid_default) {
    auto slider = std::make_shared<feq::ThermalSlider>();
    slider->Pc = a.threshold.dist;
    slider->spec = spec;
    slider->reform = a.reform.dist != nullptr;
    screen_slider = slider;
    // (a restart file brings its grid; fresh blocks need drive: screened_grid())
    if (comm->me == 0 && !(drive_flag && slider->reform))
      utils::logmesg(lmp, "fix eq/meso: no grid keyword with screen and the thermal kernel: a run "
                          "with fresh blocks needs drive with contacts that re-form, or a "
                          "restart file's grid\n");
  }
  if (grid_default) a.du = feq::meso_default_grid(*a.threshold.dist);
  try {
    if (grid_default && !(a.du > 0.0)) throw feq::GridError("grid: zero width");
    if (thermal_kernel)
      model.reset(new feq::ThermalMesoModel(a.threshold.dist, a.reform.dist, a.du, spec, labels,
                                            a.crossing, a.start));
    else
      model.reset(new feq::AthermalBlocks(std::unique_ptr<feq::MesoModel>(
          new feq::MesoModel(a.threshold.dist, a.reform.dist, a.du, a.crossing, a.start))));
  } catch (const feq::GridError &e) {
    if (!grid_default) throw;
    // (the thermal kernel's state grows with its panels and aged thresholds)
    throw feq::SpecError(fmt::format("threshold {}: its standard deviation {:.6g} (from its "
                                     "moments) gives no usable default grid spacing (1/8 of it, "
                                     "{:.6g}){}; set one with the grid keyword{}",
                                     a.threshold.text, sd, a.du,
                                     a.du > 0.0 ? " for a block's state" : "",
                                     thermal_kernel ? fmt::format(" ({})", e.what()) : ""));
  }
  shaping.add("Nlambda", EQRecord::number(nlambda));
  shaping.add("kc", EQRecord::number(kc));
  shaping.add("threshold", EQRecord::distribution(a.threshold));
  shaping.add("reform", EQRecord::distribution(a.reform));
  shaping.add("grid", EQRecord::number(a.du));
  shaping.add("dir", std::string(1, "xyz"[idir]));
  // with the thermal kernel only (athermal restart records are as before);
  // at theta = 0 omega shapes nothing (barrier needs T > 0): recorded as 1
  if (thermal_kernel)
    shaping.add("thermal", fmt::format("{:.17g}|{:.17g}|{:.17g}|{:.17g}|{}{}{}", spec.theta,
                                       spec.theta > 0.0 ? spec.omega : 1.0, spec.p, spec.q,
                                       labels, delay_record(spec), aging_record(spec)));
}

// what the arguments must satisfy together; returns the number of blocks
bigint FixEQMeso::check(const Args &a)
{
  if (a.stage0 != 0.0 && !drive_flag)
    error->all(FLERR, "Fix eq/meso: stage needs the drive keyword (the stage holds the driving "
                      "springs)");
  check_stage(a.stage0);
  if (idir == 2 && domain->dimension == 2)
    error->all(FLERR, "Fix eq/meso: dir z is not allowed in a 2d simulation; allowed: x, y");
  if (group->dynamic[igroup])
    error->all(FLERR, "Fix eq/meso: group {} is dynamic; blocks need a static group",
               group->names[igroup]);
  const bigint nblocks = group->count(igroup);
  if (nblocks == 0) error->all(FLERR, "Fix eq/meso: group {} has no atoms", group->names[igroup]);
  // the largest force of a block, N_lambda k_c max(x_s), must be finite
  constexpr double FMAX = 1e300;
  const double xmax = a.threshold.dist->effective_upper();
  if (!(nlambda * kc * xmax <= FMAX))
    error->all(FLERR, "Fix eq/meso: Nlambda = {} and kc = {} with threshold {} (x_s up to {:.6g}) "
                      "would overflow the blocks' forces (Nlambda kc max(x_s) = {:.6g} must stay <= "
                      "{:g}): lower Nlambda or kc", nlambda, kc, a.threshold.text, xmax,
               nlambda * kc * xmax, FMAX);
  return nblocks;
}

FixEQMeso::~FixEQMeso()
{
  delete[] extlist;
  memory->destroy(out);
}

int FixEQMeso::setmask()
{
  int mask = 0;
  mask |= POST_INTEGRATE;
  mask |= POST_INTEGRATE_RESPA;
  mask |= PRE_FORCE;
  mask |= PRE_FORCE_RESPA;
  mask |= MIN_PRE_FORCE;
  mask |= POST_FORCE;
  mask |= POST_FORCE_RESPA;
  mask |= MIN_POST_FORCE;
  mask |= POST_RUN;
  return mask;
}

void FixEQMeso::init()
{
  init_blocks();
  check_fixed_delay("");
  if (screen_flag && comm->mode == 0) {
    // before LAMMPS' neighbor init, whose message about the too large list
    // cutoff names neither this fix nor its keyword; partners() checks the
    // ghost cutoff LAMMPS settles on
    double have = comm->cutghostuser;
    if (force->pair) have = std::max(have, force->pair->cutforce + neighbor->skin);
    check_ghost_cutoff(have);
  }
  if (screen_flag) EQCompat::request_fix_full_list(neighbor, this, instance_me, rcut);
  list_stamp = -1;
}

/* ----------------------------------------------------------------------
   a fixed delay is held in one bin per sub-step in flight (a step of the
   fix, or of its r-RESPA level, moving a block by du or less is one):
   tau must be at most MESO_DELAY_BINS - 2 such steps; checked at init()
   and when fix dt/reset changes the timestep within a run (reset_dt();
   the timestep command between runs calls it too: the next init() checks)
------------------------------------------------------------------------- */

void FixEQMeso::check_fixed_delay(const char *when)
{
  if (!(fixed_tau > 0.0)) return;
  double step = update->dt;
  std::string level;
  if (utils::strmatch(update->integrate_style, "^respa")) {
    step = static_cast<Respa *>(update->integrate)->step[ilevel_respa];
    level = fmt::format(" of r-RESPA level {} (step {})", ilevel_respa + 1, step);
  }
  const int most = feq::MESO_DELAY_BINS - 2;
  if (fixed_tau > most * step)
    error->all(FLERR,
               "Fix {} eq/meso delay fixed: tau = {} is {:.6g} time steps{}{}, more than the {} "
               "a block holds in flight; use a larger timestep, a shorter delay or delay exp",
               id, fixed_tau, fixed_tau / step, level, when, most);
}

void FixEQMeso::reset_dt()
{
  if (update->whichflag == 0) return;    // between runs: the next init() checks
  check_fixed_delay(" after the timestep changed within the run (fix dt/reset)");
}

void FixEQMeso::init_list(int /*id*/, NeighList *ptr)
{
  list = ptr;
}

/* ----------------------------------------------------------------------
   a block first seen in the group: its site is where it is now, its
   contacts relaxed (or stretched by R with start reform)
------------------------------------------------------------------------- */

void FixEQMeso::init_block(int i)
{
  double *st = state[i];
  memset(st, 0, M_HEAD * sizeof(double));
  st[M_SITE] = EQUtil::Unwrap(atom, domain, idir)(i);
  st[M_ATTACHED] = 1.0;
  model->init(st + M_HEAD, 0.0);
  st[M_FLAG] = 1.0;
}

/* ---------------------------------------------------------------------- */

void FixEQMeso::setup(int vflag)
{
  ran = 1;
  if (grid_default && screen_flag) choose_grid();
  // no time passes at the set-up: no thermal breaks
  in_setup = 1;
  if (utils::strmatch(update->integrate_style, "^verlet")) {
    post_force(vflag);
  } else {
    static_cast<Respa *>(update->integrate)->copy_flevel_f(ilevel_respa);
    post_force_respa(vflag, ilevel_respa, 0);
    static_cast<Respa *>(update->integrate)->copy_f_flevel(ilevel_respa);
  }
  in_setup = 0;
  check_normalization();
}

void FixEQMeso::min_setup(int /*vflag*/)
{
  ran = 1;
  apply(false, atom->f);
}

void FixEQMeso::post_force(int /*vflag*/)
{
  // the time of this step (thermal breaks): the timestep, with r-RESPA
  // that of the fix's level
  hstep = in_setup ? 0.0 : respa_step > 0.0 ? respa_step : update->dt;
  apply(true, atom->f);
  if (screen_flag) screening();
  if (check_every > 0 && update->ntimestep % check_every == 0) check_normalization();
}

void FixEQMeso::post_force_respa(int vflag, int ilevel, int /*iloop*/)
{
  if (ilevel != ilevel_respa) return;
  // the time of a step at this level (an inner level is called more often)
  respa_step = static_cast<Respa *>(update->integrate)->step[ilevel];
  post_force(vflag);
  respa_step = 0.0;
}

// during minimization the blocks' contacts hold: the force is the elastic
// response of the attached contacts to the block's displacement
void FixEQMeso::min_post_force(int /*vflag*/)
{
  apply(false, atom->f);
}

/* ----------------------------------------------------------------------
   each block's master equation to its current displacement (advance), or
   its elastic response without breaking (minimization, definition);
   forces -F_n and the driving springs into f (nullptr: the state and the
   outputs only)
------------------------------------------------------------------------- */

void FixEQMeso::apply(bool advance, double **f)
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int d = idir;
  const EQUtil::Unwrap unwrap(atom, domain, d);
  const double nk = nlambda * kc;
  for (double &v : local_sum) v = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *const st = state[i];
    if (st[M_FLAG] == 0.0) init_block(i);
    double *const q = st + M_HEAD;
    const double X = unwrap.displacement(i, st[M_SITE], st[M_DISP]);
    if (!std::isfinite(X))
      error->one(FLERR, "Fix eq/meso: displacement of block {} is {} (numerical instability: check "
                        "the timestep against N_lambda k_c, the coupling and the driving springs)",
                 atom->tag[i], X);
    double F;
    if (advance) {
      const double X0 = model->position(q);
      double broken;
      try {
        broken = model->advance(q, X, st[M_EPS], hstep);
      } catch (const std::exception &e) {
        error->one(FLERR, "Fix eq/meso: block {}: {}", atom->tag[i], e.what());
      }
      if (st[M_EPS] > model->eps_accurate()) check_thermal_grid(i, st[M_EPS]);
      // the breaking rate per unit displacement, averaged over the last
      // `window` of the block's forward motion (exponential weight):
      // a burst of breaks within one step counts as 1/window, a steady
      // rate Gamma as Gamma
      if (X > X0) {
        const double a = std::exp(-(X - X0) / window);
        st[M_RATE] = a * st[M_RATE] + broken * (1.0 - a) / (X - X0);
      }
      F = nk * model->mean_stretch(q);
    } else {
      F = nk * (model->mean_stretch(q) + (X - model->position(q)) * model->attached(q));
    }
    const double att = model->attached(q);
    const double fd = drive_flag ? kdrive * (stage - X) : 0.0;
    if (f) f[i][d] += fd - F;
    st[M_DISP] = X;
    st[M_FORCE] = F;
    st[M_FDRIVE] = fd;
    st[M_ATTACHED] = att;
    publish(i);
    local_sum[S_FORCE] += F;
    local_sum[S_RATE] += st[M_RATE];
    local_sum[S_EPS] += st[M_EPS];
    local_sum[S_DISP] += X;
    local_sum[S_FDRIVE] += fd;
    local_sum[S_COUNT] += 1.0;
  }
  ++neval;
}

/* ----------------------------------------------------------------------
   screening: the blocks of the neighbor list (within rcut + skin) of each
   local block, found after every list build and sorted by atom ID (ties:
   periodic images, by their offset), so that eps is the same sum in the
   same order on any number of ranks and whatever the list's schedule
------------------------------------------------------------------------- */

void FixEQMeso::check_ghost_cutoff(double have)
{
  const double need = rcut + neighbor->skin;
  if (have < need)
    error->all(FLERR, "Fix eq/meso screen: rcut {} + neighbor skin {} exceeds the ghost atom "
                      "cutoff {}; partners would be missed: set comm_modify cutoff {} or more",
               rcut, neighbor->skin, have, need);
}

void FixEQMeso::partners()
{
  check_ghost_cutoff(comm->get_comm_cutoff());
  double **x = atom->x;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  struct Partner {
    tagint tag;
    double del[3];
    int j;
  };
  std::vector<Partner> mine;
  std::vector<int> range(2 * static_cast<size_t>(nlocal), 0);
  std::vector<int> pj2;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    if (!(mask[i] & groupbit)) continue;
    mine.clear();
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (j >= nall || !(mask[j] & groupbit)) continue;
      mine.push_back({tag[j], {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]}, j});
    }
    std::sort(mine.begin(), mine.end(), [](const Partner &a, const Partner &b) {
      if (a.tag != b.tag) return a.tag < b.tag;
      for (int k = 0; k < 3; k++)
        if (a.del[k] != b.del[k]) return a.del[k] < b.del[k];
      return false;
    });
    range[2 * i] = static_cast<int>(pj2.size());
    for (const Partner &p : mine) pj2.push_back(p.j);
    range[2 * i + 1] = static_cast<int>(pj2.size());
  }
  first.swap(range);
  pj.swap(pj2);
  list_stamp = neighbor->ncalls;
}

/* ----------------------------------------------------------------------
   eps_n = x_c sum_m Gamma_m Pi_mn from the rates of this step, for the
   next one; Pi_mn at the distance of the sites now (blocks move along dir
   from their sites; along the other directions with their positions)
------------------------------------------------------------------------- */

void FixEQMeso::screening()
{
  const bool rebuilt = neighbor->ago == 0 || list_stamp < 0;
  if (rebuilt) partners();
  gather_columns(true);
  pi0_local = lattice_sums(true, rebuilt);
  screened = 1;
  if (rebuilt) {
    check_screened_grid();
    check_window();
  }
}

// the rate (rates: else 0) and the displacement of every local block into
// cbuf, and to the ghosts; before a run's first step the displacements of
// the positions now (the atoms may have moved since the last evaluation)
void FixEQMeso::gather_columns(bool rates)
{
  const int nlocal = atom->nlocal;
  if (static_cast<int>(cbuf.size()) < 2 * atom->nmax)
    cbuf.resize(2 * static_cast<size_t>(atom->nmax));
  const int *mask = atom->mask;
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  for (int i = 0; i < nlocal; i++) {
    const bool block = (mask[i] & groupbit) != 0;
    double X = 0.0;
    if (block && rates) {
      X = state[i][M_DISP];
    } else if (block && state[i][M_FLAG] != 0.0) {
      double site = state[i][M_SITE];
      X = unwrap.displacement(i, site, state[i][M_DISP]);
    }
    cbuf[2 * i] = block && rates ? state[i][M_RATE] : 0.0;
    cbuf[2 * i + 1] = X;
  }
  comm_mode = COMM_RATE;
  EQCompat::forward_comm(comm, static_cast<Fix *>(this));
}

// over the partners of every local block at the distance of the sites:
// Pi0 = sum_m Pi_mn, and (eps_update) eps_n = x_c sum_m Gamma_m Pi_mn
// from the rates in cbuf; returns this rank's largest Pi0.  After a list
// build (rebuilt) the largest Pi0 of all ranks goes into pi0_max (>= 1:
// an error)
double FixEQMeso::lattice_sums(bool eps_update, bool rebuilt)
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **x = atom->x;
  const int d = idir;
  const double cutsq = rcut * rcut * (1.0 + 2e-12);
  const double scale = nlambda * kappa;
  double pimax = 0.0, dxbig = 0.0, eps_sum = 0.0;
  int iworst = -1, ibig = -1, jbig = -1;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double Xi = cbuf[2 * i + 1];
    double e = 0.0, pi0 = 0.0;
    for (int m = first[2 * i]; m < first[2 * i + 1]; m++) {
      const int j = pj[m];
      const double dX = Xi - cbuf[2 * j + 1];
      double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      del[d] -= dX;    // sites
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      if (rsq > cutsq) continue;
      if (!(rsq > 0.0))
        error->one(FLERR, "Fix eq/meso screen: blocks {} and {} share a site", atom->tag[i],
                   atom->tag[j]);
      if (std::fabs(dX) > dxbig) {
        dxbig = std::fabs(dX);
        ibig = i;
        jbig = j;
      }
      const double ratio = lambda_c / std::sqrt(rsq);
      const double pi = scale * ratio * ratio * ratio;
      pi0 += pi;
      e += pi * cbuf[2 * j];
    }
    if (eps_update) {
      state[i][M_EPS] = out[i][M_EPS] = xc * e;
      eps_sum += xc * e;
    }
    if (pi0 > pimax) {
      pimax = pi0;
      iworst = i;
    }
  }
  // partners come from the list of the current positions: their
  // displacements may differ by less than the skin (with a margin of a
  // factor 2 for the motion until the next list build)
  if (dxbig > 0.5 * neighbor->skin)
    error->one(FLERR, "Fix eq/meso screen: the displacements of blocks {} and {} differ by {:.6g}, "
                      "more than half the neighbor skin {}: partners may be missing from the "
                      "neighbor list; raise the skin (neighbor SKIN bin) above twice the largest "
                      "difference", atom->tag[ibig], atom->tag[jbig], dxbig, neighbor->skin);
  // the global mean of eps is that of the per-atom column: the screening
  // of the next step
  if (eps_update) local_sum[S_EPS] = eps_sum;
  // Pi0 = sum_m Pi_mn < 1, checked after every list build (one reduction)
  if (rebuilt) {
    struct {
      double value;
      int rank;
    } in{pimax, comm->me}, out{0.0, 0};
    MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
    pi0_max = out.value;
    if (pi0_max >= 1.0) {
      double who = iworst >= 0 ? static_cast<double>(atom->tag[iworst]) : 0.0;
      MPI_Bcast(&who, 1, MPI_DOUBLE, out.rank, world);
      error->all(FLERR, "Fix eq/meso screen: Pi0 = sum_m Pi_mn = {:.6g} >= 1 at block {}: no "
                        "screened solution (eps0 = Pi0/(1 - Pi0) diverges); lower kappa ({}) or "
                        "rcut ({})", pi0_max, static_cast<tagint>(who), kappa, rcut);
    }
  }
  return pimax;
}

// with screening the thresholds that matter are x_s/(1 + eps), narrower by
// 1 + eps0 = 1/(1 - Pi0) in the steady state: a grid that resolves them
// at T > 0 the grid is the user's or made for eps0 at the drive's velocity
// (screened_grid()), and eps0 grows as 1/v: a load factor
// that makes (1 + eps) du coarser than a quarter of the thresholds' sd is
// reported once per rank (the kernel stops beyond eps_valid())
void FixEQMeso::check_thermal_grid(int i, double eps)
{
  if (eps_warned) return;
  eps_warned = 1;
  error->warning(FLERR, "Fix {} eq/meso grid: block {} has the load factor eps = {:.6g}, so that "
                        "the effective grid (1 + eps) du = {:.6g} is coarser than 1/4 of the "
                        "thresholds' standard deviation {:.6g}: F and eps lose accuracy (measured: "
                        "14 % error of F at (1 + eps) du = 4 sd); use grid {:.6g} or less",
                 id, atom->tag[i], eps, (1.0 + eps) * model->grid(), threshold_sd,
                 0.25 * threshold_sd / (1.0 + eps));
}

// with fewer than 1/MESO_GRID_SD_FRACTION cells per standard deviation
// (the limit that is an error without screening) is reported once, with
// why the fix is on it and the grid the default would choose
void FixEQMeso::check_screened_grid()
{
  // with the thermal kernel eps0 depends on the velocity (the blocks' own
  // load factors are checked, check_thermal_grid())
  if (thermal_kernel) return;
  const double screened_sd = threshold_sd * (1.0 - pi0_max);
  if (grid_warned || !(model->grid() > feq::MESO_GRID_SD_FRACTION * screened_sd)) return;
  grid_warned = 1;
  const double want = feq::meso_default_grid(*thresholds, pi0_max);
  std::string why;
  if (!grid_default)
    why = "set by the grid keyword";
  else if (want < model->min_grid())
    why = fmt::format("the finest grid within the limit of {} doubles per block",
                      feq::MESO_MAX_WIDTH);
  else if (!grid_fresh)
    why = "the grid of the blocks' state (they moved in an earlier run or came from a restart "
          "file with a history: a grid is never changed under a state)";
  else
    why = "the default grid chosen at this run's set-up (Pi0 has grown since)";
  if (comm->me == 0)
    error->warning(FLERR, "Fix {} eq/meso: grid {:.6g} resolves the screened thresholds x_s/(1 + "
                          "eps0) (Pi0 = {:.6g}, eps0 = Pi0/(1 - Pi0) = {:.6g}) with {:.3g} cells per "
                          "standard deviation, fewer than {:.0f}: steady eps and F may miss the "
                          "steady state by more than 1e-4 (relative; the grid error is amplified by "
                          "1 + eps0); grid {:.3g} (1/8 of the screened standard deviation) reaches "
                          "it, the default for this Pi0; this grid is {}",
                   id, model->grid(), pi0_max, pi0_max / (1.0 - pi0_max),
                   screened_sd / model->grid(), 1.0 / feq::MESO_GRID_SD_FRACTION, want, why);
}

// with screening, windows below window_safe (lib meso_min_window) leave
// the steady state of a screened lattice unstable: reported once
void FixEQMeso::check_window()
{
  if (window_warned || !(pi0_max > 0.0) || !(window < window_safe)) return;
  window_warned = 1;
  if (comm->me == 0)
    error->warning(FLERR, "Fix {} eq/meso: window {:.6g} is below {:.6g} = {} <x_s> (<x_s>/sd)^2 "
                          "of the thresholds, the smallest window with which screened blocks are "
                          "known to reach their steady state: with smaller windows it can be "
                          "unstable (the blocks break in synchronized bursts, eps far from its "
                          "steady value, whatever the time step and grid); set window {:.6g} or more",
                   id, window, window_safe, feq::MESO_WINDOW_COEFF, window_safe);
}

/* ----------------------------------------------------------------------
   the default grid for the screened thresholds, at the setup of the first
   run: 1/8 of their standard deviation sd (1 - Pi0) with the largest Pi0
   of the lattice (the partners of the list just built), not finer than
   the state size allows.  Only while every block is fresh (its state is
   that of a block just defined, on any rank): a fresh block is the same
   on any grid, so it is re-made on the new one exactly; a block with a
   history keeps its grid (grids are never mixed, a state never
   interpolated), and check_screened_grid() warns if it is too coarse
------------------------------------------------------------------------- */

void FixEQMeso::choose_grid()
{
  grid_fresh = all_fresh() ? 1 : 0;
  if (!grid_fresh) return;
  partners();
  gather_columns(false);
  lattice_sums(false, true);
  std::string how;
  const double screened = screened_grid(how);
  const double want = std::max(screened, model->min_grid());
  if (!(want > 0.0) || want == model->grid()) return;
  set_grid(want);
  if (screen_slider && want > screened && comm->me == 0)
    error->warning(FLERR, "Fix {} eq/meso grid: the default grid for the screened thresholds "
                          "would be {:.6g} (1/8 of {}), finer than a block's state allows; grid "
                          "{:.6g} resolves them with {:.3g} cells per standard deviation: steady "
                          "eps and F lose accuracy (set a larger velocity, or fewer labels)",
                   id, screened, how, want, screened / want * 8.0);
  if (comm->me == 0)
    utils::logmesg(lmp, "fix eq/meso: grid {:.17g} for the screened thresholds (Pi0 = {:.6g}: {} "
                        "of their standard deviation {}); {} doubles per block\n",
                   model->grid(), pi0_max,
                   want > screened ? std::string("the finest grid within the state size limit, "
                                                 "coarser than 1/8")
                                   : std::string("1/8"),
                   how, M_HEAD + model->width());
}

// 1/8 of the screened thresholds' standard deviation sd/(1 + eps0), eps0
// the steady load factor of a uniform lattice with the largest Pi0: the
// athermal Pi0/(1 - Pi0), sd (1 - Pi0); with the thermal kernel the root
// of eps0 = Pi0 x_c Gamma(eps0) at the drive's velocity (lib
// screened_load_factor(): thermal breaks, aging and delays make it
// depend on the velocity).  how: the formula, for the log
double FixEQMeso::screened_grid(std::string &how)
{
  if (!screen_slider || pi0_max == 0.0) {
    how = "sd (1 - Pi0)";
    return feq::meso_default_grid(*thresholds, pi0_max);
  }
  // the drive's velocity, else the one an earlier set-up or the restart
  // file's run made the grid for (made anew for this Pi0)
  const double vdrive = drive_flag ? std::fabs(vstage) : 0.0;
  const double v = vdrive > 0.0 ? vdrive : screened_v;
  if (!(v > 0.0) || !screen_slider->reform) {
    if (grid_restored) {    // the restart file's grid, as it was made
      how = "the restart file's grid, kept";
      return model->grid();
    }
    if (!(drive_flag && screen_slider->reform))
      error->all(FLERR, "Fix {} eq/meso {}: with screen needs the grid keyword, or drive with "
                        "contacts that re-form (this run sets up blocks that have not moved, with "
                        "screening partners, and no restart file gave them a grid; {} the screened "
                        "thresholds x_s/(1 + eps0) depend on the velocity: the default grid is made "
                        "for the steady eps0 at the drive's velocity; else choose du <= sd/(4 (1 + "
                        "eps0)), sd the thresholds' standard deviation, eps0 the steady load "
                        "factor)",
                 id, thermal_keyword, thermal_cause);
    error->all(FLERR, "Fix {} eq/meso drive: the default grid with screen at T > 0, with aging or "
                      "with a delay needs a velocity v != 0 at the set-up of a run while no block "
                      "has moved (it is made for the steady load factor at v); set v, or the grid "
                      "keyword", id);
  }
  feq::ThermalSlider s = *screen_slider;
  s.v = v;
  double eps0 = 0.0;
  try {
    eps0 = feq::screened_load_factor(s, pi0_max);
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix {} eq/meso screen: {}; set the grid keyword", id, e.what());
  }
  how = fmt::format("sd/(1 + eps0), eps0 = {:.6g} the steady load factor at {} {:.6g}", eps0,
                    vdrive > 0.0 ? "the drive's velocity" : "the earlier velocity", v);
  screened_v = v;
  return feq::MESO_GRID_DEFAULT_SD * threshold_sd / (1.0 + eps0);
}

// every set-up block holds the state of a block just defined (at X = 0)
bool FixEQMeso::all_fresh()
{
  std::vector<double> made(model->width());
  model->init(made.data(), 0.0);
  const size_t bytes = made.size() * sizeof(double);
  int mine = 1;
  for (int i = 0; i < atom->nlocal && mine; i++)
    if ((atom->mask[i] & groupbit) && state[i][M_FLAG] != 0.0 &&
        memcmp(state[i] + M_HEAD, made.data(), bytes) != 0)
      mine = 0;
  int all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, world);
  return all != 0;
}

// the blocks' master equation on the grid du: the state of every local
// block re-made fresh on it (its site and outputs kept), the per-atom
// arrays re-sized, the restart signature of the grid updated
void FixEQMeso::set_grid(double du)
{
  try {
    std::unique_ptr<feq::BlockModel> m = model->regrid(du);
    model = std::move(m);
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix {} eq/meso {}", id, e.what());
  }
  const int width = M_HEAD + model->width();
  double **made = nullptr;
  memory->create(made, std::max(atom->nmax, 1), width, "eq:state");
  for (int i = 0; i < atom->nlocal; i++) {
    memcpy(made[i], state[i], M_HEAD * sizeof(double));
    memset(made[i] + M_HEAD, 0, model->width() * sizeof(double));
    if (made[i][M_FLAG] != 0.0) model->init(made[i] + M_HEAD, 0.0);
  }
  memory->destroy(state);
  state = made;
  ncol = width;
  maxexchange = ncol;
  for (size_t k = 0; k < shaping.keywords.size(); k++)
    if (shaping.keywords[k] == "grid") shaping.hashes[k] = feq::hash52(EQRecord::number(du));
}

// rate and displacement of each block
int FixEQMeso::pack_forward_comm(int n, int *list_, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  for (int i = 0; i < n; i++) {
    buf[2 * i] = cbuf[2 * list_[i]];
    buf[2 * i + 1] = cbuf[2 * list_[i] + 1];
  }
  return 2 * n;
}

void FixEQMeso::unpack_forward_comm(int n, int first_, double *buf)
{
  if (static_cast<int>(cbuf.size()) < 2 * (first_ + n))
    cbuf.resize(2 * static_cast<size_t>(first_ + n));
  for (int i = 0; i < n; i++) {
    cbuf[2 * (first_ + i)] = buf[2 * i];
    cbuf[2 * (first_ + i) + 1] = buf[2 * i + 1];
  }
}

/* ----------------------------------------------------------------------
   every block's Q must hold its probability (attached + detached = 1):
   a loss beyond rounding is an error that names the block
------------------------------------------------------------------------- */

void FixEQMeso::check_normalization()
{
  const int *mask = atom->mask;
  double worst = 0.0;
  tagint who = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit) || state[i][M_FLAG] == 0.0) continue;
    const double *q = state[i] + M_HEAD;
    const double e = model->valid(q) ? model->normalization_error(q) : HUGE_VAL;
    if (!(e <= worst)) {
      worst = e;
      who = atom->tag[i];
    }
  }
  if (!(worst <= NORM_TOLERANCE))
    error->one(FLERR, "Fix eq/meso: block {} lost the normalization of its distribution of "
                      "stretches (|int Q - 1| = {:.3g} > {}); the state is corrupt or the grid ({}) "
                      "is too coarse for the motion", who, worst, NORM_TOLERANCE, model->grid());
  MPI_Allreduce(&worst, &norm_max, 1, MPI_DOUBLE, MPI_MAX, world);
}

/* ----------------------------------------------------------------------
   global restart: the stage (as fix eq/substrate's, FixEQBlocks) and,
   when it was a default, the grid of the stored blocks (0: set by the
   grid keyword), so that a fix re-specified with the default grid
   continues on the default its blocks were made on; otherwise the grid
   must be re-specified as it was (the signature names the grid keyword).
   Fifth value: the velocity the default grid was made for with screen
   and the thermal kernel (0: none), so that the reader makes it anew
   where the writer would (screened_grid()); records of 4 values (before
   27 Nov 2026) take the file's drive velocity instead
------------------------------------------------------------------------- */

void FixEQMeso::write_restart(FILE *fp)
{
  // (with the thermal kernel and screen only a grid made for the screening
  // or adopted from a file: not the unscreened one the fix starts on)
  const bool chosen = !screen_slider || screened_v > 0.0 || grid_restored;
  EQRecord::write(lmp, fp,
                  {stage, vstage, static_cast<double>(drive_flag),
                   grid_default && chosen ? model->grid() : 0.0, screened_v},
                  shaping);
}

void FixEQMeso::restart(char *buf)
{
  const double *rec = reinterpret_cast<const double *>(buf);
  // records of earlier versions have the stage only (3 values): their grid
  // is the command's; 4 values: no velocity of the grid
  if (!(rec[0] == feq::RECORD_MAGIC && rec[1] == feq::RECORD_FORMAT &&
        (rec[2] == 4.0 || rec[2] == 5.0))) {
    FixEQBlocks::restart(buf);
    return;
  }
  const int nvalues = static_cast<int>(rec[2]);
  // a record of the thermal kernel has one keyword more (thermal): say
  // which way the file and the command differ
  const size_t nsig = shaping.hashes.size();
  const double nfile = rec[3 + nvalues];
  if (nfile == double(nsig + 1) && !thermal_kernel)
    error->all(FLERR, "Fix {} eq/meso thermal: the restart file's blocks were made by the thermal "
                      "kernel (thermal with T > 0, aging or delay): re-specify thermal, barrier, "
                      "labels, aging and delay as in that run", id);
  if (nfile + 1.0 == double(nsig) && thermal_kernel)
    error->all(FLERR, "Fix {} eq/meso thermal: the restart file's blocks were made athermal "
                      "(T = 0 without aging or delay): remove thermal, aging and delay to continue "
                      "them, or define the fix under another ID to start afresh", id);
  const double du = rec[6];
  const bool adopt = grid_default && std::isfinite(du) && du > 0.0;
  if (!grid_default && std::isfinite(du) && du > 0.0 && du != model->grid())
    error->all(FLERR, "Fix {} eq/meso: the restart file's blocks are on the grid {:.17g} that the "
                      "writing run chose by default, not on grid {:.17g}: omit the grid keyword to "
                      "continue on it, or give exactly that value", id, du, model->grid());
  // the signature against the file's default grid when the command has none
  feq::Signature sig = shaping;
  if (adopt)
    for (size_t k = 0; k < sig.keywords.size(); k++)
      if (sig.keywords[k] == "grid") sig.hashes[k] = feq::hash52(EQRecord::number(du));
  EQRecord::read(lmp, this, buf, nvalues, sig, "blocks");
  // (with the thermal kernel and screen: kept for blocks that have not
  // moved, made anew at the velocity it was made for, screened_grid())
  if (nvalues == 5 && !(std::isfinite(rec[7]) && rec[7] >= 0.0))
    error->all(FLERR, "Fix {} eq/meso: the restart file's record of this fix is unusable: the "
                      "velocity of its grid is {}", id, rec[7]);
  if (adopt && screen_slider) {
    grid_restored = 1;
    if (nvalues == 5) screened_v = rec[7];
    else if (rec[5] != 0.0 && std::isfinite(rec[4])) screened_v = std::fabs(rec[4]);
  }
  if (adopt && du != model->grid()) {
    set_grid(du);
    if (comm->me == 0)
      utils::logmesg(lmp, "fix eq/meso: grid {:.17g} of the restart file's blocks; {} doubles per "
                          "block\n", du, M_HEAD + model->width());
  }
  // the stage: FixEQBlocks' record of 3 values and the signature
  std::vector<double> stage_rec(rec, rec + 6);
  stage_rec[2] = 3.0;
  stage_rec.insert(stage_rec.end(), rec + 3 + nvalues, rec + 4 + nvalues + sig.hashes.size());
  FixEQBlocks::restart(reinterpret_cast<char *>(stage_rec.data()));
}

/* ----------------------------------------------------------------------
   per-atom restart data of another grid or distributions would be
   misread: the count must be this fix's
------------------------------------------------------------------------- */

void FixEQMeso::unpack_restart(int nlocal, int nth)
{
  FixEQPerAtom::unpack_restart(nlocal, nth);
  publish(nlocal);
  restored = 1;
}

// a block restored from a restart file: set up (flag 1) with a valid
// master-equation state of this fix's model, or not set up (flag 0)
void FixEQMeso::check_restored(int i)
{
  const double *st = state[i];
  std::string why;
  if (st[M_FLAG] != 0.0 && st[M_FLAG] != 1.0)
    why = fmt::format("set-up flag {}", st[M_FLAG]);
  else if (st[M_FLAG] == 1.0 && !model->valid(st + M_HEAD))
    why = "its distribution of stretches is not a valid state of this fix's model (thresholds, "
          "reform or grid differ from the run that wrote it, or the data are garbled)";
  if (!why.empty())
    error->one(FLERR, "Fix {} eq/meso: the restart file's block {} is garbled: {}", id,
               atom->tag[i], why);
  if (st[M_FLAG] == 1.0) check_reach(i, idir, st[M_SITE], "site");
}

/* ----------------------------------------------------------------------
   the per-atom output: its own nmax x NOUT array (LAMMPS reads a per-atom
   array with a stride of its number of columns, e.g. in atom-style
   variables; the state rows are wider), a copy of the state's first
   columns that follows the state through growth, sorting and exchange
------------------------------------------------------------------------- */

void FixEQMeso::grow_arrays(int nmax)
{
  FixEQPerAtom::grow_arrays(nmax);
  memory->grow(out, nmax, NOUT, "eq/meso:out");
  array_atom = out;
}

void FixEQMeso::copy_arrays(int i, int j, int delflag)
{
  FixEQPerAtom::copy_arrays(i, j, delflag);
  memcpy(out[j], out[i], NOUT * sizeof(double));
}

void FixEQMeso::set_arrays(int i)
{
  FixEQPerAtom::set_arrays(i);
  memset(out[i], 0, NOUT * sizeof(double));
}

int FixEQMeso::unpack_exchange(int nlocal, double *buf)
{
  const int n = FixEQPerAtom::unpack_exchange(nlocal, buf);
  publish(nlocal);
  return n;
}

void FixEQMeso::publish(int i)
{
  memcpy(out[i], state[i], NOUT * sizeof(double));
}

/* ----------------------------------------------------------------------
   global output, reduced on demand (one Allreduce for all entries)
------------------------------------------------------------------------- */

void FixEQMeso::reduce()
{
  if (reduced_eval == neval) return;
  MPI_Allreduce(local_sum, global_sum, NSUM, MPI_DOUBLE, MPI_SUM, world);
  reduced_eval = neval;
}

// before the first run the outputs follow the positions (displace_atoms
// after the definition); blocks restored from a restart file keep theirs
void FixEQMeso::outputs_before_run()
{
  if (!ran && !restored) apply(false, nullptr);
}

double FixEQMeso::compute_scalar()
{
  outputs_before_run();
  reduce();
  return global_sum[S_FORCE];
}

double FixEQMeso::compute_vector(int n)
{
  outputs_before_run();
  switch (n) {
    case V_STAGE: return drive_flag ? stage : 0.0;
    case V_NORM: return norm_max;
    case V_PI0: {
      // of this step's distances (reduced on demand); before the first
      // run there are no neighbor lists to find the partners in
      if (screen_flag && !screened)
        error->all(FLERR, "Fix {} eq/meso: the largest Pi0 (global vector entry 9) is not "
                          "available before the first run (the partners come from its neighbor "
                          "list): read it after a run or run 0", id);
      double all = 0.0;
      MPI_Allreduce(&pi0_local, &all, 1, MPI_DOUBLE, MPI_MAX, world);
      return all;
    }
  }
  reduce();
  const double count = global_sum[S_COUNT];
  switch (n) {
    case V_FORCE: return global_sum[S_FORCE];
    case V_RATE: return count > 0.0 ? global_sum[S_RATE] / count : 0.0;
    case V_EPS: return count > 0.0 ? global_sum[S_EPS] / count : 0.0;
    case V_DISP: return count > 0.0 ? global_sum[S_DISP] / count : 0.0;
    case V_FDRIVE: return global_sum[S_FDRIVE];
    case V_COUNT: return count;
  }
  return 0.0;
}

/* ----------------------------------------------------------------------
   fix_modify ID velocity v
------------------------------------------------------------------------- */

int FixEQMeso::modify_param(int narg, char **arg)
{
  if (const int used = modify_velocity(narg, arg)) return used;
  error->all(FLERR, "Fix_modify {}: unknown keyword '{}'; allowed: velocity (and LAMMPS' energy, "
                    "virial, respa)", id, arg[0]);
  return 0;
}

double FixEQMeso::memory_usage()
{
  return FixEQPerAtom::memory_usage() +
      static_cast<double>(cbuf.capacity() + qbuf.capacity()) * sizeof(double) +
      static_cast<double>(pj.capacity() + first.capacity()) * sizeof(int);
}
