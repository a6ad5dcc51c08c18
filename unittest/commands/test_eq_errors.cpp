// Bad input to the FRICTION-EQ styles gives a LAMMPS error that names the
// command, the keyword and the allowed values (never a crash or NaN).
// Uses LAMMPS' own unittest helpers (unittest/testing/core.h).
#include "lammps.h"

#include "atom.h"
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

const std::string TABLE = std::string(FEQ_SOURCE_DIR) + "/potentials/eq_thresholds.table";

class EQContactsErrors : public LAMMPSTest {
 protected:
  void InitSystem() override
  {
    HIDE_OUTPUT([&] {
      command("units lj");
      command("dimension 2");
      command("atom_style atomic");
      command("lattice sq 1.0");
      command("region box block 0 4 0 4 -0.5 0.5");
      command("create_box 1 box");
      command("create_atoms 1 box");
      command("mass 1 1.0");
      command("group nobody empty");
    });
  }
  // "fix c all eq/contacts " + rest
  void fix(const std::string &rest) { command("fix c all eq/contacts " + rest); }
};

}    // namespace

TEST_F(EQContactsErrors, ValidCommandsAreAccepted)
{
  HIDE_OUTPUT([&] {
    fix("1.0 5 threshold uniform 0.75 1.25");
    command("unfix c");
    fix("2.0 7 threshold gaussian 1.0 0.2 reform gaussian 0.1 0.02 stiffness uniform 0.5 1.5 "
        "dir y crossing step start reform");
    command("unfix c");
    fix("1.0 7 threshold realistic 1.0 reform none stiffness gaussian 1.0 0.1");
    command("unfix c");
    fix("1.0 7 threshold table " + TABLE + " REALISTIC_1.0 reform uniform 0.0 0.1");
  });
  ASSERT_NE(lmp->modify->find_fix("c"), -1);
}

