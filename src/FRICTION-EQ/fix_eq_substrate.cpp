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
   FRICTION-EQ package for LAMMPS: fix eq/substrate

   Substrate force of the lambda_c blocks of the FK-ME model (Braun,
   Peyrard, Stryzheus, Tosatti, "Collective effects at frictional
   interfaces", Sec. V B, Eq. crack.eqi00), with optional driving springs
   to a moving stage.  The shapes live in the LAMMPS-free lib/eq_substrate;
   this fix adapts them to LAMMPS atoms, forces, output, exchange and
   restart (per-atom state as in fix spring/self).  With pair eq/elastic
   the blocks' displacements are the coordinates of its elastic field
   (eq_field.h): this fix hands them over before every force evaluation.
------------------------------------------------------------------------- */

#include "fix_eq_substrate.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "force.h"
#include "pair.h"
#include "modify.h"
#include "respa.h"
#include "update.h"
#include "utils.h"

#include "eq_keywords.h"
#include "eq_lammps_util.h"
#include "eq_record_lammps.h"
#include "eq_random.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
const char *KEYWORDS =
    "dir, drive, stage, reverse, crossing, integrator, disorder, thermal, barrier, seed, rate";
const char *SHAPES = "sawtooth, smooth, table";
// global vector: f = K X_s, X_s, v_stage, <v>, <u>, sum F_s, sum drive, E_sub, E_drive, N,
// thermal hops
enum {
  V_F, V_STAGE, V_VSTAGE, V_VEL, V_DISP, V_FSUB, V_FDRIVE, V_ESUB, V_EDRIVE, V_COUNT, V_HOPS, NVEC
};
}    // namespace

/* ---------------------------------------------------------------------- */

FixEQSubstrate::FixEQSubstrate(LAMMPS *lmp, int narg, char **arg) :
    FixEQBlocks(lmp, narg, arg), rev_break(0), exact(1), integrator(Integrator::AUTO), window(0.5),
    dseed(0), thermal_flag(0), tseed(0), njump(0), jump_step(-1), jump_tag(0), jump_size(0.0), neval(0), reduced_eval(-1),
    chained(0), fsub_valid(0), ran(0), restored(0)
{
  sitecol = SITE;
  dispcol = DISP;
  flagcol = DISORDER;
  for (double &v : global_sum) v = 0.0;
  const double stage0 = parse(narg, arg);
  const bigint nblocks = check(arg, stage0);
  setup_thermal();
  stage = stage0;
  // what the stored blocks are made with (restart check): their k_c, the
  // substrate (the well origins are multiples of its period), the
  // quenched factors, the direction and the meaning of the well origins
  shaping.add("kc", EQRecord::number(kc));
  shaping.add("shape", shape.kind() == feq::SubstrateShape::TABLE ? shape.describe()
                       : std::string(arg[4]));
  shaping.add("uc", fmt::format("{:.17g}|{:.17g}|{:.17g}", shape.period(), shape.work(),
                                shape.max_phi()));
  shaping.add("disorder", disorder.dist ? EQRecord::distribution(disorder) + "|" +
                                              std::to_string(dseed)
                                        : std::string("none"));
  shaping.add("dir", std::string(1, "xyz"[idir]));
  shaping.add("reverse", rev_break ? "break" : "periodic");

  if (comm->me == 0)
    utils::logmesg(lmp, "fix eq/substrate: {} blocks along {}; F_s = {} * phi(u), phi {}, "
                        "max phi = {:.6g} at u = {:.6g}; reverse {}; crossing {}; {}{}\n",
                   nblocks, "xyz"[idir], kc, shape.describe(), shape.max_phi(), shape.argmax_phi(),
                   rev_break ? "break" : "periodic", exact ? "exact" : "step",
                   drive_flag ? fmt::format("driving springs K = {} to a stage at {} moving at {}",
                                            kdrive, stage0, vstage)
                              : std::string("no driving springs"),
                   disorder.dist ? "; disorder " + disorder.text : std::string());
  if (rate.active() && comm->me == 0)
    utils::logmesg(lmp, "fix eq/substrate: velocity strengthening F_rate = A asinh(v/(2 v0)), "
                        "A = {}, v0 = {} (viscous damping A/(2 v0) = {:.6g} for |v| << v0)\n",
                   rate.amplitude(), rate.v0(), rate.linear_gamma());
  if (thermal_flag && comm->me == 0)
    utils::logmesg(lmp, "fix eq/substrate: thermal hops: {}; seed {}; theta = k_B T / eps_a = {:.6g}, "
                        "hop rate at zero stretch {:.6g}\n",
                   tkw.text().empty() ? std::string("T = 0") : tkw.text(), tseed,
                   hopper.thermal().params().theta, hopper.rate(0.0, 1.0));

  restart_global = 1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = thermal_flag ? NVEC : NVEC - 1;    // the hop count only with thermal
  global_freq = 1;
  extscalar = 1;
  extvector = -1;
  extlist = new int[NVEC]{0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1};
  energy_global_flag = 1;
  respa_level_support = 1;
  const int ncolumns = thermal_flag ? static_cast<int>(NCOL_THERMAL) : static_cast<int>(NCOL);
  peratom_setup(ncolumns, ncolumns);

  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (atom->mask[i] & groupbit) init_block(i);
  // the outputs before the first run: those of the blocks at their sites
  apply(nullptr);
}

