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
   FRICTION-EQ package for LAMMPS: fix eq/meso

   fix ID group eq/meso Nlambda kc threshold <style> <values> [keyword values ...]

   Each atom of the group is a lambda_c block of the far zone (paper Sec.
   "Far zone", Eqs. crack.eq03x-crack.eq07): it carries its own
   distribution Q_n(u; X_n) of the stretches of its N_lambda contacts,
   advanced by the master equation as the block moves (lib/eq_meso), and
   the interface pulls it back with F_n = N_lambda k_c int u Q_n du.
   Optional screening (scr.eq01-scr.eq05): the breaking rate of block n
   sees the forces scaled by 1 + eps_n, eps_n = x_c sum_m Gamma_m Pi_mn,
   Pi_mn = N_lambda kappa (lambda_c / r_mn)^3 over the blocks within a
   cutoff.  At T > 0 (keywords thermal, barrier) the contacts also break
   thermally at the rate nu((1 + eps) u, x_s) per unit time over each
   step's time (lib/eq_meso_thermal).  See doc/src/fix_eq_meso.rst.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(eq/meso,FixEQMeso);
// clang-format on
#else

#ifndef LMP_FIX_EQ_MESO_H
#define LMP_FIX_EQ_MESO_H

#include "eq_fix_blocks.h"

#include <memory>
#include <string>
#include <vector>

namespace feq {
class BlockModel;
struct ThermalSlider;
}

namespace LAMMPS_NS {

class FixEQMeso : public FixEQBlocks {
 public:
  FixEQMeso(class LAMMPS *, int, char **);
  ~FixEQMeso() override;
  int setmask() override;
  void init() override;
  void reset_dt() override;
  void init_list(int, class NeighList *) override;
  void setup(int) override;
  void min_setup(int) override;
  void post_force(int) override;
  void post_force_respa(int, int, int) override;
  void min_post_force(int) override;
  double compute_scalar() override;
  double compute_vector(int) override;
  int modify_param(int, char **) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  void unpack_restart(int, int) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int unpack_exchange(int, double *) override;

 protected:
  void check_restored(int i) override;
  void check_fixed_delay(const char *when);

 public:
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

  // columns of the per-atom state; the first NOUT are the per-atom output:
  // displacement X, friction force F = N_lambda k_c <u>, breaking rate
  // Gamma (breaks per contact and unit displacement, averaged over the
  // last `window` of forward motion),
  // screening eps, driving-spring force, attached fraction, site; then a
  // set-up flag and the block's master-equation state (lib/eq_meso)
  enum { M_DISP, M_FORCE, M_RATE, M_EPS, M_FDRIVE, M_ATTACHED, M_SITE, M_FLAG, M_HEAD };
  static constexpr int NOUT = M_SITE + 1;

 private:
  std::unique_ptr<feq::BlockModel> model;    // lib/eq_meso (athermal) or lib/eq_meso_thermal
  int thermal_kernel;    // lib/eq_meso_thermal: thermal with T > 0, or aging or delay
  double hstep;        // time of the current step (0 at set-up)
  double respa_step;   // time of a step of the rRESPA level (0: update->dt)
  int in_setup;
  double nlambda, kc, xc;    // contacts per block, their stiffness, mean threshold
  // screening: Pi(r) = nlambda kappa (lambda_c / r)^3 for r <= rcut
  int screen_flag;
  double kappa, lambda_c, rcut;
  double window;       // the breaking rate is averaged over this much displacement
  class NeighList *list;
  // the blocks in the neighbor list of each local block (within rcut +
  // skin), sorted by atom ID so that eps is the same sum on any number of
  // ranks: pj[first[2i] .. first[2i+1])
  std::vector<int> first, pj;
  double pi0_max;      // largest sum_m Pi_mn over the blocks at the last list build
  double threshold_sd;    // standard deviation of the thresholds (the grid's scale)
  feq::DistributionPtr thresholds;
  // the thermal kernel's contacts (spec, thresholds, re-forming) for its
  // default grid with screen (screened_grid()); null otherwise
  std::shared_ptr<const feq::ThermalSlider> screen_slider;
  double screened_v = 0.0;    // the velocity the default grid was made for (0: none yet)
  int grid_restored = 0;      // the default grid came from a restart file
  std::string thermal_keyword, thermal_cause;    // what chose the thermal kernel (messages)
  int grid_warned;     // the warning on a grid too coarse for the screened thresholds was given
  // the grid: the user's (grid keyword), or the default, chosen for the
  // screened thresholds at the setup of every run while every block is
  // fresh (grid_fresh: they were at the last set-up); restart files carry
  // the grid of their blocks
  int grid_default, grid_fresh;
  double window_safe;    // smallest safe window with screening (lib meso_min_window)
  double fixed_tau = 0.0;    // delay fixed tau (0: none): at most MESO_DELAY_BINS - 2 steps
  int window_warned;
  int eps_warned;      // the warning on a load factor beyond the thermal grid's accuracy (this rank)
  double pi0_local;    // largest sum_m Pi_mn of this rank's blocks at the last step
  bigint list_stamp;   // neighbor->ncalls of the partners (-1: none)
  int screened;        // the screening has been computed (pi0_local holds)
  int ran;             // a run or minimization has set this fix up
  int restored;        // blocks came from a restart file
  void outputs_before_run();
  void check_screened_grid();
  void check_thermal_grid(int i, double eps);
  void check_window();
  void choose_grid();
  double screened_grid(std::string &how);
  void set_grid(double du);
  bool all_fresh();
  void gather_columns(bool rates);
  double lattice_sums(bool eps_update, bool rebuilt);
  int comm_mode;
  std::vector<double> cbuf;    // forward communication: rate and displacement per atom
  // normalization check of the blocks' Q every check_every steps
  int check_every;
  double norm_max;

  enum { S_FORCE, S_RATE, S_EPS, S_DISP, S_FDRIVE, S_COUNT, NSUM };
  double local_sum[NSUM], global_sum[NSUM];
  bigint neval, reduced_eval;
  // the per-atom output array (a copy of the state's first NOUT columns)
  double **out;
  void publish(int i);

  struct Args;
  void parse(int narg, char **arg, Args &a);
  void parse_screen(const std::vector<std::string> &args, size_t &iarg);
  void make_model(Args &a);
  bigint check(const Args &a);
  void init_block(int i) override;
  void apply(bool advance, double **f);
  void partners();
  // the ghost atom cutoff must hold rcut + skin (error naming screen)
  void check_ghost_cutoff(double have);
  void screening();
  void check_normalization();
  void reduce();
};

}    // namespace LAMMPS_NS

#endif
#endif
