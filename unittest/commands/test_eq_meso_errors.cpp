// Bad input to fix eq/meso gives a LAMMPS error that names the command,
// the keyword and the allowed values; a restart file of another grid is
// refused; screening with Pi0 >= 1 is refused.
#include "lammps.h"

#include "atom.h"
#include "fix.h"
#include "input.h"
#include "modify.h"

#include "testing/core.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <cstdio>
#include <mpi.h>

bool verbose = false;

namespace {

class EQMesoErrors : public LAMMPSTest {
 protected:
  void InitSystem() override
  {
    HIDE_OUTPUT([&] {
      command("units lj");
      command("dimension 2");
      command("atom_style atomic");
      command("lattice sq 1.0");
      command("region box block 0 6 0 3 -0.5 0.5");
      command("create_box 1 box");
      command("create_atoms 1 box");
      command("mass 1 1.0");
      command("group nobody empty");
      command("comm_modify cutoff 2.0");
    });
  }
  void fix(const std::string &rest) { command("fix m all eq/meso " + rest); }
};

const char *T = "threshold uniform 0.75 1.25";

}    // namespace

TEST_F(EQMesoErrors, ValidCommandsAreAccepted)
{
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T);
    command("unfix m");
    fix("50 2.0 threshold realistic 1.0 reform gaussian 0.05 0.1 grid 0.05 dir y crossing step "
        "start reform drive 0.5 1e-3 stage 2.0 screen 0.001 1.0 1.5 window 0.2 check 10");
    command("fix_modify m velocity -1e-3");
    command("run 0 post no");
  });
  ASSERT_NE(lmp->modify->find_fix("m"), -1);
}