// kc, the shape, then the keywords; returns the stage's X0.  1e400 reads
// as inf: every number of this command must be finite (an infinite
// stiffness, velocity or stage makes NaN forces)
double FixEQSubstrate::parse(int narg, char **arg)
{
  if (narg < 5)
    error->all(FLERR, "Illegal fix eq/substrate command: expected 'fix ID group eq/substrate kc "
                      "<shape> <values> [keyword values ...]' with shape one of: {}", SHAPES);
  if (!atom->tag_enable) error->all(FLERR, "Fix eq/substrate requires atom IDs (atom_modify id yes)");
  kc = EQUtil::numeric(lmp, "Fix eq/substrate: kc", arg[3]);
  if (!(kc >= 0.0) || !std::isfinite(kc))
    error->all(FLERR, "Fix eq/substrate: kc must be finite and >= 0 (got {})", arg[3]);

  const std::vector<std::string> args(arg, arg + narg);
  const feq::NumberParser number = EQUtil::number_parser(lmp);
  size_t iarg = 4;
  double stage0 = 0.0;
  try {
    parse_shape(args, iarg);
    while (iarg < args.size()) {
      const std::string &kw = args[iarg++];
      if (parse_block_keyword(kw, args, iarg, number, stage0)) continue;
      if (kw == "crossing") exact = feq::parse_choice(args, iarg, kw, {"exact", "step"}) == 0;
      else if (kw == "integrator")
        integrator = static_cast<Integrator>(
            feq::parse_choice(args, iarg, kw, {"auto", "verlet", "overdamped"}));
      else if (kw == "reverse")
        rev_break = feq::parse_choice(args, iarg, kw, {"periodic", "break"});
      else if (kw == "disorder") parse_disorder(args, iarg);
      else if (kw == "rate") parse_rate(args, iarg);
      else if (kw == "aging" || kw == "delay" || kw == "rest")
        throw feq::SpecError("keyword '" + kw + "' is one of fix eq/contacts (the age and the "
                             "re-formation delay of a contact): a block of this fix re-enters "
                             "the next well at once and does not age; allowed here: thermal, "
                             "barrier (with seed)");
      else if (feq::parse_thermal_keyword(kw, args, iarg, number, tkw))
        thermal_flag |= kw == "thermal";
      else if (kw == "seed") {
        if (iarg >= args.size()) throw feq::SpecError("seed: missing value");
        const std::string &tok = args[iarg++];
        if (!utils::is_integer(tok) ||
            (tseed = EQUtil::bnumeric(lmp, "Fix eq/substrate seed", tok)) <= 0)
          throw feq::SpecError("seed must be a positive integer (got '" + tok + "')");
      }
      else throw feq::SpecError("unknown keyword '" + kw + "'; allowed: " + KEYWORDS);
    }
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/substrate {}", e.what());
  }
  return stage0;
}

// sawtooth uc, smooth uc or table file keyword
void FixEQSubstrate::parse_shape(const std::vector<std::string> &args, size_t &iarg)
{
  const std::string &style = args[iarg++];
  if (style == "sawtooth" || style == "smooth") {
    const double uc = feq::parse_finite(args, iarg, style + " uc", EQUtil::number_parser(lmp));
    if (!(uc > 0.0)) throw feq::SpecError(style + ": uc must be > 0 (got " + args[iarg - 1] + ")");
    shape = style == "sawtooth" ? feq::SubstrateShape::sawtooth(uc) : feq::SubstrateShape::smooth(uc);
  } else if (style == "table") {
    if (iarg + 2 > args.size())
      throw feq::SpecError("table: expected 2 values (file keyword), got " +
                           std::to_string(args.size() - iarg));
    const std::string file = args[iarg++], key = args[iarg++];
    std::vector<double> u, phi;
    try {
      feq::read_table_text(EQUtil::file_loader(lmp)(file), file, key, u, phi);
    } catch (const feq::SpecError &e) {
      throw feq::SpecError(std::string("table: ") + e.what());
    }
    shape = feq::SubstrateShape::table(u, phi, file + " " + key);
  } else {
    throw feq::SpecError("unknown shape '" + style + "'; allowed: " + SHAPES);
  }
}

