// Bad input to pair_style eq/elastic, fix eq/quasistatic and the
// interaction keywords of fix eq/contacts gives a LAMMPS error naming the
// command, the keyword and the allowed values.  Uses LAMMPS' unittest
// helpers (unittest/testing/core.h).
#include "lammps.h"

#include "force.h"
#include "input.h"
#include "modify.h"
#include "pair.h"

#include "testing/core.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <cstdio>
#include <fstream>
#include <mpi.h>

bool verbose = false;

namespace {

const std::string KTABLE = std::string(FEQ_SOURCE_DIR) + "/potentials/eq_crossover.table";

class EQInteractErrors : public LAMMPSTest {
 protected:
  void InitSystem() override
  {
    HIDE_OUTPUT([&] {
      command("units lj");
      command("dimension 2");
      command("atom_style atomic");
      command("lattice hex 1.1547005383792515");
      command("region box block 0 6 0 4 -0.5 0.5");
      command("create_box 2 box");
      command("create_atoms 1 box");
      command("mass * 1.0");
      command("neighbor 0.5 bin");
    });
  }
};

}    // namespace

TEST_F(EQInteractErrors, PairStyleAndCoeffs)
{
  TEST_FAILURE(".*ERROR: Illegal pair_style eq/elastic command: expected 'pair_style eq/elastic "
               "rcut \\[check N\\]'.*",
               command("pair_style eq/elastic"););
  TEST_FAILURE(".*ERROR: Illegal pair_style eq/elastic command: expected 'pair_style eq/elastic "
               "rcut \\[check N\\]'.*",
               command("pair_style eq/elastic 3.0 check"););
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: unknown keyword 'every'; allowed: check.*",
               command("pair_style eq/elastic 3.0 every 10"););
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: check must be an integer >= 0 \\(0: never; got "
               "-5\\).*",
               command("pair_style eq/elastic 3.0 check -5"););
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: check: expected an integer, got '2.5'.*",
               command("pair_style eq/elastic 3.0 check 2.5"););
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: rcut must be a finite number > 0 \\(got -1\\).*",
               command("pair_style eq/elastic -1"););
  TEST_FAILURE(".*ERROR: Pair style eq/elastic: rcut must be a finite number > 0 \\(got 1e999\\).*",
               command("pair_style eq/elastic 1e999"););
  BEGIN_HIDE_OUTPUT();
  command("pair_style eq/elastic 3.0");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Incorrect args for pair eq/elastic coefficients: expected 'pair_coeff I "
               "J ftilde lambda_c \\[rcut\\]' or 'pair_coeff I J table FILE KEYWORD \\[rcut\\]'.*",
               command("pair_coeff 1 1"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: ftilde must be >= 0 \\(got "
               "-0.1.*\\).*",
               command("pair_coeff 1 1 -0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: lambda_c must be > 0.*",
               command("pair_coeff 1 1 0.1 0.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: ftilde 'abc' is not a number; "
               "allowed: a number >= 0 or the word 'table'.*",
               command("pair_coeff 1 1 abc 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: lambda_c 'x' is not a number > 0.*",
               command("pair_coeff 1 1 0.1 x"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: rcut must be a finite number > 0 "
               "\\(got 0\\).*",
               command("pair_coeff 1 1 0.1 3.0 0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: rcut must be a finite number > 0 "
               "\\(got 1e999\\).*",
               command("pair_coeff 1 1 0.1 3.0 1e999"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: ftilde must be >= 0.*",
               command("pair_coeff 1 1 1e999 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: wrong number of values.*",
               command("pair_coeff 1 1 0.1 3.0 4.0 5.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: cannot open table file "
               "'nonexistent.table'.*",
               command("pair_coeff 1 1 table nonexistent.table K"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: keyword 'NOPE' not found in table "
               "file.*",
               command("pair_coeff 1 1 table " + KTABLE + " NOPE"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: table: wrong number of values.*",
               command("pair_coeff 1 1 table " + KTABLE););
  // type ranges are checked by the pair style (not by LAMMPS' utils::bounds,
  // whose message named neither the command nor the type)
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 3 3: atom type '3' is out of range "
               "\\(the box has 2 atom types\\); allowed: 1-2, \\*, \\*N, M\\*, M\\*N.*",
               command("pair_coeff 3 3 0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 0 0: atom type '0' is out of range.*",
               command("pair_coeff 0 0 0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 a: atom type 'a' is neither an atom "
               "type nor a range of types; allowed: 1-2.*",
               command("pair_coeff 1 a 0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1\\*3 1: atom type '1\\*3' is out of "
               "range.*",
               command("pair_coeff 1*3 1 0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 2\\*1 1: atom type '2\\*1' is an empty "
               "range.*",
               command("pair_coeff 2*1 1 0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for -1 1: atom type '-1' is neither.*",
               command("pair_coeff -1 1 0.1 3.0"););
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1\\*\\*2 1: atom type '1\\*\\*2' is "
               "neither.*",
               command("pair_coeff 1**2 1 0.1 3.0"););
  HIDE_OUTPUT([&] {
    command("pair_coeff 2* *2 0.1 3.0");
    command("pair_coeff *1 1* 0.1 3.0");
  });
}

TEST_F(EQInteractErrors, BadTables)
{
  const std::string bad = "eq_bad_kernel.table";
  {
    std::ofstream f(bad);
    f << "# bad tables\nUNSORTED\nN 3\n\n1 1.0 1.0\n2 0.5 2.0\n3 2.0 0.5\n\n"
      << "SHORT\nN 4\n\n1 1.0 1.0\n2 2.0 0.5\n\nNEGR\nN 2\n1 -1.0 1.0\n2 2.0 0.5\n\n"
      << "FLAG\nN 2 iso\n1 1.0 1.0\n2 2.0 0.5\n\nANISO3\nN 2 aniso\n1 1.0 1.0\n2 2.0 0.5\n";
  }
  BEGIN_HIDE_OUTPUT();
  command("pair_style eq/elastic 3.0");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: table file 'eq_bad_kernel.table' "
               "line 6: r must increase strictly.*",
               command("pair_coeff 1 1 table " + bad + " UNSORTED"););
  TEST_FAILURE(".*ERROR: .*section 'SHORT': expected 4 points, found 2.*",
               command("pair_coeff 1 1 table " + bad + " SHORT"););
  TEST_FAILURE(".*ERROR: .*line 17: r must be > 0.*",
               command("pair_coeff 1 1 table " + bad + " NEGR"););
  TEST_FAILURE(".*ERROR: .*unknown flag 'iso' after 'N 2'; allowed: aniso.*",
               command("pair_coeff 1 1 table " + bad + " FLAG"););
  TEST_FAILURE(".*ERROR: .*expected 'index r k0 k2'.*",
               command("pair_coeff 1 1 table " + bad + " ANISO3"););
  remove(bad.c_str());
}

TEST_F(EQInteractErrors, PairNeedsContactsAndMixing)
{
  BEGIN_HIDE_OUTPUT();
  command("pair_style eq/elastic 3.0");
  command("pair_coeff 1 1 0.1 3.0");
  command("pair_coeff 2 2 0.1 3.0");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Pair style eq/elastic needs a fix eq/contacts.*", command("run 0 post no"););
  BEGIN_HIDE_OUTPUT();
  command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25");
  END_HIDE_OUTPUT();
  // fix adapt would change the extract()ed arrays without effect: refused
  BEGIN_HIDE_OUTPUT();
  command("variable f equal 0.05");
  command("fix a all adapt 1 pair eq/elastic ftilde 1 1 v_f");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Pair style eq/elastic does not support fix adapt \\(its kernels are set "
               "by pair_coeff\\): change the coefficients with pair_coeff between runs.*",
               command("run 0 post no"););
  BEGIN_HIDE_OUTPUT();
  command("unfix a");
  command("fix d all eq/contacts 1.0 6 threshold uniform 0.75 1.25");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Pair style eq/elastic found 2 fixes with coordinates \\(fix c "
               "eq/contacts, fix d eq/contacts\\); allowed: exactly one fix eq/contacts, "
               "eq/substrate or eq/meso.*",
               command("run 0 post no"););
  BEGIN_HIDE_OUTPUT();
  command("unfix d");
  command("pair_coeff 2 2 table " + KTABLE + " CROSSOVER_L3");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Pair eq/elastic: type pair 1 2 would mix a table kernel; set pair_coeff 1 "
               "2 explicitly.*",
               command("run 0 post no"););
  BEGIN_HIDE_OUTPUT();
  command("pair_coeff 1 2 0.1 3.0");
  command("run 0 post no");
  command("run_style respa 2 2");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Fix eq/contacts with pair style eq/elastic does not support run_style "
               "respa; allowed: run_style verlet.*",
               command("run 0 post no"););
}

TEST_F(EQInteractErrors, ContactKeywords)
{
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform_as: unknown value 'spring'; allowed: stretch, "
               "force.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 reform_as spring"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts reform_as: missing value; allowed: stretch, force.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 reform_as"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts avalanches: missing file name.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 avalanches"););
  TEST_FAILURE(".*ERROR.*: Fix eq/contacts avalanches: cannot open file /nonexistent/dir/a.dat.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 avalanches "
                       "/nonexistent/dir/a.dat"););
}

TEST_F(EQInteractErrors, Quasistatic)
{
  BEGIN_HIDE_OUTPUT();
  command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25 reform none");
  command("fix m all nve");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Illegal fix eq/quasistatic command: expected 'fix ID group "
               "eq/quasistatic contacts-ID \\[max dX\\]'.*",
               command("fix q all eq/quasistatic"););
  TEST_FAILURE(".*ERROR: Fix eq/quasistatic: unknown keyword 'min'; allowed: max.*",
               command("fix q all eq/quasistatic c min 0.1"););
  TEST_FAILURE(".*ERROR: Fix eq/quasistatic max: value must be finite and > 0 \\(got -0.1\\).*",
               command("fix q all eq/quasistatic c max -0.1"););
  TEST_FAILURE(".*ERROR: Fix eq/quasistatic max: missing value.*",
               command("fix q all eq/quasistatic c max"););
  BEGIN_HIDE_OUTPUT();
  command("fix q all eq/quasistatic nothere");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Fix q eq/quasistatic: fix ID nothere does not exist; expected the ID of "
               "a fix eq/contacts.*",
               command("run 1 post no"););
  BEGIN_HIDE_OUTPUT();
  command("unfix q");
  command("fix q all eq/quasistatic m");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Fix q eq/quasistatic: fix m is a fix nve, not eq/contacts.*",
               command("run 1 post no"););
  // the slider must carry every contact
  BEGIN_HIDE_OUTPUT();
  command("unfix q");
  command("group half id <= 10");
  command("fix q half eq/quasistatic c");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Fix eq/quasistatic: group half leaves 38 contacts of fix c \\(group "
               "all\\) behind; the advance to the next break assumes that every contact moves "
               "with the slider: use a group that contains group all.*",
               command("run 1 post no"););
  // every contact broken for good (each step breaks at least one of the
  // 48): nothing left to drive towards
  BEGIN_HIDE_OUTPUT();
  command("unfix q");
  command("unfix m");
  command("fix q all eq/quasistatic c");
  END_HIDE_OUTPUT();
  TEST_FAILURE(".*ERROR: Fix eq/quasistatic: no attached contact left in fix c; nothing can break "
               "\\(use the max keyword to keep driving\\).*",
               command("run 49 post no"););
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
