// Bad input to fix eq/substrate, its fix_modify keywords, the eq/me
// substrate table and pair eq/elastic with blocks gives a LAMMPS error that
// names the command, the keyword and the allowed values.  Also: what a
// restart file restores of the stage.
#include "lammps.h"

#include "atom.h"
#include "fix.h"
#include "group.h"
#include "input.h"
#include "modify.h"

#include "testing/core.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <mpi.h>

bool verbose = false;

namespace {

class EQSubstrateErrors : public LAMMPSTest {
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
      command("group left id 1 2 3");
    });
  }
  void fix(const std::string &rest) { command("fix s all eq/substrate " + rest); }
};

}    // namespace

TEST_F(EQSubstrateErrors, ValidCommandsAreAccepted)
{
  HIDE_OUTPUT([&] {
    fix("1.0 sawtooth 1.0");
    command("unfix s");
    fix("2.0 smooth 1.5 dir y drive 0.07 1e-4 stage 12.0 reverse break disorder gaussian 1.0 0.02 9");
    command("fix_modify s kc left 0.5 velocity -2e-4 energy yes");
    command("unfix s");
    {
      std::ofstream out("eq_sub_ok.table");
      out << "BLOCK\nN 3\n\n1 0.0 0.0\n2 0.5 1.0\n3 1.0 0.8\n";
    }
    fix("1.0 table eq_sub_ok.table BLOCK reverse periodic disorder uniform 0.9 1.1 3");
    command("run 0 post no");
  });
  std::remove("eq_sub_ok.table");
  ASSERT_NE(lmp->modify->find_fix("s"), -1);
}