// disorder <distribution> seed: the shared parser (role stiffness) with
// messages that name this keyword, and numbers that must be finite
void FixEQSubstrate::parse_disorder(const std::vector<std::string> &args, size_t &iarg)
{
  const feq::NumberParser lmp_number = EQUtil::number_parser(lmp);
  const feq::NumberParser number = [&](const std::string &tok) -> double {
    const double v = lmp_number(tok);
    if (!std::isfinite(v)) throw feq::SpecError("not a finite number");
    return v;
  };
  disorder = feq::parse_distribution(feq::Role::STIFFNESS, args, iarg, number, {},
                                     feq::SpecWording("disorder", "a finite number"));
  if (iarg >= args.size()) throw feq::SpecError("disorder: missing seed after " + disorder.text);
  const std::string &tok = args[iarg++];
  if (!utils::is_integer(tok) ||
      (dseed = EQUtil::bnumeric(lmp, "Fix eq/substrate disorder: seed", tok)) <= 0)
    throw feq::SpecError("disorder: seed must be a positive integer (got '" + tok + "')");
}

// rate A v0: the velocity strengthening of a moving block (lib/eq_substrate
// RateLaw checks the values and names "rate A" or "rate v0")
void FixEQSubstrate::parse_rate(const std::vector<std::string> &args, size_t &iarg)
{
  if (iarg + 2 > args.size())
    throw feq::SpecError("rate: expected 2 values (A v0), got " + std::to_string(args.size() - iarg));
  const feq::NumberParser number = EQUtil::number_parser(lmp);
  const double A = feq::parse_finite(args, iarg, "rate A", number);
  const double v0 = feq::parse_finite(args, iarg, "rate v0", number);
  rate = feq::RateLaw(A, v0);
}

// thermal, barrier and seed together: the hop law of fix eq/contacts for a
// sawtooth block whose contacts break at both ends of its well
void FixEQSubstrate::setup_thermal()
{
  if (!thermal_flag) {
    if (tseed > 0)
      error->all(FLERR, "Fix eq/substrate seed: the seed keys the budgets of thermal hops and "
                        "needs the thermal keyword");
    if (tkw.spec.p != 0.0 || tkw.spec.q != 0.0)
      error->all(FLERR, "Fix eq/substrate barrier: needs the thermal keyword");
    return;
  }
  if (shape.kind() != feq::SubstrateShape::SAWTOOTH)
    error->all(FLERR, "Fix eq/substrate thermal: needs the sawtooth shape (got {}): the hop law "
                      "is that of elastic contacts that break at the end of the well", shape.describe());
  if (!rev_break)
    error->all(FLERR, "Fix eq/substrate thermal: needs 'reverse break': a hop moves the block's "
                      "well origin by u_c ahead of it, which the periodic prolongation of the "
                      "substrate force (reverse periodic, the default) would undo");
  if (tseed <= 0)
    error->all(FLERR, "Fix eq/substrate thermal: needs 'seed S' (a positive integer that keys the "
                      "hazard budgets of the hops)");
  try {
    hopper = feq::BlockHops(tkw.finish(force->boltz, shape.period()), shape.period(),
                            static_cast<uint64_t>(tseed));
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/substrate {}", e.what());
  }
}

