// Stateful use and misuse of the FRICTION-EQ styles: partners removed or
// replaced between and within runs, restarts re-specified with other
// arguments or garbled, products of finite arguments that overflow,
// outputs before the first run, and the combinations the docs forbid.
// Each ends in a LAMMPS error naming the styles and keyword involved, or
// in the right result; never in a crash.  (The stateful-misuse generator
// of unittest/fuzz runs hundreds of variants of these on 1 and 2 ranks.)
#include "lammps.h"

#include "atom.h"
#include "fix.h"
#include "input.h"
#include "modify.h"
#include "variable.h"

#include "testing/core.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mpi.h>
#include <string>
#include <vector>

bool verbose = false;

namespace {

// a 2d lattice of 8 x 6 contacts (or blocks) with periodic boundaries
class EQState : public LAMMPSTest {
 protected:
  void InitSystem() override
  {
    HIDE_OUTPUT([&] {
      command("units lj");
      command("dimension 2");
      command("atom_style atomic");
      command("boundary p p p");
      command("lattice sq 1.0");
      command("region box block 0 8 0 6 -0.5 0.5");
      command("create_box 1 box");
      command("create_atoms 1 box");
      command("mass 1 1.0");
      command("neighbor 0.5 bin");
    });
  }
  double value(const std::string &expr)
  {
    return lmp->input->variable->compute_equal(expr);
  }
};

const char *CONTACTS = "fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25";
const char *PAIR = "pair_style eq/elastic 2.0";
const char *COEFF = "pair_coeff 1 1 0.05 2.0";

// the bytes of a file, and back
std::vector<char> slurp(const std::string &file)
{
  std::ifstream in(file, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void spill(const std::string &file, const std::vector<char> &bytes)
{
  std::ofstream out(file, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}    // namespace

/* ----------------------------------------------------------------------
   partners removed or replaced
------------------------------------------------------------------------- */

TEST_F(EQState, PartnerRemovedBetweenRuns)
{
  HIDE_OUTPUT([&] {
    command(CONTACTS);
    command("fix q all eq/quasistatic c max 0.01");
    command("run 2 post no");
    command("unfix c");
  });
  TEST_FAILURE(".*ERROR: Fix q eq/quasistatic: fix ID c does not exist; expected the ID of a fix "
               "eq/contacts.*",
               command("run 2 post no"););
  // the same fix defined anew: the driver goes on with it
  HIDE_OUTPUT([&] {
    command(CONTACTS);
    command("run 2 post no");
  });
  EXPECT_EQ(value("f_c[7]"), 48.0);
  EXPECT_GT(value("f_q"), 0.0);
}

TEST_F(EQState, FieldSourceRemovedBetweenRuns)
{
  HIDE_OUTPUT([&] {
    command(PAIR);
    command(COEFF);
    command(CONTACTS);
    command("fix q all eq/quasistatic c max 0.01");
    command("run 2 post no");
    command("unfix q");
    command("unfix c");
  });
  TEST_FAILURE(".*ERROR: Pair style eq/elastic needs a fix eq/contacts.*",
               command("run 1 post no"););
}

// run N pre no every M "unfix ...": LAMMPS does not set up the run again,
// the styles must find out themselves
TEST_F(EQState, QuasistaticContactsRemovedWithinRun)
{
  HIDE_OUTPUT([&] {
    command(CONTACTS);
    command("fix q all eq/quasistatic c max 0.01");
  });
  TEST_FAILURE(".*ERROR: Fix q eq/quasistatic: fix c eq/contacts, the contacts it drives, was "
               "removed or replaced during the run.*",
               command("run 4 pre no every 2 \"unfix c\""););
}

TEST_F(EQState, FieldSourceRemovedWithinRun)
{
  HIDE_OUTPUT([&] {
    command(PAIR);
    command(COEFF);
    command(CONTACTS);
    command("fix m all move linear 0.1 0.0 0.0 units box");
  });
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: fix c eq/contacts, the coordinate source found at "
               "the start of the run, was removed or replaced during the run.*",
               command("run 4 pre no every 2 \"unfix c\" \"" + std::string(CONTACTS) + "\""););
}

// thermo without press: between the parts of a run with pre no LAMMPS
// calls only Output::setup, where compute pressure would read the virial
// of the deleted pair through the pointer it took in init() (heap use
// after free under ASan, for any pair style replaced this way) before
// any code of the package runs
TEST_F(EQState, FieldReplacedWithinRun)
{
  HIDE_OUTPUT([&] {
    command(PAIR);
    command(COEFF);
    command(CONTACTS);
    command("fix m all move linear 0.1 0.0 0.0 units box");
    command("thermo_style custom step pe");
  });
  TEST_FAILURE(".*ERROR: Fix c eq/contacts: pair style eq/elastic, the field of its contacts at "
               "the start of the run, was removed or replaced during the run.*",
               command("run 4 pre no every 2 \"pair_style zero 2.0\" \"pair_coeff * *\""););
}

// pair_style of the same style keeps the pair (LAMMPS re-reads its
// settings): new cutoffs and kernels during the run are refused
TEST_F(EQState, FieldRedefinedWithinRun)
{
  HIDE_OUTPUT([&] {
    command(PAIR);
    command(COEFF);
    command(CONTACTS);
    command("fix m all move linear 0.1 0.0 0.0 units box");
  });
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: pair_style or pair_coeff during a run \\(run N "
               "pre no every M\\) is not supported.*",
               command("run 4 pre no every 2 \"" + std::string(PAIR) + "\" \"" +
                       std::string(COEFF) + "\""););
}

// a run in parts without a new set-up (run N pre no every M) with the
// partners unchanged is the same run: the same breaks and forces
TEST_F(EQState, RunInPartsKeepsThePartners)
{
  auto run = [&](const std::string &how) {
    HIDE_OUTPUT([&] { command("clear"); });
    InitSystem();
    HIDE_OUTPUT([&] {
      command("displace_atoms all random 0.2 0.2 0.0 4321 units box");
      command(PAIR);
      command(COEFF);
      command(CONTACTS);
      command("fix q all eq/quasistatic c max 0.05");
      command(how);
    });
    return std::vector<double>{value("f_c[3]"), value("f_c[1]"), value("pe"), value("f_q")};
  };
  const std::vector<double> whole = run("run 40");
  const std::vector<double> parts = run("run 40 pre no every 10 \"print part\"");
  EXPECT_GT(whole[0], 20.0);    // the contacts broke
  EXPECT_EQ(parts, whole);
}

/* ----------------------------------------------------------------------
   restarts: arguments that shape the stored state, garbled records
------------------------------------------------------------------------- */

TEST_F(EQState, ContactsRestartWithOtherArguments)
{
  HIDE_OUTPUT([&] {
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5");
    command("fix m all move linear 0.1 0.0 0.0 units box");
    command("run 20 post no");
    command("write_restart eq_state_c.restart");
  });
  struct Change {
    const char *fix, *keyword;
  };
  const Change changes[] = {
      {"2.0 5 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5", "kc"},
      {"1.0 5 threshold uniform 0.7 1.25 stiffness uniform 0.5 1.5", "threshold"},
      {"1.0 5 threshold gaussian 1.0 0.1 stiffness uniform 0.5 1.5", "threshold"},
      {"1.0 5 threshold uniform 0.75 1.25 reform delta 0.1 stiffness uniform 0.5 1.5", "reform"},
      {"1.0 5 threshold uniform 0.75 1.25", "stiffness"},
      {"1.0 5 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5 dir y", "dir"},
  };
  for (const Change &c : changes) {
    HIDE_OUTPUT([&] {
      command("clear");
      command("read_restart eq_state_c.restart");
    });
    TEST_FAILURE(".*ERROR: Fix c eq/contacts: " + std::string(c.keyword) +
                     " differs from that of the run that wrote the restart file: the stored "
                     "contacts were made with the other " + c.keyword + ".*",
                 command(std::string("fix c all eq/contacts ") + c.fix););
  }
  // what does not shape the stored state may change; another seed warns
  HIDE_OUTPUT([&] {
    command("clear");
    command("read_restart eq_state_c.restart");
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5 "
            "crossing step reform_as stretch");
    command("clear");
    command("read_restart eq_state_c.restart");
  });
  ::testing::internal::CaptureStdout();
  command("fix c all eq/contacts 1.0 9 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5");
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_THAT(out, ::testing::ContainsRegex("WARNING: Fix eq/contacts: seed 9 differs from the "
                                            "restart file's seed 5"));
  std::remove("eq_state_c.restart");
}

// the thermal keywords add values per contact: a restart file of the
// other layout names them; their values themselves may change
TEST_F(EQState, ContactsRestartAcrossTheThermalLayout)
{
  HIDE_OUTPUT([&] {
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 thermal 0.1 1.0 1.0");
    command("fix m all move linear 0.1 0.0 0.0 units box");
    command("run 20 post no");
    command("write_restart eq_state_t.restart");
    command("clear");
    command("read_restart eq_state_t.restart");
  });
  TEST_FAILURE(".*ERROR.*: Fix c eq/contacts: the restart file holds 15 values per atom "
               "for this fix, it expects 7 .*the keywords thermal, barrier, aging, delay, rest "
               "add 8 values per contact.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
  HIDE_OUTPUT([&] {
    command("clear");
    command("read_restart eq_state_t.restart");
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 thermal 0.3 1.0 1.0 "
            "aging exp 0.1 2.0 delay fixed 0.5");
    command("fix m all move linear 0.1 0.0 0.0 units box");
    // (long enough for breaks: about 0.17 thermal breaks are expected in 20 steps)
    command("run 2000 post no");
  });
  EXPECT_GT(lmp->modify->fix[lmp->modify->find_fix("c")]->compute_vector(2), 0.0);
  std::remove("eq_state_t.restart");
}

TEST_F(EQState, BlocksRestartWithOtherArguments)
{
  HIDE_OUTPUT([&] {
    command("fix s all eq/substrate 1.0 sawtooth 1.0 disorder uniform 0.8 1.2 7");
    command("fix m all move linear 0.3 0.0 0.0 units box");
    command("run 20 post no");
    command("write_restart eq_state_s.restart");
  });
  struct Change {
    const char *fix, *keyword;
  };
  const Change changes[] = {
      {"2.0 sawtooth 1.0 disorder uniform 0.8 1.2 7", "kc"},
      {"1.0 sawtooth 1.5 disorder uniform 0.8 1.2 7", "uc"},
      {"1.0 smooth 1.0 disorder uniform 0.8 1.2 7", "shape"},
      {"1.0 sawtooth 1.0 disorder uniform 0.8 1.2 8", "disorder"},
      {"1.0 sawtooth 1.0", "disorder"},
      {"1.0 sawtooth 1.0 disorder uniform 0.8 1.2 7 dir y", "dir"},
      {"1.0 sawtooth 1.0 disorder uniform 0.8 1.2 7 reverse break", "reverse"},
  };
  for (const Change &c : changes) {
    HIDE_OUTPUT([&] {
      command("clear");
      command("read_restart eq_state_s.restart");
    });
    TEST_FAILURE(".*ERROR: Fix s eq/substrate: " + std::string(c.keyword) +
                     " differs from that of the run that wrote the restart file.*",
                 command(std::string("fix s all eq/substrate ") + c.fix););
  }
  HIDE_OUTPUT([&] {
    command("clear");
    command("read_restart eq_state_s.restart");
    command("fix s all eq/substrate 1.0 sawtooth 1.0 disorder uniform 0.8 1.2 7 crossing step");
  });
  std::remove("eq_state_s.restart");
}

TEST_F(EQState, MesoRestartWithOtherArguments)
{
  HIDE_OUTPUT([&] {
    command("fix b all eq/meso 100 1.0 threshold uniform 0.75 1.25 grid 0.02");
    command("fix m all move linear 0.3 0.0 0.0 units box");
    command("run 10 post no");
    command("write_restart eq_state_m.restart");
  });
  struct Change {
    const char *fix, *keyword;
  };
  const Change changes[] = {
      {"50 1.0 threshold uniform 0.75 1.25 grid 0.02", "Nlambda"},
      {"100 2.0 threshold uniform 0.75 1.25 grid 0.02", "kc"},
      {"100 1.0 threshold uniform 0.75 1.25 grid 0.02 dir y", "dir"},
      {"100 1.0 threshold uniform 0.75 1.25 grid 0.02 reform delta 0.1", "reform"},
  };
  for (const Change &c : changes) {
    HIDE_OUTPUT([&] {
      command("clear");
      command("read_restart eq_state_m.restart");
    });
    TEST_FAILURE(".*ERROR: Fix b eq/meso: " + std::string(c.keyword) +
                     " differs from that of the run that wrote the restart file.*",
                 command(std::string("fix b all eq/meso ") + c.fix););
  }
  // crossing and start do not shape the stored blocks
  HIDE_OUTPUT([&] {
    command("clear");
    command("read_restart eq_state_m.restart");
    command("fix b all eq/meso 100 1.0 threshold uniform 0.75 1.25 grid 0.02 crossing step start "
            "reform");
  });
  std::remove("eq_state_m.restart");
}

// the global record of fix eq/contacts (magic number 1178947909.0 "FEQE",
// format, count, values, signature) with its format or count changed, or
// cut short: an error before anything of it is used
TEST_F(EQState, GarbledRestartRecord)
{
  HIDE_OUTPUT([&] {
    command(CONTACTS);
    command("run 0 post no");
    command("write_restart eq_state_g.restart");
  });
  const std::vector<char> bytes = slurp("eq_state_g.restart");
  const double magic = 1178947909.0;
  char pattern[sizeof(double)];
  memcpy(pattern, &magic, sizeof(double));
  size_t at = std::string::npos;
  for (size_t k = 0; k + sizeof(double) <= bytes.size(); ++k)
    if (memcmp(bytes.data() + k, pattern, sizeof(double)) == 0) at = k;
  ASSERT_NE(at, std::string::npos);
  const double bad[] = {7.0, 1e9};    // format, count of values
  for (int which = 0; which < 2; ++which) {
    std::vector<char> garbled = bytes;
    memcpy(garbled.data() + at + (which + 1) * sizeof(double), &bad[which], sizeof(double));
    spill("eq_state_g2.restart", garbled);
    HIDE_OUTPUT([&] {
      command("clear");
      command("read_restart eq_state_g2.restart");
    });
    TEST_FAILURE(".*ERROR: Fix c eq/contacts: the restart file's record of this fix is unusable: "
                 "the record (is not one this version of the package writes|holds 1000000000).*",
                 command(CONTACTS););
  }
  std::remove("eq_state_g.restart");
  std::remove("eq_state_g2.restart");
}

/* ----------------------------------------------------------------------
   overflow of finite arguments, outputs before the first run
------------------------------------------------------------------------- */

TEST_F(EQState, OverflowingArguments)
{
  TEST_FAILURE(".*ERROR: Fix eq/meso: Nlambda = 1e\\+200 and kc = 1e\\+200 .* would overflow the "
               "blocks' forces.*",
               command("fix b all eq/meso 1e200 1e200 threshold uniform 0.75 1.25"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts: kc = 1e\\+300 with stiffness constant .* and threshold "
               "uniform 1e\\+10 2e\\+10 .* would overflow.*",
               command("fix c all eq/contacts 1e300 5 threshold uniform 1e10 2e10"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate: kc = 1e\\+300 with the substrate sawtooth .* would "
               "overflow.*",
               command("fix s all eq/substrate 1e300 sawtooth 1e10"););
  HIDE_OUTPUT([&] { command(PAIR); });
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: ftilde 1e300 and lambda_c 1e10 "
               "overflow the kernel.*",
               command("pair_coeff 1 1 1e300 1e10"););
}

TEST_F(EQState, OutputsBeforeTheFirstRun)
{
  HIDE_OUTPUT([&] {
    command("fix c all eq/contacts 2.0 5 threshold uniform 0.75 1.25 reform uniform -0.2 0.2 "
            "start reform");
    command("fix s all eq/substrate 1.0 sawtooth 1.0 drive 2.0 0.1 stage 0.5");
    command("fix b all eq/meso 10 1.0 threshold uniform 0.75 1.25 drive 3.0 0.0 stage 0.2");
  });
  EXPECT_EQ(value("f_c[7]"), 48.0);    // contacts
  EXPECT_EQ(value("f_c[4]"), 48.0);    // attached
  // the friction force is the sum of the per-contact forces k_i s_i
  // (start reform: s_i != 0), column 3 of the per-atom array
  double **a = lmp->modify->fix[lmp->modify->find_fix("c")]->array_atom;
  double sum = 0.0, mag = 0.0;
  for (int i = 0; i < lmp->atom->nlocal; i++) {
    sum += a[i][2];
    mag += std::fabs(a[i][2]);
  }
  EXPECT_GT(mag, 0.0);
  EXPECT_NEAR(value("f_c[1]"), sum, 1e-14 * mag);
  EXPECT_EQ(value("f_s[10]"), 48.0);             // blocks
  EXPECT_NEAR(value("f_s[7]"), 48 * 1.0, 48 * 4e-16 * 48);    // sum K (X_s - u) = 48 * 2 * 0.5
  EXPECT_EQ(value("f_b[6]"), 48.0);
  EXPECT_NEAR(value("f_b[5]"), 48 * 3.0 * 0.2, 48 * 4e-16 * 28.8);    // a sum of 48 terms
}

/* ----------------------------------------------------------------------
   combinations the documentation forbids
------------------------------------------------------------------------- */

TEST_F(EQState, ForbiddenCombinations)
{
  // the thermal keywords keep times on the fix's clock: time runs forward
  HIDE_OUTPUT([&] {
    command("timestep -0.01");
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 thermal 0.1 1.0 1.0");
    command("fix m all move linear 0.1 0.0 0.0 units box");
  });
  TEST_FAILURE(".*ERROR: Fix c eq/contacts: the keywords thermal, barrier, aging, delay, rest "
               "need time to run forward: timestep -0.01.*",
               command("run 1 post no"););
  HIDE_OUTPUT([&] {
    command("unfix m");
    command("timestep 0.01");
    command("fix m all move linear 0.1 0.0 0.0 units box");
    command("run 1 post no");
    command("unfix m");
    command("unfix c");
  });
  HIDE_OUTPUT([&] {
    command(CONTACTS);
    command("fix q all eq/quasistatic c");
    command("fix m all move linear 0.1 0.0 0.0 units box");
  });
  TEST_FAILURE(".*ERROR: Fix q eq/quasistatic and fix m move both move 48 atoms.*",
               command("run 1 post no"););
  HIDE_OUTPUT([&] {
    command("unfix m");
    command("unfix q");
    command("unfix c");
    command("fix s all eq/substrate 1.0 sawtooth 1.0 drive 1.0 0.0 stage 0.3");
  });
  TEST_FAILURE(".*ERROR: Fix s eq/substrate: minimize \\(min_style cg\\) needs the substrate "
               "energy: add fix_modify s energy yes.*",
               command("minimize 0 1e-8 100 1000"););
  HIDE_OUTPUT([&] {
    command("fix_modify s energy yes");
    command("minimize 0 1e-8 100 1000");
    command("fix_modify s energy no");
    command("min_style fire");
    command("minimize 0 1e-8 100 1000");
    command("fix o all brownian 1e-6 1 gamma_t 1.0 rng none");
    command("fix v all nve");
  });
  TEST_FAILURE(".*ERROR: Fix s eq/substrate: its blocks are moved by a first-order integrator "
               "\\(fix o brownian\\) and a velocity-Verlet one \\(fix v nve\\).*",
               command("run 1 post no"););
  HIDE_OUTPUT([&] {
    command("unfix s");
    command("fix s all eq/substrate 1.0 sawtooth 1.0 integrator overdamped");
    command("run 1 post no");
  });
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