TEST_F(EQMesoErrors, Arguments)
{
  TEST_FAILURE(".*ERROR: Illegal fix eq/meso command: expected 'fix ID group eq/meso Nlambda kc "
               "threshold <style> <values> \\[keyword values ...\\]'.*",
               fix("100 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso: Nlambda \\(contacts per block\\) must be finite and > 0 "
               "\\(got 0\\).*",
               fix(std::string("0 1.0 ") + T););
  TEST_FAILURE(".*ERROR: Fix eq/meso: Nlambda: expected a number, got 'many'.*",
               fix(std::string("many 1.0 ") + T););
  TEST_FAILURE(".*ERROR: Fix eq/meso: kc must be finite and > 0 \\(got -1\\).*",
               fix(std::string("100 -1 ") + T););
  TEST_FAILURE(".*ERROR: Fix eq/meso: kc must be finite and > 0 \\(got 1e400\\).*",
               fix(std::string("100 1e400 ") + T););
  TEST_FAILURE(".*ERROR: Fix eq/meso: the threshold keyword is required; allowed styles: uniform, "
               "gaussian, realistic, table.*",
               fix("100 1.0 reform delta 0.0 grid 0.01"););
  TEST_FAILURE(".*ERROR: Fix eq/meso unknown keyword 'speed'; allowed: threshold, reform, grid, "
               "dir, crossing, start, drive, stage, screen, window, check.*",
               fix(std::string("100 1.0 ") + T + " speed 2"););
  TEST_FAILURE(".*ERROR: Fix eq/meso grid: du must be > 0 \\(got -0.01\\).*",
               fix(std::string("100 1.0 ") + T + " grid -0.01"););
  // a grid that does not resolve the thresholds (0.25 sd = 0.036)
  TEST_FAILURE(".*ERROR: Fix eq/meso grid: spacing 0.1 is too coarse for threshold uniform 0.75 "
               "1.25.*",
               fix(std::string("100 1.0 ") + T + " grid 0.1"););
  TEST_FAILURE(".*ERROR: Fix eq/meso dir: unknown value 'w'; allowed: x, y, z.*",
               fix(std::string("100 1.0 ") + T + " dir w"););
  TEST_FAILURE(".*ERROR: Fix eq/meso: dir z is not allowed in a 2d simulation; allowed: x, y.*",
               fix(std::string("100 1.0 ") + T + " dir z"););
  TEST_FAILURE(".*ERROR: Fix eq/meso crossing: unknown value 'late'; allowed: exact, step.*",
               fix(std::string("100 1.0 ") + T + " crossing late"););
  TEST_FAILURE(".*ERROR: Fix eq/meso start: unknown value 'now'; allowed: relaxed, reform.*",
               fix(std::string("100 1.0 ") + T + " start now"););
  TEST_FAILURE(".*ERROR: Fix eq/meso drive: K must be > 0 \\(got 0\\).*",
               fix(std::string("100 1.0 ") + T + " drive 0 1e-3"););
  TEST_FAILURE(".*ERROR: Fix eq/meso: stage needs the drive keyword.*",
               fix(std::string("100 1.0 ") + T + " stage 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso screen: kappa must be >= 0 \\(got -0.1\\).*",
               fix(std::string("100 1.0 ") + T + " screen -0.1 1.0 1.5"););
  TEST_FAILURE(".*ERROR: Fix eq/meso screen: lambda_c must be > 0 \\(got 0\\).*",
               fix(std::string("100 1.0 ") + T + " screen 0.1 0 1.5"););
  TEST_FAILURE(".*ERROR: Fix eq/meso screen rcut: expected a finite number, got '1e400'.*",
               fix(std::string("100 1.0 ") + T + " screen 0.1 1.0 1e400"););
  TEST_FAILURE(".*ERROR: Fix eq/meso screen rcut: expected a number, got 'far'.*",
               fix(std::string("100 1.0 ") + T + " screen 0.1 1.0 far"););
  TEST_FAILURE(".*ERROR: Fix eq/meso window: w must be > 0 \\(got 0\\).*",
               fix(std::string("100 1.0 ") + T + " window 0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso check: steps must be an integer >= 0 \\(0: never; got -3\\).*",
               fix(std::string("100 1.0 ") + T + " check -3"););
  TEST_FAILURE(".*ERROR: Fix eq/meso start: 'reform' needs a reform distribution.*",
               fix(std::string("100 1.0 ") + T + " reform none start reform"););
  TEST_FAILURE(".*ERROR: Fix eq/meso: group nobody has no atoms.*",
               command(std::string("fix m nobody eq/meso 100 1.0 ") + T););
}

// screening whose block-block coupling sums to Pi0 >= 1 has no screened
// solution: refused at the first neighbor list build, naming the keyword
TEST_F(EQMesoErrors, ScreeningWithoutSolution)
{
  HIDE_OUTPUT([&] { fix(std::string("100 1.0 ") + T + " screen 0.003 1.0 1.01"); });
  TEST_FAILURE(".*ERROR: Fix eq/meso screen: Pi0 = sum_m Pi_mn = 1.2 >= 1 at block [0-9]+: no "
               "screened solution \\(eps0 = Pi0/\\(1 - Pi0\\) diverges\\); lower kappa \\(0.003\\) or "
               "rcut \\(1.01\\).*",
               command("run 0 post no"););
}

// Pi0 = 4 x 100 x 0.002325 = 0.93: the screened thresholds x_s/(1 + eps0)
// have the standard deviation 0.144338 (1 - Pi0) = 0.0101; the default
// grid 0.144338/8 = 0.0180 resolves it with 0.56 cells: a warning, once;
// a grid of 0.002 (5 cells) none
TEST_F(EQMesoErrors, GridTooCoarseForTheScreening)
{
  HIDE_OUTPUT([&] { fix(std::string("100 1.0 ") + T + " screen 0.002325 1.0 1.01 grid 0.0180422"); });
  ::testing::internal::CaptureStdout();
  command("run 0 post no");
  command("run 0 post no");
  std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_THAT(out, ::testing::HasSubstr("WARNING: Fix m eq/meso: grid 0.0180422 resolves the "
                                        "screened thresholds x_s/(1 + eps0) (Pi0 = 0.93, eps0 = "
                                        "Pi0/(1 - Pi0) = 13.2857) with 0.56 cells per standard "
                                        "deviation, fewer than 4"));
  EXPECT_THAT(out, ::testing::HasSubstr("grid 0.00126 (1/8 of the screened standard deviation)"));
  EXPECT_EQ(out.find("WARNING: Fix m eq/meso: grid"), out.rfind("WARNING: Fix m eq/meso: grid"));
  HIDE_OUTPUT([&] {
    command("unfix m");
    fix(std::string("100 1.0 ") + T + " screen 0.002325 1.0 1.01 grid 0.002");
  });
  ::testing::internal::CaptureStdout();
  command("run 0 post no");
  out = ::testing::internal::GetCapturedStdout();
  EXPECT_THAT(out, ::testing::Not(::testing::HasSubstr("WARNING: Fix m eq/meso: grid")));
}

// partners beyond the ghost cutoff would be missed (LAMMPS from 2022 on
// refuses the neighbor list itself; 29 Sep 2021 does not: the fix does)
TEST_F(EQMesoErrors, GhostCutoff)
{
  HIDE_OUTPUT([&] {
    command("comm_modify cutoff 1.0");
    fix(std::string("100 1.0 ") + T + " screen 0.001 1.0 1.5");
  });
  TEST_FAILURE(".*ERROR: (Fix eq/meso screen: rcut 1.5 \\+ neighbor skin .* exceeds the ghost "
               "atom cutoff .*; partners would be missed: set comm_modify cutoff .* or more|Custom "
               "neighbor list cutoff .* is too large for communication cutoff 1).*",
               command("run 0 post no"););
}

// the per-block state of a restart file belongs to one grid and one set
// of distributions: another width is refused
TEST_F(EQMesoErrors, RestartOfAnotherGrid)
{
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02");
    command("run 0 post no");
    command("write_restart eq_meso_grid.restart");
    command("clear");
    command("read_restart eq_meso_grid.restart");
  });
  TEST_FAILURE(".*ERROR: Fix m eq/meso: grid differs from that of the run that wrote the restart "
               "file: the stored blocks were made with the other grid; re-specify grid as in that "
               "run.*",
               fix(std::string("100 1.0 ") + T + " grid 0.01"););
  std::remove("eq_meso_grid.restart");
}

// the same width, other thresholds: refused by the signature of the
// blocks' settings in the restart file
TEST_F(EQMesoErrors, RestartOfOtherThresholds)
{
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02");
    command("run 0 post no");
    command("write_restart eq_meso_thr.restart");
    command("clear");
    command("read_restart eq_meso_thr.restart");
  });
  TEST_FAILURE(".*ERROR: Fix m eq/meso: threshold differs from that of the run that wrote the "
               "restart file.*",
               fix("100 1.0 threshold uniform 0.7 1.25 grid 0.02"););
  std::remove("eq_meso_thr.restart");
}