// what the arguments must satisfy together (finite energies and forces
// among them); returns the number of blocks
bigint FixEQSubstrate::check(char **arg, double stage0)
{
  if (!drive_flag && stage0 != 0.0)
    error->all(FLERR, "Fix eq/substrate: stage needs the drive keyword (the stage holds the "
                      "driving springs)");
  // the energies are sums over blocks and periods of the work per period W
  // and of K (u - X_s)^2/2; each must stay below 1e300 (sawtooth uc 1e300:
  // W = uc^2/2 = inf)
  const double EMAX = 1e300;
  if (!(shape.work() <= EMAX)) {
    if (shape.kind() == feq::SubstrateShape::SAWTOOTH)
      error->all(FLERR, "Fix eq/substrate sawtooth: uc = {} is too large: the work per period "
                        "uc^2/2 = {} would overflow the energies; allowed: 0 < uc <= {:.6g}",
                 arg[5], shape.work(), std::sqrt(2.0 * EMAX));
    error->all(FLERR, "Fix eq/substrate {}: the work per period W = int_0^uc phi du = {:.6g} would "
                      "overflow the energies; allowed: W <= {:g}", arg[4], shape.work(), EMAX);
  }
  // the largest substrate force k_c d max(phi) and energy per period k_c d W
  const double dmax = disorder.dist ? disorder.dist->effective_upper() : 1.0;
  if (!(kc * dmax * shape.max_phi() <= EMAX) || !(kc * dmax * shape.work() <= EMAX))
    error->all(FLERR, "Fix eq/substrate: kc = {} with the substrate {} (max phi = {:.6g}, work per "
                      "period {:.6g}){} would overflow the forces or energies (kc d max(phi) and "
                      "kc d W must stay <= {:g}): lower kc, uc or the disorder",
               kc, shape.describe(), shape.max_phi(), shape.work(),
               disorder.dist ? fmt::format(" and disorder up to {:.6g}", dmax) : std::string(),
               EMAX);
  if (drive_flag && !(0.5 * kdrive * stage0 * stage0 <= EMAX))
    error->all(FLERR, "Fix eq/substrate stage: X0 = {} is too large for drive K = {}: the "
                      "driving-spring energy K X0^2/2 = {:.6g} would overflow the energies; "
                      "allowed: |X0| <= {:.6g}", stage0, kdrive, 0.5 * kdrive * stage0 * stage0,
               std::sqrt(2.0 * EMAX / kdrive));
  check_stage(stage0);
  if (idir == 2 && domain->dimension == 2)
    error->all(FLERR, "Fix eq/substrate: dir z is not allowed in a 2d simulation; allowed: x, y");
  if (group->dynamic[igroup])
    error->all(FLERR, "Fix eq/substrate: group {} is dynamic; blocks need a static group",
               group->names[igroup]);
  const bigint nblocks = group->count(igroup);
  if (nblocks == 0) error->all(FLERR, "Fix eq/substrate: group {} has no atoms", group->names[igroup]);
  return nblocks;
}

/* ---------------------------------------------------------------------- */

FixEQSubstrate::~FixEQSubstrate()
{
  delete[] extlist;
}

int FixEQSubstrate::setmask()
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

void FixEQSubstrate::init()
{
  init_blocks();
  // minimize: the line search of the energy-based minimizers compares
  // energies, which must include this fix's (min_style fire and quickmin
  // use the forces only)
  if (update->whichflag == 2 && !thermo_energy && update->minimize_style &&
      !utils::strmatch(update->minimize_style, "^fire") &&
      !utils::strmatch(update->minimize_style, "^quickmin"))
    error->all(FLERR, "Fix {} eq/substrate: minimize (min_style {}) needs the substrate energy: add "
                      "fix_modify {} energy yes (or use min_style fire or quickmin)",
               id, update->minimize_style, id);
  const double w = force_window();
  if (exact && w != window && comm->me == 0)
    utils::logmesg(lmp, "fix eq/substrate: crossings corrected for a force window of {} "
                        "({} integrator)\n", w == 1.0 ? "[t_n, t_n+1]" : "[t_n+1/2, t_n+3/2]",
                   w == 1.0 ? "first-order overdamped" : "velocity-Verlet");
  window = w;
  if (rate.active() && w == 1.0 && !ran && comm->me == 0)
    utils::logmesg(lmp, "fix eq/substrate: rate with a first-order integrator: the rate force "
                        "uses the velocity of the previous step (fix brownian stores v = dx/dt); "
                        "stable for A/(2 v0) = {:.6g} < gamma_t\n", rate.linear_gamma());
}

/* ----------------------------------------------------------------------
   the force window of the integrator (crossing exact): given by the
   integrator keyword, or read off the time-integrating fixes that move
   blocks: one that only updates the positions from the current forces
   (initial_integrate alone: first-order overdamped, e.g. fix brownian)
   applies F(x_n) over [t_n, t_n+1], the velocity-Verlet family (initial
   and final integrate) over [t_n+1/2, t_n+3/2].  Both kinds at once
   cannot be read unambiguously: the keyword must say.
------------------------------------------------------------------------- */