TEST_F(EQSubstrateErrors, Arguments)
{
  TEST_FAILURE(".*ERROR: Illegal fix eq/substrate command: expected 'fix ID group eq/substrate kc "
               "<shape> <values> \\[keyword values ...\\]' with shape one of: sawtooth, smooth, "
               "table.*",
               fix("1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate: kc must be finite and >= 0 \\(got -1\\).*",
               fix("-1 sawtooth 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate: kc: expected a number, got 'abc'.*",
               fix("abc sawtooth 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate unknown shape 'sine'; allowed: sawtooth, smooth, table.*",
               fix("1.0 sine 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate sawtooth: uc must be > 0 \\(got 0\\).*",
               fix("1.0 sawtooth 0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate smooth uc: expected a number, got 'one'.*",
               fix("1.0 smooth one"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate sawtooth uc: missing value.*", fix("1.0 sawtooth"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate unknown keyword 'speed'; allowed: dir, drive, stage, "
               "reverse, crossing, integrator, disorder.*",
               fix("1.0 sawtooth 1.0 speed 1"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate dir: unknown value 'w'; allowed: x, y, z.*",
               fix("1.0 sawtooth 1.0 dir w"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate: dir z is not allowed in a 2d simulation; allowed: x, y.*",
               fix("1.0 sawtooth 1.0 dir z"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate drive: K must be > 0 \\(got 0\\).*",
               fix("1.0 sawtooth 1.0 drive 0 1e-4"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate drive v: missing value.*",
               fix("1.0 sawtooth 1.0 drive 0.07"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate: stage needs the drive keyword.*",
               fix("1.0 sawtooth 1.0 stage 3.0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate reverse: unknown value 'back'; allowed: periodic, break.*",
               fix("1.0 sawtooth 1.0 reverse back"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate crossing: unknown value 'late'; allowed: exact, step.*",
               fix("1.0 sawtooth 1.0 crossing late"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder uniform: need 0 < lo < hi \\(got lo = 1.1, "
               "hi = 0.9\\).*",
               fix("1.0 sawtooth 1.0 disorder uniform 1.1 0.9 5"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder unknown style 'weibull'; allowed: constant, "
               "uniform, gaussian.*",
               fix("1.0 sawtooth 1.0 disorder weibull 1 2 5"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder: missing seed after gaussian 1 0.02.*",
               fix("1.0 sawtooth 1.0 disorder gaussian 1.0 0.02"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder: seed must be a positive integer \\(got "
               "'-4'\\).*",
               fix("1.0 sawtooth 1.0 disorder gaussian 1.0 0.02 -4"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate: group nobody has no atoms.*",
               command("fix s nobody eq/substrate 1.0 sawtooth 1.0"););
  HIDE_OUTPUT([&] {
    command("region left block 0 2 INF INF INF INF");
    command("group moving dynamic all region left");
  });
  TEST_FAILURE(".*ERROR: Fix eq/substrate: group moving is dynamic; blocks need a static group.*",
               command("fix s moving eq/substrate 1.0 sawtooth 1.0"););
}

// utils::numeric reads 1e400 as inf: every number must be finite
TEST_F(EQSubstrateErrors, NonFiniteNumbers)
{
  TEST_FAILURE(".*ERROR: Fix eq/substrate: kc must be finite and >= 0 \\(got 1e400\\).*",
               fix("1e400 sawtooth 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate sawtooth uc: expected a finite number, got '1e400'.*",
               fix("1.0 sawtooth 1e400"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate drive K: expected a finite number, got '1e400'.*",
               fix("1.0 sawtooth 1.0 drive 1e400 1e-4"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate drive v: expected a finite number, got '-1e400'.*",
               fix("1.0 sawtooth 1.0 drive 0.07 -1e400"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate stage X0: expected a finite number, got '1e400'.*",
               fix("1.0 sawtooth 1.0 drive 0.07 1e-4 stage 1e400"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder uniform: expected a finite number for hi, got "
               "'1e400'.*",
               fix("1.0 sawtooth 1.0 disorder uniform 0.9 1e400 5"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder gaussian: expected a finite number for sd, got "
               "'1e400'.*",
               fix("1.0 sawtooth 1.0 disorder gaussian 1.0 1e400 5"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder gaussian: expected a finite number for mean, "
               "got '1e400'.*",
               fix("1.0 sawtooth 1.0 disorder gaussian 1e400 0.1 5"););
  HIDE_OUTPUT([&] { fix("1.0 sawtooth 1.0 drive 0.07 1e-4"); });
  TEST_FAILURE(".*ERROR: Fix_modify s kc: value must be finite and >= 0 \\(got 1e400\\).*",
               command("fix_modify s kc left 1e400"););
  TEST_FAILURE(".*ERROR: Fix_modify s velocity: v must be finite \\(got -1e400\\).*",
               command("fix_modify s velocity -1e400"););
}

// found by unittest/fuzz: finite numbers whose energies overflowed (NaN
// and inf in pe, f_sub), tables accepted silently, '1-2' as a seed
TEST_F(EQSubstrateErrors, EnergiesStayFinite)
{
  TEST_FAILURE(".*ERROR: Fix eq/substrate sawtooth: uc = 1e300 is too large: the work per period "
               "uc\\^2/2 = inf would overflow the energies; allowed: 0 < uc <= 1.41421e\\+150.*",
               fix("1.0 sawtooth 1e300"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate stage: X0 = 1e\\+300 is too large for drive K = 0.07: the "
               "driving-spring energy K X0\\^2/2 = inf would overflow the energies; allowed: \\|X0\\| "
               "<= 5.34522e\\+150.*",
               fix("1.0 sawtooth 1.0 drive 0.07 1e-4 stage 1e300"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate stage: X0 = 12 is too large for drive K = 1e\\+300.*",
               fix("1.0 sawtooth 1.0 drive 1e300 1e-4 stage 12"););
  // (2026: 'seed must be a positive integer', 2021: 'seed: expected an integer')
  TEST_FAILURE(".*ERROR: Fix eq/substrate disorder: seed.*'1-2'.*",
               fix("1.0 sawtooth 1.0 disorder constant 1-2"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate sawtooth uc: expected a number, got '1.5.2'.*",
               fix("1.0 sawtooth 1.5.2"););
  // the largest allowed values run, with finite energies
  HIDE_OUTPUT([&] {
    fix("1.0 sawtooth 1e150 drive 0.07 1e-4 stage 1e150");
    command("fix_modify s energy yes");
    command("run 0 post no");
  });
  const double e = lmp->modify->fix[lmp->modify->find_fix("s")]->compute_scalar();
  EXPECT_TRUE(std::isfinite(e));
  {
    std::ofstream out("eq_sub_n.table");
    const char *pts = "\n1 0.0 0.0\n2 0.5 1.0\n3 1.0 0.8\n4 1.5 0.5\n";
    out << "REAL\nN 2.5\n" << pts << "\nSMALL\nN 3\n" << pts << "\nFLAG\nN 4 iso\n" << pts;
  }
  HIDE_OUTPUT([&] { command("unfix s"); });
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: table file 'eq_sub_n.table' line 2: expected 'N "
               "<count>' with count >= 2 after keyword 'REAL' \\(got 'N 2.5': not an integer\\).*",
               fix("1.0 table eq_sub_n.table REAL"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: table file 'eq_sub_n.table' section 'SMALL': more "
               "points than 'N 3' \\(line 10\\) says: point 4 on line 15.*",
               fix("1.0 table eq_sub_n.table SMALL"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: table file 'eq_sub_n.table' line 18: unknown flag "
               "'iso' after 'N 4'.*",
               fix("1.0 table eq_sub_n.table FLAG"););
  std::remove("eq_sub_n.table");
}

TEST_F(EQSubstrateErrors, Tables)
{
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: cannot open table file 'no_such.table'.*",
               fix("1.0 table no_such.table KEY"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: expected 2 values \\(file keyword\\), got 1.*",
               fix("1.0 table only_file.table"););
  {
    std::ofstream out("eq_sub_bad.table");
    out << "START\nN 2\n\n1 0.1 0.0\n2 1.0 1.0\n"
        << "ORDER\nN 3\n\n1 0.0 0.0\n2 0.5 1.0\n3 0.4 1.0\n"
        << "SHORT\nN 4\n\n1 0.0 0.0\n2 0.5 1.0\n";
  }
  TEST_FAILURE(".*ERROR: Fix eq/substrate table eq_sub_bad.table START: the first point must be "
               "u = 0 \\(got 0.1\\).*",
               fix("1.0 table eq_sub_bad.table START"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table eq_sub_bad.table ORDER: u must increase \\(point 3: "
               "u = 0.4 after 0.5\\).*",
               fix("1.0 table eq_sub_bad.table ORDER"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: table file 'eq_sub_bad.table' section 'SHORT': "
               "expected 4 points, found 2.*",
               fix("1.0 table eq_sub_bad.table SHORT"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: keyword 'NOPE' not found in table file "
               "'eq_sub_bad.table'.*",
               fix("1.0 table eq_sub_bad.table NOPE"););
  std::remove("eq_sub_bad.table");
}

TEST_F(EQSubstrateErrors, FixModify)
{
  HIDE_OUTPUT([&] { fix("1.0 sawtooth 1.0"); });
  TEST_FAILURE(".*ERROR: Fix_modify s kc: group nogroup does not exist.*",
               command("fix_modify s kc nogroup 0.5"););
  TEST_FAILURE(".*ERROR: Fix_modify s kc: value must be finite and >= 0 \\(got -0.5\\).*",
               command("fix_modify s kc left -0.5"););
  TEST_FAILURE(".*ERROR: Illegal fix_modify s kc command: expected 'fix_modify s kc GROUP value'.*",
               command("fix_modify s kc left"););
  TEST_FAILURE(".*ERROR: Fix_modify s velocity: fix s has no stage \\(add the drive keyword\\).*",
               command("fix_modify s velocity 1e-4"););
  TEST_FAILURE(".*ERROR: Fix_modify s: unknown keyword 'speed'; allowed: kc, velocity \\(and "
               "LAMMPS' energy, virial, respa\\).*",
               command("fix_modify s speed 1e-4"););
}

// A restart file restores the stage position and velocity (the velocity of
// the writing run, also one set by fix_modify velocity) in place of the
// command's stage X0 and drive v, but only when the writing fix had driving
// springs: a file without them leaves the command's stage.
TEST_F(EQSubstrateErrors, RestartStage)
{
  auto stage = [&](int n) {
    return lmp->modify->fix[lmp->modify->find_fix("s")]->compute_vector(n);    // 1: X_s, 2: v
  };
  HIDE_OUTPUT([&] {
    fix("1.0 sawtooth 1.0");
    command("run 0 post no");
    command("write_restart eq_sub_nodrive.restart");
    command("clear");
    command("read_restart eq_sub_nodrive.restart");
    fix("1.0 sawtooth 1.0 drive 0.07 1e-4 stage 12.0");
  });
  EXPECT_EQ(stage(1), 12.0);
  EXPECT_EQ(stage(2), 1e-4);
  // the stage moves at the velocity set by fix_modify (no integrator: the
  // blocks stay): X_s = 12 - 10 * 0.5 * 2e-4
  HIDE_OUTPUT([&] {
    command("fix_modify s velocity -2e-4");
    command("timestep 0.5");
    command("run 10 post no");
    command("write_restart eq_sub_drive.restart");
    command("clear");
    command("read_restart eq_sub_drive.restart");
    fix("1.0 sawtooth 1.0 drive 0.07 1e-4 stage 3.0");
  });
  EXPECT_NEAR(stage(1), 12.0 - 10 * 0.5 * 2e-4, 1e-12);
  EXPECT_EQ(stage(2), -2e-4);
  // fix_modify velocity after read_restart replaces the restored one
  HIDE_OUTPUT([&] { command("fix_modify s velocity 5e-4"); });
  EXPECT_EQ(stage(2), 5e-4);
  // a fix without drive ignores the stage of the file (with a warning)
  HIDE_OUTPUT([&] {
    command("clear");
    command("read_restart eq_sub_drive.restart");
  });
  BEGIN_CAPTURE_OUTPUT();
  fix("1.0 sawtooth 1.0");
  const auto out = END_CAPTURE_OUTPUT();
  EXPECT_THAT(out, testing::HasSubstr("WARNING: Fix eq/substrate: the restart file has driving "
                                      "springs, this fix has none"));
  EXPECT_EQ(stage(1), 0.0);
  EXPECT_EQ(stage(2), 0.0);
  std::remove("eq_sub_nodrive.restart");
  std::remove("eq_sub_drive.restart");
}

TEST_F(EQSubstrateErrors, PairWithBlocks)
{
  HIDE_OUTPUT([&] {
    command("pair_style eq/elastic 1.5");
    command("pair_coeff 1 1 5.0 1.0");
    command("neighbor 0.2 bin");
    fix("1.0 sawtooth 1.0");
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25");
  });
  TEST_FAILURE(".*ERROR: Pair style eq/elastic found 2 fixes with coordinates \\(fix s "
               "eq/substrate, fix c eq/contacts\\); allowed: exactly one fix eq/contacts, "
               "eq/substrate or eq/meso.*",
               command("run 0 post no"););
  HIDE_OUTPUT([&] {
    command("unfix c");
    command("displace_atoms left move 0.3 0 0 units box");
  });
  // coupled blocks whose displacements differ by more than half the skin
  TEST_FAILURE(".*ERROR on proc 0: Pair eq/elastic: the displacements of coupled blocks [0-9]+ and "
               "[0-9]+ differ by 0.3, more than half the neighbor skin 0.2.*",
               command("run 0 post no"););
}

TEST_F(EQSubstrateErrors, MasterEquationTable)
{
  TEST_FAILURE(".*ERROR: eq/me substrate: uc = 3.000000 beyond xmax = 2.000000; raise xmax.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 substrate sub.table BLOCK 3.0"););
  TEST_FAILURE(".*ERROR: eq/me substrate: uc must be > 0.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 substrate sub.table BLOCK 0"););
  TEST_FAILURE(".*ERROR: eq/me substrate: missing value.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 substrate sub.table"););
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