// T > 0: keywords thermal, barrier, labels, delay (lib eq_meso_thermal)
TEST_F(EQMesoErrors, Thermal)
{
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 barrier 1.0 0.5 labels 8");
    command("run 0 post no");
    command("unfix m");
    // T = 0: the athermal kernel (no grid needed)
    fix(std::string("100 1.0 ") + T + " thermal 0.0 1.0 1.0");
    command("unfix m");
    // delay exp at T > 0; delay none or a zero tau: no delay, also at T = 0
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay exp 10");
    command("run 0 post no");
    command("unfix m");
    fix(std::string("100 1.0 ") + T + " delay none");
    command("unfix m");
    fix(std::string("100 1.0 ") + T + " delay exp 0");
    command("unfix m");
  });
  // the default grid serves the thermal kernel without screening, not with it
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " thermal 0.05 1.0 1.0");
    command("unfix m");
  });
  // (at a run's set-up with fresh blocks: a restart file may bring the grid)
  TEST_FAILURE(".*ERROR: Fix m eq/meso thermal: with screen needs the grid keyword, or drive with "
               "contacts that re-form \\(this run sets up blocks that have not moved, with "
               "screening partners, and no restart file gave them a grid; at T > 0 the.*",
               fix(std::string("100 1.0 ") + T + " thermal 0.05 1.0 1.0 screen 0.001 1.0 1.01");
               command("run 0 post no"););
  TEST_FAILURE(".*ERROR: Fix m eq/meso thermal: with screen needs the grid keyword, or drive with "
               "contacts that re-form.*",
               fix(std::string("100 1.0 ") + T + " thermal 0.05 1.0 1.0 screen 0.001 1.0 1.01 "
                   "drive 1.0 1e-3 reform none");
               command("run 0 post no"););
  TEST_FAILURE(".*ERROR: Fix m eq/meso drive: the default grid with screen at T > 0, with aging or "
               "with a delay needs a velocity v != 0.*",
               fix(std::string("100 1.0 ") + T + " thermal 0.05 1.0 1.0 screen 0.001 1.0 1.01 "
                   "drive 1.0 0.0");
               command("run 0 post no"););
  // with drive the default grid is made at the first run, for the drive's velocity
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " thermal 0.05 1.0 1.0 screen 0.001 1.0 1.01 drive 1.0 1e-3");
    command("run 0 post no");
    command("unfix m");
  });
  TEST_FAILURE(".*ERROR: Fix eq/meso thermal omega: must be > 0 \\(got 0\\).*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso thermal T: expected a number, got 'hot'.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal hot 1.0 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso barrier q: must be >= 0 \\(got -1\\).*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 barrier 0 -1"););
  TEST_FAILURE(".*ERROR: Fix eq/meso barrier: needs thermal with T > 0.*",
               fix(std::string("100 1.0 ") + T + " barrier 1 0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso labels: expected an integer from 1 to 4096.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 labels 2.5"););
  // delay exp (lib: a waiting pool), delay fixed (a FIFO)
  // delay fixed: at most MESO_DELAY_BINS - 2 = 1022 steps in flight (timestep 0.005 here)
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay fixed 5.11");
    command("run 0 post no");
    command("unfix m");
  });
  TEST_FAILURE(".*ERROR: Fix m eq/meso delay fixed: tau = 5.111 is 1022.2 time steps, more than the "
               "1022 a block holds in flight; use a larger timestep, a shorter delay or delay "
               "exp.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay fixed 5.111");
               command("run 0 post no"););
  HIDE_OUTPUT([&] { command("unfix m"); });
  // r-RESPA: the fix advances once per step of its level (run_style respa
  // 2 4: the inner level's step is 0.005/4; tau = 2 is 400 outer steps,
  // 1600 inner ones)
  HIDE_OUTPUT([&] {
    command("run_style respa 2 4");
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay fixed 2.0");
    command("run 0 post no");
  });
  TEST_FAILURE(".*ERROR: Fix m eq/meso delay fixed: tau = 2 is 1600 time steps of r-RESPA level 1 "
               "\\(step 0.00125\\), more than the 1022 a block holds in flight; use a larger "
               "timestep, a shorter delay or delay exp.*",
               command("fix_modify m respa 1"); command("run 0 post no"););
  HIDE_OUTPUT([&] {
    command("unfix m");
    command("run_style verlet");
  });
  // fix dt/reset changes the timestep without init(): checked in reset_dt()
  // (tau = 5: 1000 steps of 0.005, 50000 of 1e-4)
  TEST_FAILURE(".*ERROR: Fix m eq/meso delay fixed: tau = 5 is 50000 time steps after the "
               "timestep changed within the run \\(fix dt/reset\\), more than the 1022 a block "
               "holds in flight.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay fixed 5.0");
               command("fix dtr all dt/reset 1 NULL 1e-4 0.01 units box");
               command("run 2 post no"););
  HIDE_OUTPUT([&] {
    command("unfix dtr");
    command("unfix m");
    command("timestep 0.005");
    // the timestep command between runs (it calls reset_dt() too): no
    // error while the script may still change the fix ...
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay fixed 5.0");
    command("timestep 1e-4");
    command("unfix m");
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay fixed 5.0");
    command("timestep 1e-4");
  });
  // ... and the next run's init() checks
  TEST_FAILURE(".*ERROR: Fix m eq/meso delay fixed: tau = 5 is 50000 time steps, more than the "
               "1022 a block holds in flight.*",
               command("run 0 post no"););
  HIDE_OUTPUT([&] {
    command("unfix m");
    command("timestep 0.005");
  });
  TEST_FAILURE(".*ERROR: Fix eq/meso delay tau: must be >= 0 \\(got -1\\).*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay exp -1"););
  TEST_FAILURE(".*ERROR: Fix eq/meso delay tau: expected a number, got 'long'.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay exp long"););
  TEST_FAILURE(".*ERROR: Fix eq/meso delay: unknown value 'gamma'; allowed: none, fixed, exp.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 delay gamma 1"););
  // at T = 0 a delay takes the thermal kernel (theta = 0), which needs a grid
  TEST_FAILURE(".*ERROR: Fix m eq/meso delay: with screen needs the grid keyword, or drive with "
               "contacts that re-form \\(this run sets up .*; with a formation delay.*",
               fix(std::string("100 1.0 ") + T + " delay exp 1 screen 0.001 1.0 1.01");
               command("run 0 post no"););
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.0 1.0 1.0 delay exp 1 labels 8");
    command("run 0 post no");
    command("unfix m");
  });
  TEST_FAILURE(".*ERROR: Fix eq/meso delay: needs re-forming contacts \\(reform delta 0\\), not "
               "reform none.*",
               fix(std::string("100 1.0 ") + T + " reform none grid 0.02 thermal 0.05 1.0 1.0 "
                   "delay exp 1"););
  // aging and rest at T > 0 (the thermal kernel keeps the ages)
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 aging exp 0.2 5 rest 10 "
        "delay exp 3");
    command("run 0 post no");
    command("unfix m");
  });
  // at T = 0: aging takes the thermal kernel; rest alone changes nothing
  TEST_FAILURE(".*ERROR: Fix m eq/meso aging: with screen needs the grid keyword, or drive with "
               "contacts that re-form \\(this run sets up .*; with threshold aging.*",
               fix(std::string("100 1.0 ") + T + " screen 0.001 1.0 1.01 aging log 0.1 1");
               command("run 0 post no"););
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02 aging log 0.1 1 rest 10");
    command("run 0 post no");
    command("unfix m");
  });
  TEST_FAILURE(".*ERROR: Fix eq/meso rest: needs aging, delay or thermal with T > 0.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.0 1.0 1.0 rest 10"););
  TEST_FAILURE(".*ERROR: Fix eq/meso barrier: needs thermal with T > 0.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 aging log 0.1 1 barrier 1 0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso aging tau_a: must be > 0 \\(got 0\\).*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 aging log 0.1 0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso reform gaussian 0.05 0.1: with the thermal kernel \\(thermal at T > 0, "
               "aging or delay\\), contacts re-form "
               "unstretched \\(reform delta 0\\) or never \\(reform none\\).*",
               fix(std::string("100 1.0 ") + T +
                   " reform gaussian 0.05 0.1 grid 0.02 thermal 0.05 1.0 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/meso grid: spacing 1e-05 needs about .* doubles per block with 32 "
               "threshold panels.*",
               fix(std::string("100 1.0 ") + T + " grid 1e-5 thermal 0.05 1.0 1.0"););
}