double FixEQSubstrate::force_window()
{
  if (integrator == Integrator::VERLET) return 0.5;
  if (integrator == Integrator::OVERDAMPED) return 1.0;
  std::string first, second;
  const int *mask = atom->mask;
  for (int k = 0; k < modify->nfix; k++) {
    Fix *other = modify->fix[k];
    if (!other->time_integrate) continue;
    int mine = 0, any = 0;
    for (int i = 0; i < atom->nlocal && !mine; i++)
      mine = (mask[i] & groupbit) && (mask[i] & other->groupbit);
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, world);
    if (!any) continue;
    std::string &kind = (modify->fmask[k] & FINAL_INTEGRATE) ? second : first;
    if (kind.empty()) kind = fmt::format("fix {} {}", other->id, other->style);
  }
  if (!first.empty() && !second.empty() && exact)
    error->all(FLERR, "Fix {} eq/substrate: its blocks are moved by a first-order integrator ({}) "
                      "and a velocity-Verlet one ({}): the crossing correction cannot tell the force "
                      "window; set integrator verlet or integrator overdamped (or crossing step)",
               id, first, second);
  return first.empty() ? 0.5 : 1.0;
}

void FixEQSubstrate::setup(int vflag)
{
  ran = 1;
  if (utils::strmatch(update->integrate_style, "^verlet"))
    post_force(vflag);
  else {
    static_cast<Respa *>(update->integrate)->copy_flevel_f(ilevel_respa);
    post_force_respa(vflag, ilevel_respa, 0);
    static_cast<Respa *>(update->integrate)->copy_f_flevel(ilevel_respa);
  }
}

void FixEQSubstrate::min_setup(int /*vflag*/)
{
  ran = 1;
  apply(atom->f);
}

void FixEQSubstrate::post_force(int /*vflag*/)
{
  apply(atom->f);
}

void FixEQSubstrate::post_force_respa(int vflag, int ilevel, int /*iloop*/)
{
  if (ilevel == ilevel_respa) post_force(vflag);
}

void FixEQSubstrate::min_post_force(int /*vflag*/)
{
  apply(atom->f);
}

/* ----------------------------------------------------------------------
   a block first seen in the group: its site is where it is now; its
   quenched factor d is a pure function of (seed, atom ID)
------------------------------------------------------------------------- */

void FixEQSubstrate::init_block(int i)
{
  double *s = state[i];
  s[SITE] = EQUtil::Unwrap(atom, domain, idir)(i);
  s[DISP] = s[FSUB] = s[FDRIVE] = s[INTERACT] = 0.0;
  s[KC] = kc;
  s[ANCHOR] = 0.0;
  s[DISORDER] = disorder.dist
      ? disorder.dist->sample(feq::draw(dseed, atom->tag[i], 0, feq::STREAM_STIFFNESS))
      : 1.0;
  if (thermal_flag) {
    s[LIFE] = s[HOPS] = 0.0;
    s[BUDGET] = hopper.budget(static_cast<uint64_t>(atom->tag[i]), 0);
  }
}

// the duration of a step of this fix's force evaluations (its r-RESPA
// level: the time between two of them)
double FixEQSubstrate::step_dt() const
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    return static_cast<Respa *>(update->integrate)->step[ilevel_respa];
  return update->dt;
}

/* ----------------------------------------------------------------------
   F = -k_c d phi + K (X_s - u) along dir.  reverse periodic: phi(u mod
   u_c) and the well origin a = u_c floor(u/u_c); reverse break: a moves
   by u_c when the stretch r = u - a reaches u_c or -u_c, and the force is
   -k_c d sgn(r) phi(|r|).

   crossing exact: F_s jumps by J = +-k_c d (phi(u_c) - phi(0)) where a
   block passes the end of its well.  A time step that crosses it at the
   fraction theta of the step (from the positions before and after, linear
   in between) gave the block the force of one side for the whole window
   the integrator applies a force over: [t_n, t_n+1] for fix brownian
   (w = 1), [t_n+1/2, t_n+3/2] for velocity-Verlet integrators (w = 1/2).
   The missing impulse (w - theta) J dt is added to the force of this step,
   so the crossing no longer costs an error of order dt.  f: the forces
   are added to it (nullptr: the state and outputs only, at definition)
------------------------------------------------------------------------- */

