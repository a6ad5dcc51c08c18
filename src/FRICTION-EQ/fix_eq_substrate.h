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
   FRICTION-EQ package for LAMMPS: fix eq/substrate

   fix ID group eq/substrate kc shape args keyword values ...

   Each atom of the group is a lambda_c block of the FK-ME model (paper
   Sec. V B): the substrate pulls it back with F_s(u) = k_c,n d_n phi(u),
   u being its unwrapped displacement from its site along the sliding
   direction and phi a periodic shape (sawtooth, smooth, or a table from
   the master equation).  Optional driving springs K tie every block to a
   stage moving with velocity v; optional velocity strengthening (rate A
   v0) adds -A asinh(v/(2 v0)), the block law F_k(v) of T > 0.  See
   doc/src/fix_eq_substrate.rst.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(eq/substrate,FixEQSubstrate);
// clang-format on
#else

#ifndef LMP_FIX_EQ_SUBSTRATE_H
#define LMP_FIX_EQ_SUBSTRATE_H

#include "eq_fix_blocks.h"

#include "eq_distribution.h"
#include "eq_substrate.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixEQSubstrate : public FixEQBlocks {
 public:
  FixEQSubstrate(class LAMMPS *, int, char **);
  ~FixEQSubstrate() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void min_setup(int) override;
  void post_force(int) override;
  void post_force_respa(int, int, int) override;
  void min_post_force(int) override;
  void post_run() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  int modify_param(int, char **) override;
  void unpack_restart(int, int) override;

 protected:
  void check_restored(int i) override;

 public:


  // columns of the per-atom state (also the per-atom output array):
  // displacement u, substrate force -k_c d phi, driving-spring force
  // K (X_s - u), k_c of the block (set by fix_modify kc), quenched factor
  // d, origin a of the block's current well (u - a is the stretch of its
  // contacts; a / u_c counts its slips), site (unwrapped coordinate along
  // dir where u = 0), field h of pair eq/elastic (force -h; 0 without)
  enum { DISP, FSUB, FDRIVE, KC, DISORDER, ANCHOR, SITE, INTERACT, NCOL };
  // with the thermal keyword three more: the hazard budget left of the
  // block's life in its well, the wells it has entered (the counter key of
  // its budgets) and how many of them by a thermal hop
  enum { BUDGET = NCOL, LIFE, HOPS, NCOL_THERMAL };

 private:
  double kc;            // default k_c of a block
  feq::SubstrateShape shape;
  // backward motion: periodic prolongation of F_s, or the block's
  // contacts break at u - a = -u_c as they do at +u_c (reverse break)
  int rev_break;
  // crossing exact: impulse correction where a block passes the end of its
  // well; window: where in the step the integrator applies a force (1: fix
  // brownian's [t_n, t_n+1], 1/2: velocity Verlet's [t_n+1/2, t_n+3/2]),
  // from the integrator keyword or read off the integrating fixes
  enum class Integrator { AUTO, VERLET, OVERDAMPED };
  int exact;
  Integrator integrator;
  double window;
  // quenched disorder of the blocks' k_c (threshold force) factors d_n
  feq::DistributionSpec disorder;
  bigint dseed;
  // thermally activated hops (thermal, barrier, seed keywords)
  int thermal_flag;              // the thermal keyword was given (state layout)
  feq::ThermalKeywords tkw;
  feq::BlockHops hopper;
  bigint tseed;
  // velocity strengthening (rate A v0): -A asinh(v/(2 v0)) along dir
  // during runs, v the block's velocity atom->v (no per-block state)
  feq::RateLaw rate;
  // moves of a block by more than half a period in one step (time step too
  // large), counted on each rank and reported once per run (post_run); the
  // first one of this rank
  bigint njump, jump_step;
  tagint jump_tag;
  double jump_size;

  // sums over the blocks (velocity, displacement, forces, energies, count)
  enum { S_VEL, S_DISP, S_FSUB, S_FDRIVE, S_ESUB, S_EDRIVE, S_COUNT, S_HOPS, NSUM };
  double global_sum[NSUM];
  bigint neval, reduced_eval;    // force evaluations; the one the sums are of
  // the last force evaluation was one of dynamics (a setup or a step, at
  // any r-RESPA level): the displacements it stored are those of the
  // previous (inner) step, so crossings of this one can be located
  int chained;
  // the stored substrate forces (FSUB) are those of the stored
  // displacements (DISP) and the current k_c (see apply())
  int fsub_valid;
  int ran;         // a run or minimization has set this fix up
  int restored;    // blocks came from a restart file
  void outputs_before_run();
  void reduce();

  double parse(int narg, char **arg);
  void parse_shape(const std::vector<std::string> &args, size_t &iarg);
  void parse_disorder(const std::vector<std::string> &args, size_t &iarg);
  void setup_thermal();
  void parse_rate(const std::vector<std::string> &args, size_t &iarg);
  double step_dt() const;
  std::string layout_hint(long stored) const override;
  bigint check(char **arg, double stage0);
  void init_block(int i) override;
  void apply(double **f);
  double force_window();
};

}    // namespace LAMMPS_NS

#endif
#endif
