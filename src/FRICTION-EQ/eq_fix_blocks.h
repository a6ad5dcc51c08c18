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
   FRICTION-EQ package for LAMMPS: what the package's block fixes share
   (fix eq/substrate: FK-ME blocks, Sec. V B; fix eq/meso: lambda_c blocks
   with their own master equation, far zone).

   Each atom of the group is a block with a site (the unwrapped coordinate
   along dir where its displacement u is 0, set when the block is first
   seen).  The displacements are the coordinates of an elastic field
   (pair eq/elastic couples the blocks at the distance of their sites):
   the field reads them when it recomputes (source_coordinates()) and
   follows the positions in between, the sites being fixed; the fix only
   counts its force evaluations for it.  Optional driving springs K tie
   every block to a stage at X_s that moves with velocity v: keywords
   drive K v and stage X0, fix_modify ID velocity v, restart of the stage.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_FIX_BLOCKS_H
#define LMP_EQ_FIX_BLOCKS_H

#include "eq_field.h"
#include "eq_fix_peratom.h"
#include "eq_distribution.h"
#include "eq_record.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixEQBlocks : public FixEQPerAtom, public EQCoordinateSource {
 public:
  FixEQBlocks(class LAMMPS *, int, char **);

  void setup_pre_force(int) override;
  void pre_force(int) override;
  void min_pre_force(int) override;
  void setup_pre_force_respa(int, int) override;
  void pre_force_respa(int, int, int) override;
  void post_integrate() override;
  void post_integrate_respa(int, int) override;
  void post_run() override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // EQCoordinateSource: the blocks' displacements, coupled at the
  // distance of their sites
  const char *eq_name() const override { return name.c_str(); }
  int eq_instance() const override { return instance_me; }
  int source_dir() const override { return idir; }
  int source_groupbit() const override { return groupbit; }
  bool source_site_distance() const override { return true; }
  bigint source_evaluation() const override { return nevaluation; }
  bigint source_version() const override { return 0; }
  const double *source_coordinates() override;
  bool source_changes(bigint, EQChangeSet &) const override { return false; }

 protected:
  std::string name;    // "fix ID style"
  feq::Signature shaping;    // the arguments the stored blocks depend on (set by the derived fix)
  int idir;
  int sitecol;         // column of the site in the per-atom state
  int dispcol;         // column of the displacement of the last evaluation
  int flagcol;         // a column that is 0 until the block is set up
  int ilevel_respa, nlevels_respa;
  // driving springs to the stage at X_s, advanced by v dt every step
  int drive_flag;
  double kdrive, vstage, stage;
  // the elastic field that couples the blocks this run (pair eq/elastic),
  // or none; the displacements it reads; force evaluations begun
  EQHeld<EQElasticField> field;
  std::vector<double> qbuf;
  bigint nevaluation;

  // a block first seen in the group (its site is where it is now)
  virtual void init_block(int i) = 0;
  // the keywords dir, drive, stage; false: not one of them
  bool parse_block_keyword(const std::string &kw, const std::vector<std::string> &args,
                           size_t &iarg, const feq::NumberParser &number, double &stage0);
  // r-RESPA levels and the field (from the derived init())
  void init_blocks();
  // K v and K X0 of the driving springs must be finite (errors name what)
  void check_drive_rate(double k, double v, const char *what);
  void check_stage(double stage0);
  // fix_modify ID velocity v; returns the number of arguments used (0: not it)
  int modify_velocity(int narg, char **arg);
  // displacement u = x - site of every local block (NaN: not a block)
  void displacements(double *u);
  // h of the field at the local blocks now (nullptr: no field this run)
  const double *field_h();
};

}    // namespace LAMMPS_NS

#endif