void FixEQSubstrate::apply(double **f)
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int d = idir;
  const EQUtil::Unwrap unwrap(atom, domain, d);
  const double *const hfield = field_h();
  const double Xs = stage;
  const double K = kdrive;
  const double uc = shape.period();
  const double dphi = shape.phi_in(uc) - shape.phi_in(0.0);
  // only during dynamics, where the last evaluation was that of the
  // previous step at the r-RESPA level of this fix (or the setup)
  const bool dynamics = update->whichflag == 1 && update->setupflag == 0;
  const bool correct = dynamics && exact && chained;
  // a block that moves by more than half a period in one step skips parts
  // of the substrate force (time step too large)
  const bool check_jump = dynamics && chained;
  // the setup of a run at the positions of the last evaluation (run N +
  // run N, a restart) keeps its force, the crossing impulse included:
  // the run continues as if it had not been split
  const bool keep = exact && fsub_valid && update->whichflag == 1 && update->setupflag;
  const double half = 0.5 * uc;
  // thermal hops: time passes only between the evaluations of a run
  const double hop_dt = dynamics && chained ? step_dt() : 0.0;
  feq::WellChange changes[feq::BlockHops::MAX_CHANGES];
  int nchange = 0;
  // rate: the drag of the block's velocity, in runs (setup included, as
  // fix viscous), never in a minimization (no time passes)
  const bool rating = f && rate.active() && update->whichflag == 1;
  const double *const *const vel = atom->v;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *const st = state[i];
    if (st[DISORDER] == 0.0) init_block(i);
    const double u = unwrap.displacement(i, st[SITE], st[DISP]);
    if (!std::isfinite(u))
      error->one(FLERR,
                 "Fix eq/substrate: displacement of block {} is {} (numerical instability: "
                 "check the timestep against the stiffest force, k_c, K and the coupling, and the "
                 "integrator)", atom->tag[i], u);
    const double u_old = st[DISP];
    const double a_old = st[ANCHOR];
    if (check_jump && std::fabs(u - u_old) > half) {
      if (njump++ == 0) {
        jump_step = update->ntimestep;
        jump_tag = atom->tag[i];
        jump_size = u - u_old;
      }
    }
    const double kd = st[KC] * st[DISORDER];
    double fs;
    nchange = 0;
    if (keep && u == u_old) {
      fs = st[FSUB];
    } else if (thermal_flag) {
      // sawtooth, reverse break: the walk of lib/eq_substrate (hops and
      // crossings, each a new life with a new budget)
      feq::HopState hs;
      hs.anchor = a_old;
      hs.budget = st[BUDGET];
      hs.life = st[LIFE];
      hs.hops = st[HOPS];
      try {
        nchange = hopper.step(static_cast<uint64_t>(atom->tag[i]), u_old, u, st[DISORDER],
                              hop_dt, exact, hs, changes);
      } catch (const feq::SpecError &e) {
        error->one(FLERR, "Fix eq/substrate thermal: {}", e.what());
      }
      st[ANCHOR] = hs.anchor;
      st[BUDGET] = hs.budget;
      st[LIFE] = hs.life;
      st[HOPS] = hs.hops;
      const double r = u - hs.anchor;
      fs = r >= 0.0 ? -kd * shape.phi_in(r) : kd * shape.phi_in(-r);
    } else if (!rev_break) {
      // most steps stay in the well of the last evaluation: no division
      double r = u - a_old;
      if (!(r >= 0.0 && r < uc)) {
        double n;
        shape.reduce(u, n, r);
        st[ANCHOR] = n * uc;
      }
      fs = -kd * shape.phi_in(r);
    } else {
      double a = a_old;
      double r = u - a;
      if (!(std::fabs(r) < uc)) {
        const double m = std::trunc(r / uc);    // whole periods slipped
        a += m * uc;
        r = u - a;
        if (r >= uc) a += uc, r = u - a;        // rounding
        if (r <= -uc) a -= uc, r = u - a;
        st[ANCHOR] = a;
      }
      fs = r >= 0.0 ? -kd * shape.phi_in(r) : kd * shape.phi_in(-r);
    }
    // the well changed: one impulse correction per change (thermal: at the
    // fraction of the step where each happened)
    if (thermal_flag) {
      if (correct)
        for (int k = 0; k < nchange; ++k)
          fs += (window - changes[k].theta) * changes[k].sign * kd * dphi;
    } else if (correct && st[ANCHOR] != a_old && u != u_old) {
      const double sign = st[ANCHOR] > a_old ? 1.0 : -1.0;
      const double first = rev_break ? a_old + sign * uc : (sign > 0.0 ? a_old + uc : a_old);
      const long nb = std::lround(std::fabs(st[ANCHOR] - a_old) / uc);
      for (long k = 0; k < nb; ++k) {
        const double c = first + sign * k * uc;
        double theta = (c - u_old) / (u - u_old);
        theta = theta < 0.0 ? 0.0 : (theta > 1.0 ? 1.0 : theta);
        fs += (window - theta) * sign * kd * dphi;
      }
    }
    const double fd = drive_flag ? K * (Xs - u) : 0.0;
    if (f) f[i][d] += fs + fd;
    // the rate term scales with the block's contacts, as its shape does
    // (kd / kc = 1 for a block of the default k_c without disorder)
    if (rating) f[i][d] -= rate.force(vel[i][d]) * (kd / kc);
    st[DISP] = u;
    st[FSUB] = fs;
    st[FDRIVE] = fd;
    st[INTERACT] = hfield ? hfield[i] : 0.0;
  }
  ++neval;
  chained = update->whichflag == 1;
  fsub_valid = 1;
}