TEST_F(EQMesoErrors, ThermalRestartOfTheOtherKind)
{
  const std::string file = "eq_meso_kind.restart";
  // blocks of fix m with these keywords written after run 0, then read
  // back into a cleared LAMMPS (the box of InitSystem())
  auto written_with = [&](const std::string &keywords, bool fresh_box) {
    if (fresh_box) {
      HIDE_OUTPUT([&] { command("clear"); });
      InitSystem();    // (hides its own output)
    }
    HIDE_OUTPUT([&] {
      fix(std::string("100 1.0 ") + T + " grid 0.02" + keywords);
      command("run 0 post no");
      command("write_restart " + file);
      command("clear");
      command("read_restart " + file);
    });
  };
  written_with("", false);
  TEST_FAILURE(".*ERROR: Fix m eq/meso thermal: the restart file's blocks were made athermal.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0"););
  written_with(" thermal 0.05 1.0 1.0", true);
  TEST_FAILURE(".*ERROR: Fix m eq/meso thermal: the restart file's blocks were made by the "
               "thermal kernel \\(thermal with T > 0, aging or delay\\).*",
               fix(std::string("100 1.0 ") + T + " grid 0.02"););
  written_with(" aging log 0.1 1", true);
  TEST_FAILURE(".*ERROR: Fix m eq/meso thermal: the restart file's blocks were made by the "
               "thermal kernel.*",
               fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.0 1.0 1.0"););
  // blocks written without a delay read with one (and the reverse), with
  // another aging law or without aging: the signature's keyword thermal
  // carries the delay and the aging
  for (const char *pair : {"|delay exp 10", "delay exp 10|", "aging log 0.1 1|aging exp 0.1 1",
                           "aging log 0.1 1|aging log 0.1 2", "|aging log 0.1 1"}) {
    const std::string spec(pair), w = spec.substr(0, spec.find('|')),
                                  r = spec.substr(spec.find('|') + 1);
    written_with(" thermal 0.05 1.0 1.0 " + w, true);
    TEST_FAILURE(".*ERROR: Fix m eq/meso: thermal differs from that of the run that wrote the "
                 "restart file.*",
                 fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 " + r););
  }
  // the rest age sets up the blocks the fix defines; restored blocks keep
  // their ages, so another rest is not a conflict
  written_with(" thermal 0.05 1.0 1.0 aging log 0.1 1 rest 10", true);
  HIDE_OUTPUT([&] {
    fix(std::string("100 1.0 ") + T + " grid 0.02 thermal 0.05 1.0 1.0 aging log 0.1 1 rest 20");
    command("run 0 post no");
  });
  std::remove(file.c_str());
}

TEST_F(EQMesoErrors, FixModify)
{
  HIDE_OUTPUT([&] { fix(std::string("100 1.0 ") + T); });
  TEST_FAILURE(".*ERROR: Fix_modify m velocity: fix m has no stage \\(add the drive keyword\\).*",
               command("fix_modify m velocity 1e-3"););
  TEST_FAILURE(".*ERROR: Fix_modify m: unknown keyword 'kc'; allowed: velocity \\(and LAMMPS' "
               "energy, virial, respa\\).*",
               command("fix_modify m kc all 0.5"););
}

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleMock(&argc, argv);
  if (argc > 1 && std::string(argv[1]) == "-v") verbose = true;
  const int rv = RUN_ALL_TESTS();
  MPI_Finalize();
  return rv;
}