TEST_F(EQContactsErrors, Arguments)
{
  TEST_FAILURE(".*ERROR: Illegal fix eq/contacts command: expected 'fix ID group eq/contacts kc "
               "seed threshold.*",
               fix("1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc must be finite and > 0 \\(got -1\\).*",
               fix("-1 5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc must be finite and > 0 \\(got 0\\).*",
               fix("0 5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc: expected a number, got 'abc'.*",
               fix("abc 5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc must be finite and > 0 \\(got 1e400\\).*",
               fix("1e400 5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: seed must be a positive integer \\(got 0\\).*",
               fix("1.0 0 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: seed must be a positive integer \\(got -3\\).*",
               fix("1.0 -3 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: seed: expected an integer, got '1.5'.*",
               fix("1.0 1.5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: seed: integer 99999999999999999999 is out of range.*",
               fix("1.0 99999999999999999999 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: the threshold keyword is required; allowed styles: "
               "uniform, gaussian, realistic, table.*",
               fix("1.0 5 reform delta 0.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts unknown keyword 'thresholds'; allowed: threshold, reform, "
               "stiffness, dir, crossing, start.*",
               fix("1.0 5 thresholds uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: group nobody has no atoms.*",
               command("fix c nobody eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
  HIDE_OUTPUT([&] {
    command("region left block 0 2 INF INF INF INF");
    command("group moving dynamic all region left");
  });
  TEST_FAILURE(".*ERROR: Fix eq/contacts: group moving is dynamic; contacts need a static group.*",
               command("fix c moving eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
}

// temperature, aging and delays: values, and what they cannot go with
TEST_F(EQContactsErrors, TemperatureAgingDelay)
{
  const std::string base = "1.0 5 threshold uniform 0.75 1.25 ";
  TEST_FAILURE(".*ERROR: Fix eq/contacts thermal eps_a: must be > 0 \\(got 0\\).*",
               fix(base + "thermal 1.0 0 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts thermal T: must be >= 0 \\(got -1\\).*",
               fix(base + "thermal -1 1.0 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts thermal omega: missing value.*",
               fix(base + "thermal 1.0 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts barrier q: expected a number, got 'x'.*",
               fix(base + "barrier 2 x"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts aging: unknown value 'power'; allowed: none, log, exp.*",
               fix(base + "aging power 0.1 1"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts aging tau_a: must be > 0 \\(got 0\\).*",
               fix(base + "aging log 0.1 0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts delay tau: must be >= 0 \\(got -2\\).*",
               fix(base + "delay exp -2"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts rest t_w: must be >= 0 \\(got -1\\).*",
               fix(base + "rest -1"););
  // time must pass: not with a driver that moves from break to break
  HIDE_OUTPUT([&] {
    fix(base + "thermal 0.1 1.0 1.0");
    command("fix q all eq/quasistatic c max 0.01");
  });
  TEST_FAILURE(".*ERROR: Fix c eq/contacts: the keywords thermal, barrier, aging, delay, rest need "
               "time, and fix q moves the slider from break to break without it.*",
               command("run 0 post no"););
  HIDE_OUTPUT([&] {
    command("unfix q");
    command("unfix c");
    fix(base + "aging log 0.1 1.0 thermal 0.05 1.0 1.0");
    command("comm_modify cutoff 3.5");
    command("pair_style eq/elastic 3.0");
    command("pair_coeff 1 1 0.06 3.0");
    // interacting contacts at T > 0, with aging and with delays run
    command("run 0 post no");
    command("unfix c");
    fix(base + "delay exp 2.0");
    command("run 0 post no");
  });
  // peratom N: compact rows for thermal rows without a field; readers at
  // the steps of its output only (LAMMPS' own check of peratom_freq)
  HIDE_OUTPUT([&] { command("unfix c"); });
  TEST_FAILURE(".*ERROR: Fix eq/contacts peratom: N must be an integer from 1 to 2147483647 \\(got 0\\).*",
               fix(base + "thermal 0.1 1.0 1.0 peratom 0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts peratom: missing N \\(steps\\).*",
               fix(base + "thermal 0.1 1.0 1.0 peratom"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: peratom: expected an integer, got '2.5'.*",
               fix(base + "thermal 0.1 1.0 1.0 peratom 2.5"););
  TEST_FAILURE(".*ERROR: Fix c eq/contacts: peratom 10 needs thermal rows \\(keywords thermal, "
               "barrier, aging, delay, rest\\).*",
               fix(base + "peratom 10"););
  HIDE_OUTPUT([&] { fix(base + "delay exp 2.0 peratom 10"); });
  TEST_FAILURE(".*ERROR: Fix c eq/contacts: peratom 10 does not work with pair style eq/elastic.*",
               command("run 0 post no"););
  HIDE_OUTPUT([&] {
    command("pair_style none");
    command("dump d all custom 5 /dev/null id f_c[1]");
  });
  TEST_FAILURE(".*ERROR: Dump custom and fix not computed at compatible times.*",
               command("run 10 post no"););
  HIDE_OUTPUT([&] {
    command("undump d");
    command("dump d all custom 10 /dev/null id f_c[1]");
    command("run 10 post no");
  });
}

TEST_F(EQContactsErrors, Threshold)
{
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold uniform: need 0 <= lo < hi \\(got lo = 1.25, "
               "hi = 0.75\\).*",
               fix("1.0 5 threshold uniform 1.25 0.75"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold uniform: expected 2 values \\(lo hi\\), got 1.*",
               fix("1.0 5 threshold uniform 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold uniform: expected a number for hi, got 'x'.*",
               fix("1.0 5 threshold uniform 0.75 x"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold unknown style 'weibull'; allowed: uniform, "
               "gaussian, realistic, table.*",
               fix("1.0 5 threshold weibull 1 2"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold: missing style; allowed: uniform, gaussian, "
               "realistic, table.*",
               fix("1.0 5 threshold"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold gaussian: need a finite mean and sd > 0 \\(got "
               "mean = 1, sd = -0.1\\).*",
               fix("1.0 5 threshold gaussian 1.0 -0.1"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold realistic: need xs > 0 \\(got -2\\).*",
               fix("1.0 5 threshold realistic -2"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: cannot open table file "
               "'no_such_file.table'.*",
               fix("1.0 5 threshold table no_such_file.table KEY"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: keyword 'NOPE' not found in table file.*",
               fix("1.0 5 threshold table " + TABLE + " NOPE"););
  {
    std::ofstream out("eq_bad.table");
    out << "BAD\nN 3\n\n1 0.5 1.0\n2 0.7 1.0\n3 0.6 1.0\n"
        << "MALFORMED\nN 2\n\n1 0.5\n2 0.7 1.0\n"
        << "NEGX\nN 2\n\n1 -0.5 1.0\n2 0.7 1.0\n";
  }
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table eq_bad.table BAD: stretches must "
               "increase strictly \\(point 3\\).*",
               fix("1.0 5 threshold table eq_bad.table BAD"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_bad.table' line 10: "
               "expected 'index x P\\(x\\)'.*",
               fix("1.0 5 threshold table eq_bad.table MALFORMED"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: breaking stretches must be >= 0.*",
               fix("1.0 5 threshold table eq_bad.table NEGX"););
  std::remove("eq_bad.table");
}

TEST_F(EQContactsErrors, ReformStiffnessAndOptions)
{
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform unknown style 'realistic'; allowed: delta, "
               "uniform, gaussian, none.*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform realistic 1.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform uniform: need lo < hi \\(got lo = 0.3, hi = 0.1\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform uniform 0.3 0.1"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform gaussian: need a finite mean and sd > 0.*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform gaussian 0.1 0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform delta 2: re-forming stretches reach the largest "
               "breaking threshold 1.25 \\(probability 1\\); a contact must form below its "
               "threshold.*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform delta 2.0"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform uniform 0.5 1.3: re-forming stretches reach the "
               "largest breaking threshold 1.25 \\(probability 0.0625\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform uniform 0.5 1.3"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform gaussian 0.2 0.3: re-forming stretches reach the "
               "largest breaking threshold 1.25 \\(probability 0.0002333004075\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform gaussian 0.2 0.3"););
  // negative stretches count too: |r| must stay below the largest threshold
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform delta -1.3: re-forming stretches reach the "
               "largest breaking threshold 1.25.*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform delta -1.3"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts stiffness uniform: need 0 < lo < hi \\(got lo = -1, hi = "
               "2\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25 stiffness uniform -1 2"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts stiffness gaussian: need mean > 0 \\(got -1\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25 stiffness gaussian -1 0.1"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts stiffness unknown style 'const'; allowed: constant, "
               "uniform, gaussian.*",
               fix("1.0 5 threshold uniform 0.75 1.25 stiffness const"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts dir: unknown value 'w'; allowed: x, y, z.*",
               fix("1.0 5 threshold uniform 0.75 1.25 dir w"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts dir: missing value; allowed: x, y, z.*",
               fix("1.0 5 threshold uniform 0.75 1.25 dir"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: dir z is not allowed in a 2d simulation; allowed: x, y.*",
               fix("1.0 5 threshold uniform 0.75 1.25 dir z"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts crossing: unknown value 'half'; allowed: exact, step.*",
               fix("1.0 5 threshold uniform 0.75 1.25 crossing half"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts start: unknown value 'hot'; allowed: relaxed, reform.*",
               fix("1.0 5 threshold uniform 0.75 1.25 start hot"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: start reform needs contacts that re-form \\(reform none "
               "given\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25 reform none start reform"););
}

// Problems that only show while running are reported with the contact.
TEST_F(EQContactsErrors, RuntimeChecks)
{
  HIDE_OUTPUT([&] {
    fix("1.0 5 threshold uniform 0.75 1.25 reform delta 1.249");
    command("fix m all move linear 1.9 0.0 0.0");    // < half the box per step
    command("timestep 1.0");
  });
  TEST_FAILURE(".*ERROR on proc 0: Fix eq/contacts: contact [0-9]+ broke more than 1000 times in "
               "one step.*reduce the timestep.*",
               command("run 2"););
  // a position that is not a number (inf - inf) is reported, not propagated
  HIDE_OUTPUT([&] {
    command("unfix m");
    command("unfix c");
    fix("1.0 5 threshold uniform 0.75 1.25");
    command("variable big equal 1e308");
    command("variable nanx equal v_big*v_big-v_big*v_big");
    command("fix m all move variable v_nanx NULL NULL NULL NULL NULL");
  });
  TEST_FAILURE(".*ERROR on proc 0: Fix eq/contacts: stretch of contact [0-9]+ is -?nan \\(numerical "
               "instability: check the timestep, the forces and the integrator\\).*",
               command("run 2"););
}

TEST_F(EQContactsErrors, RequiresAtomIDs)
{
  HIDE_OUTPUT([&] {
    command("clear");
    command("atom_modify id no");
    command("region box block 0 2 0 2 0 2");
    command("create_box 1 box");
    command("create_atoms 1 single 1 1 1");
    command("mass 1 1.0");
  });
  TEST_FAILURE(".*ERROR: Fix eq/contacts requires atom IDs \\(atom_modify id yes\\).*",
               fix("1.0 5 threshold uniform 0.75 1.25"););
}

// the eq/me command: errors, and the internal variables it sets
TEST_F(EQContactsErrors, MasterEquationCommand)
{
  TEST_FAILURE(".*ERROR: Illegal eq/me command: expected 'eq/me threshold <style> <values> "
               "\\[keyword values ...\\]'.*",
               command("eq/me"););
  TEST_FAILURE(".*ERROR: eq/me threshold realistic: need xs > 0 \\(got 0\\).*",
               command("eq/me threshold realistic 0"););
  TEST_FAILURE(".*ERROR: eq/me unknown keyword 'dX'; allowed: threshold, reform, stiffness, dir, "
               "xmax, dx, start, crossing, richardson, force, steady, snapshot, summary, exact.*",
               command("eq/me threshold realistic 1.0 dX 0.1"););
  TEST_FAILURE(".*ERROR: eq/me dx: expected a number, got 'fine'.*",
               command("eq/me threshold realistic 1.0 dx fine"););
  HIDE_OUTPUT([&] {
    command("variable eq_me_kstar equal 1.0");
  });
  TEST_FAILURE(".*ERROR: eq/me: variable eq_me_kstar exists and is not of style internal.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2"););
  HIDE_OUTPUT([&] {
    command("variable eq_me_kstar delete");
    command("eq/me threshold uniform 0.75 1.25 xmax 3");
  });
  EXPECT_NEAR(get_variable_value("eq_me_kstar"), 1.5, 2e-3);
  EXPECT_NEAR(get_variable_value("eq_me_kinetic_force"), 0.5104166666666667, 1e-12);
  // a second call updates the variables
  HIDE_OUTPUT([&] { command("eq/me threshold realistic 1.0 xmax 3"); });
  EXPECT_NEAR(get_variable_value("eq_me_kstar"), 0.17425, 1e-5);
}

// found by unittest/fuzz: sizes, output files, degenerate distributions
TEST_F(EQContactsErrors, MasterEquationSizesAndFiles)
{
  // thresholds ~1e300: the grid size overflowed (std::length_error)
  TEST_FAILURE(".*ERROR: eq/me threshold uniform 0.75 1e\\+300: the stretch grid x in \\[0, "
               "1e\\+300\\] \\(up to the largest threshold\\) would need 2e\\+302 points at dx = "
               "0.005 \\(dx/2 of richardson\\), at most 2e\\+08; raise dx.*",
               command("eq/me threshold uniform 0.75 1e300 xmax 2 dx 0.01"););
  TEST_FAILURE(".*ERROR: eq/me threshold realistic 1e\\+300: the stretch grid.*raise dx.*",
               command("eq/me threshold realistic 1e300 xmax 2 dx 0.01"););
  TEST_FAILURE(".*ERROR: eq/me threshold gaussian 1 1e\\+300 \\(truncated to x > 0\\): the "
               "stretch grid.*",
               command("eq/me threshold gaussian 1.0 1e300 xmax 2 dx 0.01"););
  // xmax 1e300: no 300-digit number
  TEST_FAILURE(".*ERROR: eq/me xmax: xmax/dx = 1e\\+302 steps \\(xmax = 1e\\+300, dx = 0.01\\), "
               "at most 1e\\+08 with richardson \\(2e\\+08 without\\); lower xmax or raise dx.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 1e300 dx 0.01"););
  // exact: lo -> 0 runs (the renewal terms are cut); lo and hi both tiny
  // would need ~xmax/lo terms
  TEST_FAILURE(".*ERROR: eq/me exact: lo is too small: the renewal sums need more than 2000 terms "
               "per point \\(lo = 1e-300, hi = 2e-300, xmax = 2\\).*",
               command("eq/me threshold uniform 1e-300 2e-300 xmax 2 dx 0.01 exact eq_ex.dat"););
  HIDE_OUTPUT([&] {
    command("eq/me threshold uniform 1e-300 1.25 xmax 2 dx 0.01 exact eq_ex.dat");
  });
  std::remove("eq_ex.dat");
  // output files: the keyword is named, before the solve, on every rank
  for (const char *kw : {"force", "steady", "summary", "exact"}) {
    TEST_FAILURE(std::string(".*ERROR: eq/me ") + kw +
                     ": cannot write file '/nonexistent/dir/out.dat' \\(No such file or "
                     "directory\\).*",
                 command(std::string("eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 ") + kw +
                         " /nonexistent/dir/out.dat"););
    TEST_FAILURE(std::string(".*ERROR: eq/me ") + kw + ": cannot write file '.' \\(Is a directory\\).*",
                 command(std::string("eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 ") + kw +
                         " ."););
  }
  TEST_FAILURE(".*ERROR: eq/me snapshot: cannot write file '/nonexistent/q.dat'.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 snapshot 1.0 "
                       "/nonexistent/q.dat"););
  TEST_FAILURE(".*ERROR: eq/me substrate: cannot write file '/nonexistent/s.table'.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 substrate "
                       "/nonexistent/s.table B 1.0"););
  // a missing file name does not take the next keyword as the name
  TEST_FAILURE(".*ERROR: eq/me force: missing file name before the keyword 'steady'.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 force steady qs.dat"););
  TEST_FAILURE(".*ERROR: eq/me summary: missing file name before the keyword 'substrate'.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 summary substrate "
                       "me.table B 1.0"););
  // reform gaussian 0.1 1e-300: F_k was -nan (the variable then missing)
  HIDE_OUTPUT([&] {
    command("eq/me threshold realistic 1.0 reform gaussian 0.1 1e-300 xmax 2 dx 0.01");
  });
  const double narrow = get_variable_value("eq_me_kinetic_force");
  HIDE_OUTPUT([&] { command("eq/me threshold realistic 1.0 reform delta 0.1 xmax 2 dx 0.01"); });
  EXPECT_DOUBLE_EQ(narrow, get_variable_value("eq_me_kinetic_force"));
  EXPECT_TRUE(std::isfinite(narrow));
}

// found by unittest/fuzz: tables and numbers that were accepted silently,
// fix_modify on fix eq/contacts
TEST_F(EQContactsErrors, TablesNumbersAndFixModify)
{
  {
    std::ofstream out("eq_n.table");
    const char *pts = "\n1 0.5 0.0\n2 0.8 2.0\n3 1.0 1.0\n4 1.3 0.0\n";
    out << "REAL\nN 2.5\n" << pts << "\nSMALL\nN 3\n" << pts << "\nFLAG\nN 4 iso\n" << pts;
  }
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_n.table' line 2: expected "
               "'N <count>' with count >= 2 after keyword 'REAL' \\(got 'N 2.5': not an integer\\).*",
               fix("1.0 5 threshold table eq_n.table REAL"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_n.table' section 'SMALL': "
               "more points than 'N 3' \\(line 10\\) says: point 4 on line 15; the point count "
               "must equal N.*",
               fix("1.0 5 threshold table eq_n.table SMALL"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_n.table' line 18: unknown "
               "flag 'iso' after 'N 4' \\(threshold and substrate tables take no flags\\).*",
               fix("1.0 5 threshold table eq_n.table FLAG"););
  TEST_FAILURE(".*ERROR: eq/me threshold table: table file 'eq_n.table' section 'SMALL': more "
               "points than 'N 3'.*",
               command("eq/me threshold table eq_n.table SMALL xmax 2 dx 0.01"););
  std::remove("eq_n.table");
  // LAMMPS 2021's utils::is_double() accepts '1.5.2' and is_integer() '1-2'
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc: expected a number, got '1.5.2'.*",
               fix("1.5.2 5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold uniform: expected a number for hi, got "
               "'1.2.5'.*",
               fix("1.0 5 threshold uniform 0.75 1.2.5"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc: expected a number, got 'e'.*",
               fix("e 5 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: seed: expected an integer, got '1-2'.*",
               fix("1.0 1-2 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: eq/me xmax: expected a number, got '1.5.2'.*",
               command("eq/me threshold uniform 0.75 1.25 xmax 1.5.2"););
  // fix eq/contacts has no fix_modify keywords of its own (2021 said only
  // 'Illegal fix_modify command')
  HIDE_OUTPUT([&] {
    fix("1.0 5 threshold uniform 0.75 1.25");
    command("fix_modify c energy yes");
  });
  TEST_FAILURE(".*ERROR: Fix_modify c: unknown keyword 'kc' for fix eq/contacts; allowed: LAMMPS' "
               "energy, virial, respa \\(fix eq/contacts has no keywords of its own\\).*",
               command("fix_modify c kc all 0.5"););
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