/* ----------------------------------------------------------------------
   the blocks that moved by more than half a period in one step, counted
   on every rank during the run: one warning on rank 0 with their number
   and the first of them (one reduction per run, none per step)
------------------------------------------------------------------------- */

void FixEQSubstrate::post_run()
{
  FixEQBlocks::post_run();
  bigint total = 0;
  MPI_Allreduce(&njump, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (total > 0) {
    // the first one: the earliest step, on the lowest rank
    struct {
      double step;
      int rank;
    } mine{njump ? static_cast<double>(jump_step) : HUGE_VAL, comm->me}, first{0.0, 0};
    MPI_Allreduce(&mine, &first, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
    double info[3] = {static_cast<double>(jump_tag), jump_size, static_cast<double>(jump_step)};
    MPI_Bcast(info, 3, MPI_DOUBLE, first.rank, world);
    if (comm->me == 0)
      error->warning(FLERR,
                     "Fix eq/substrate: {} moves of a block by more than half the substrate "
                     "period {} in one step in this run (the first: block {} by {} at step {}): "
                     "the time step is too large to resolve F_s",
                     total, shape.period(), static_cast<tagint>(info[0]), info[1],
                     static_cast<bigint>(info[2]));
  }
  njump = 0;
  jump_step = -1;
}

/* ----------------------------------------------------------------------
   global output, reduced on demand (one Allreduce for all entries)
------------------------------------------------------------------------- */

double FixEQSubstrate::compute_scalar()
{
  outputs_before_run();
  reduce();
  return global_sum[S_ESUB] + global_sum[S_EDRIVE];
}

double FixEQSubstrate::compute_vector(int n)
{
  outputs_before_run();
  switch (n) {
    case V_F: return drive_flag ? kdrive * stage : 0.0;
    case V_STAGE: return drive_flag ? stage : 0.0;
    case V_VSTAGE: return drive_flag ? vstage : 0.0;
  }
  reduce();
  const double count = global_sum[S_COUNT];
  switch (n) {
    case V_VEL: return count > 0.0 ? global_sum[S_VEL] / count : 0.0;
    case V_DISP: return count > 0.0 ? global_sum[S_DISP] / count : 0.0;
    case V_FSUB: return global_sum[S_FSUB];
    case V_FDRIVE: return global_sum[S_FDRIVE];
    case V_ESUB: return global_sum[S_ESUB];
    case V_EDRIVE: return global_sum[S_EDRIVE];
    case V_COUNT: return count;
    case V_HOPS: return global_sum[S_HOPS];
  }
  return 0.0;
}

/* ----------------------------------------------------------------------
   sums over the blocks of the last force evaluation (velocities as they
   are now, i.e. at the end of the step for thermo output); one Allreduce
   serves all entries of that evaluation
------------------------------------------------------------------------- */

void FixEQSubstrate::reduce()
{
  if (reduced_eval == neval) return;
  double local[NSUM] = {0.0};
  const double *const *const v = atom->v;
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double Xs = stage;
  const double halfK = 0.5 * kdrive;
  const double uc = shape.period(), W = shape.work();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *st = state[i];
    const double u = st[DISP];
    local[S_VEL] += v[i][idir];
    local[S_DISP] += u;
    local[S_FSUB] -= st[FSUB];
    local[S_FDRIVE] += st[FDRIVE];
    // elastic energy in the current well plus the work W of every net
    // forward slip: continuous in u while no contact breaks backward
    const double r = u - st[ANCHOR];
    local[S_ESUB] += st[KC] * st[DISORDER] * (shape.potential_in(std::fabs(r)) + W * st[ANCHOR] / uc);
    if (drive_flag) local[S_EDRIVE] += halfK * (u - Xs) * (u - Xs);
    local[S_COUNT] += 1.0;
    if (thermal_flag) local[S_HOPS] += st[HOPS];
  }
  MPI_Allreduce(local, global_sum, NSUM, MPI_DOUBLE, MPI_SUM, world);
  reduced_eval = neval;
}

/* ----------------------------------------------------------------------
   fix_modify ID kc GROUP value   k_c of the blocks in GROUP
   fix_modify ID velocity v       stage velocity from now on
------------------------------------------------------------------------- */

int FixEQSubstrate::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "kc") == 0) {
    if (narg < 3)
      error->all(FLERR, "Illegal fix_modify {} kc command: expected 'fix_modify {} kc GROUP value'",
                 id, id);
    const int jgroup = group->find(arg[1]);
    if (jgroup < 0) error->all(FLERR, "Fix_modify {} kc: group {} does not exist", id, arg[1]);
    const double value = EQUtil::numeric(lmp, fmt::format("Fix_modify {} kc", id), arg[2]);
    if (!(value >= 0.0) || !std::isfinite(value))
      error->all(FLERR, "Fix_modify {} kc: value must be finite and >= 0 (got {})", id, arg[2]);
    const double dmax = disorder.dist ? disorder.dist->effective_upper() : 1.0;
    if (!(value * dmax * shape.max_phi() <= 1e300) || !(value * dmax * shape.work() <= 1e300))
      error->all(FLERR, "Fix_modify {} kc: kc = {} with the substrate {} (max phi = {:.6g}, work "
                        "per period {:.6g}) would overflow the forces or energies (kc d max(phi) "
                        "and kc d W must stay <= 1e300)", id, value, shape.describe(),
                 shape.max_phi(), shape.work());
    const int jbit = group->bitmask[jgroup];
    const int *mask = atom->mask;
    for (int i = 0; i < atom->nlocal; i++)
      if ((mask[i] & groupbit) && (mask[i] & jbit)) {
        if (state[i][DISORDER] == 0.0) init_block(i);
        state[i][KC] = value;
      }
    reduced_eval = -1;    // the energies change with k_c
    fsub_valid = 0;       // and the force
    return 3;
  }
  if (const int used = modify_velocity(narg, arg)) return used;
  // LAMMPS handles its own keywords (energy, virial, respa, ...) before
  // asking the fix: anything else is unknown
  error->all(FLERR, "Fix_modify {}: unknown keyword '{}'; allowed: kc, velocity (and LAMMPS' "
                    "energy, virial, respa)", id, arg[0]);
  return 0;
}

/* ----------------------------------------------------------------------
   the per-block state of a restart file: its forces belong to the
   positions it was written at (see apply())
------------------------------------------------------------------------- */

void FixEQSubstrate::unpack_restart(int nlocal, int nth)
{
  FixEQPerAtom::unpack_restart(nlocal, nth);
  fsub_valid = 1;
  restored = 1;
}

// before the first run the outputs follow the positions and k_c
// (displace_atoms, fix_modify kc after the definition); blocks restored
// from a restart file keep the forces of the run that wrote them
void FixEQSubstrate::outputs_before_run()
{
  if (!ran && !restored) apply(nullptr);
}

// a block restored from a restart file: k_c >= 0 and a positive quenched
// factor (0: not set up).  (Its site is not compared with its position:
// the atoms may have been displaced between the last run and
// write_restart.)
void FixEQSubstrate::check_restored(int i)
{
  const double *st = state[i];
  if (st[DISORDER] == 0.0) return;    // not set up yet
  if (!(st[KC] >= 0.0) || !(st[DISORDER] > 0.0))
    error->one(FLERR, "Fix {} eq/substrate: the restart file's block {} is garbled: k_c {} with "
                      "factor {} (a corrupt file)", id, atom->tag[i], st[KC], st[DISORDER]);
  check_reach(i, idir, st[SITE], "site");
  if (thermal_flag && (!(st[BUDGET] >= 0.0) || !(st[LIFE] >= 0.0) || !(st[HOPS] >= 0.0) ||
                       st[HOPS] > st[LIFE] || st[LIFE] != std::floor(st[LIFE])))
    error->one(FLERR, "Fix {} eq/substrate: the restart file's block {} is garbled: hazard budget "
                      "{}, wells entered {}, thermal hops {} (a corrupt file)", id, atom->tag[i],
               st[BUDGET], st[LIFE], st[HOPS]);
}

std::string FixEQSubstrate::layout_hint(long stored) const
{
  if (stored != NCOL && stored != NCOL_THERMAL) return "";
  return fmt::format("the keyword thermal adds {} values per block (hazard budget, wells entered, "
                     "thermal hops); give it in both the run that wrote the file and this one, or "
                     "in neither", NCOL_THERMAL - NCOL);
}
