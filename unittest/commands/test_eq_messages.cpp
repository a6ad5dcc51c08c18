// Messages that name the cause, and long sliding:
//  - a table path that is a directory (every command that reads a table)
//  - a subnormal (or underflowing) number in a threshold or substrate table
//  - per-atom restart records that do not fit the fix (garbled file, other
//    settings): an error naming the fix and the counts, not a crash
//  - LAMMPS' image counts wrap after IMGMAX = 512 periodic crossings (the
//    unwrapped coordinate jumps by 1024 box lengths): contacts and blocks
//    that slide over thousands of box lengths go on as in a long box
// Uses LAMMPS' own unittest helpers (unittest/testing/core.h).
#include "lammps.h"

#include "atom.h"
#include "domain.h"
#include "fix.h"
#include "input.h"
#include "modify.h"
#include "lmptype.h"
#include "update.h"

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
#include <sys/stat.h>
#include <vector>

bool verbose = false;

namespace {

class EQMessages : public LAMMPSTest {
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
    });
  }
};

// a directory named like a table file, removed at the end of the test
struct TempDir {
  std::string name;
  explicit TempDir(const std::string &n) : name(n) { ::mkdir(n.c_str(), 0755); }
  ~TempDir() { std::remove(name.c_str()); }
};

}    // namespace

/* ----------------------------------------------------------------------
   1. a table path that is a directory: the stream opens and reads empty,
   so the message was "keyword ... not found in table file"
------------------------------------------------------------------------- */

TEST_F(EQMessages, TablePathIsADirectory)
{
  TempDir dir("eq_dir.table");
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: cannot open table file "
               "'eq_dir.table': it is a directory, not a file.*",
               command("fix c all eq/contacts 1.0 5 threshold table eq_dir.table KEY"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: cannot open table file '\\.': it is a "
               "directory, not a file.*",
               command("fix c all eq/contacts 1.0 5 threshold table . KEY"););
  TEST_FAILURE(".*ERROR: eq/me threshold table: cannot open table file 'eq_dir.table': it is a "
               "directory, not a file.*",
               command("eq/me threshold table eq_dir.table KEY xmax 2 dx 0.01"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: cannot open table file 'eq_dir.table': it is a "
               "directory, not a file.*",
               command("fix s all eq/substrate 1.0 table eq_dir.table KEY"););
  HIDE_OUTPUT([&] { command("pair_style eq/elastic 3.0"); });
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: cannot open table file "
               "'eq_dir.table': it is a directory, not a file.*",
               command("pair_coeff 1 1 table eq_dir.table KEY"););
  // a file that is not there: the system's reason
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: cannot open table file "
               "'eq_no_such.table' \\(No such file or directory\\).*",
               command("fix c all eq/contacts 1.0 5 threshold table eq_no_such.table KEY"););
}

/* ----------------------------------------------------------------------
   2. subnormal numbers in threshold and substrate tables (strtod flags
   most of them ERANGE: they were reported as "expected a number"; an
   exact one such as 0x1p-1030 was read silently)
------------------------------------------------------------------------- */

TEST_F(EQMessages, SubnormalNumbersInTables)
{
  {
    std::ofstream out("eq_sn.table");
    out << "# subnormal values\n"                                             // line 1
        << "SUB\nN 4\n\n1 0.5 0.0\n2 0.8 1e-310\n3 1.0 1.0\n4 1.3 0.0\n\n"    // 2-9, 1e-310: 6
        << "SUBX\nN 3\n\n1 0.0 0.0\n2 0x1p-1030 1.0\n3 1.3 0.0\n\n"           // 10-16: 14
        << "UNDER\nN 3\n\n1 0.0 0.0\n2 0.5 -1e-400\n3 1.3 0.0\n\n"            // 17-23: 21
        << "NORMAL\nN 3\n\n1 0.0 0.0\n2 2.2250738585072014e-308 1.0\n3 1.3 1e-300\n\n"
        << "BLOCK\nN 3\n\n1 0.0 0.0\n2 0.5 4.9e-324\n3 1.0 0.8\n";            // 31-36: 35
  }
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_sn.table' line 6: value "
               "'1e-310' is subnormal \\(nonzero and smaller in magnitude than 2.225073859e-308, "
               "the smallest normal double: it would lose precision\\); write 0 or a normal "
               "number.*",
               command("fix c all eq/contacts 1.0 5 threshold table eq_sn.table SUB"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_sn.table' line 14: value "
               "'0x1p-1030' is subnormal.*",
               command("fix c all eq/contacts 1.0 5 threshold table eq_sn.table SUBX"););
  TEST_FAILURE(".*ERROR: Fix eq/contacts threshold table: table file 'eq_sn.table' line 21: value "
               "'-1e-400' is below the subnormal range of a double \\(it would be read as 0\\); "
               "write 0 or a normal number.*",
               command("fix c all eq/contacts 1.0 5 threshold table eq_sn.table UNDER"););
  TEST_FAILURE(".*ERROR: eq/me threshold table: table file 'eq_sn.table' line 6: value '1e-310' "
               "is subnormal.*",
               command("eq/me threshold table eq_sn.table SUB xmax 2 dx 0.01"););
  TEST_FAILURE(".*ERROR: Fix eq/substrate table: table file 'eq_sn.table' line 35: value "
               "'4.9e-324' is subnormal.*",
               command("fix s all eq/substrate 1.0 table eq_sn.table BLOCK"););
  // the smallest normal number and tiny normal densities are read
  HIDE_OUTPUT([&] { command("fix c all eq/contacts 1.0 5 threshold table eq_sn.table NORMAL"); });
  ASSERT_NE(lmp->modify->find_fix("c"), -1);
  std::remove("eq_sn.table");
}

// Kernel tables (pair_coeff ... table) are read by lib/eq_kernel.cpp with a
// number reader of its own, which takes subnormals silently; enable with
// the change of read_kernel_table() to feq::parse_number().
TEST_F(EQMessages, SubnormalNumbersInKernelTables)
{
  {
    std::ofstream out("eq_snk.table");
    out << "KERN\nN 3\n\n1 1.0 0.06\n2 2.0 1e-310\n3 3.0 0.0\n";    // 1e-310: line 5
  }
  HIDE_OUTPUT([&] { command("pair_style eq/elastic 3.0"); });
  TEST_FAILURE(".*ERROR: Pair eq/elastic coefficients for 1 1: table file 'eq_snk.table' line 5: "
               "value '1e-310' is subnormal.*",
               command("pair_coeff 1 1 table eq_snk.table KERN"););
  std::remove("eq_snk.table");
}

/* ----------------------------------------------------------------------
   4. per-atom restart records: the restart file's records of one atom are
   [length, x, y, z, tag, type, mask, image, vx, vy, vz, fix records...],
   each fix record [length, values...]; here fix spring/self (4) and fix
   eq/contacts (1 + 7)
------------------------------------------------------------------------- */

namespace {

std::vector<char> read_bytes(const std::string &file)
{
  std::ifstream in(file, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string &file, const std::vector<char> &b)
{
  std::ofstream out(file, std::ios::binary);
  out.write(b.data(), (std::streamsize) b.size());
}

double at(const std::vector<char> &b, size_t o)
{
  double v;
  memcpy(&v, &b[o], sizeof(double));
  return v;
}

// the byte offsets of the atoms' records: [23, 10 values, 4, 3 values, 8, 7 values]
std::vector<size_t> atom_records(const std::vector<char> &b)
{
  std::vector<size_t> found;
  const size_t d = sizeof(double);
  for (size_t o = 0; o + 23 * d <= b.size(); ++o)
    if (at(b, o) == 23.0 && at(b, o + 11 * d) == 4.0 && at(b, o + 15 * d) == 8.0)
      found.push_back(o);
  return found;
}

}    // namespace

TEST_F(EQMessages, RestartRecordsAreChecked)
{
  HIDE_OUTPUT([&] {
    command("fix sp all spring/self 1.0");
    command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25");
    command("run 0 post no");
    command("write_restart eq_rec.restart");
  });
  const double th = lmp->modify->fix[lmp->modify->find_fix("c")]->array_atom[0][1];
  const std::vector<char> good = read_bytes("eq_rec.restart");
  const std::vector<size_t> recs = atom_records(good);
  ASSERT_EQ(recs.size(), 16u);
  const size_t d = sizeof(double);
  auto patched = [&](size_t off, double v) {
    std::vector<char> b = good;
    for (const size_t o : recs) memcpy(&b[o + off * d], &v, d);
    write_bytes("eq_rec_bad.restart", b);
  };
  auto reread = [&](const std::string &file) {
    HIDE_OUTPUT([&] {
      command("clear");
      command("read_restart " + file);
    });
  };

  // the file as written: the state comes back
  reread("eq_rec.restart");
  HIDE_OUTPUT([&] { command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25"); });
  EXPECT_EQ(lmp->modify->fix[lmp->modify->find_fix("c")]->array_atom[0][1], th);

  // this fix's record says 3 values (length 4): another version or settings
  patched(15, 4.0);
  reread("eq_rec_bad.restart");
  TEST_FAILURE(".*ERROR on proc 0: Fix c eq/contacts: the restart file holds 3 values per atom "
               "for this fix, it expects 7 \\(a corrupt file, or one written by another version "
               "of the package or other settings\\).*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
  // ... or more than the atom's data holds (it segfaulted or read garbage)
  patched(15, 1e6);
  reread("eq_rec_bad.restart");
  TEST_FAILURE(".*ERROR on proc 0: Fix c eq/contacts: the restart file's per-atom data of atom "
               "[0-9]+ is garbled: this fix's record \\(record 2\\) has length 1000000, expected "
               "8 with room for 8.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
  patched(15, std::nan(""));
  reread("eq_rec_bad.restart");
  TEST_FAILURE(".*ERROR on proc 0: Fix c eq/contacts: the restart file's per-atom data of atom "
               "[0-9]+ is garbled: this fix's record \\(record 2\\) has length nan.*",
               command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
  // the record before it (fix spring/self's) is garbled
  for (const double v : {0.0, -4.0, 2.5, 1e9}) {
    patched(11, v);
    reread("eq_rec_bad.restart");
    TEST_FAILURE(".*ERROR on proc 0: Fix c eq/contacts: the restart file's per-atom data of atom "
                 "[0-9]+ is garbled: record 1 of the 1 stored before this fix's has length "
                 "[-0-9.e+]+, expected 1 to 12 \\(a corrupt file, or one written by another "
                 "version of LAMMPS or the package\\).*",
                 command("fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25"););
  }
  std::remove("eq_rec.restart");
  std::remove("eq_rec_bad.restart");
}

/* ----------------------------------------------------------------------
   3. sliding over a thousand box lengths: after IMGMAX = 512 crossings
   the image count wraps (from 511 to -512 along +x).  Each run starts
   with image count 0 along x and wraps; it is compared with the same run
   started at image count -511, which reaches +489 after 1000 crossings
   and never wraps (same box, same atoms and seeds: the same breaks).
------------------------------------------------------------------------- */

namespace {
struct Outcome {
  double breaks, force, disp;
};
}    // namespace

class EQLongSliding : public EQMessages {
 protected:
  void InitSystem() override {}
  // n atoms in a row along y at x = 0.5 in a box [0, 1] x [0, n] (a
  // triclinic one with tilt xy = 0.3 when tri), tags 1..n, image count ix
  // along x
  void slider_box(int n, bool tri, int ix)
  {
    command("clear");
    command("units lj");
    command("dimension 2");
    command("atom_style atomic");
    command("lattice sq 1.0");
    const std::string lo = "0 1 0 " + std::to_string(n) + " -0.5 0.5";
    if (tri)
      command("region box prism " + lo + " 0.3 0 0");
    else
      command("region box block " + lo);
    command("create_box 1 box");
    for (int k = 0; k < n; ++k) command("create_atoms 1 single 0.5 " + std::to_string(k + 0.5) + " 0");
    command("mass 1 1.0");
    command("set atom * image " + std::to_string(ix) + " 0 0");
    command("neighbor 0.3 bin");
    command("neigh_modify every 1 delay 0 check yes");
  }
  // the image counts along x of all atoms lie in [lo, hi]
  void check_images(int lo, int hi)
  {
    const auto *image = lmp->atom->image;
    for (int i = 0; i < lmp->atom->nlocal; ++i) {
      const int ix = (int) (image[i] & IMGMASK) - IMGMAX;
      ASSERT_TRUE(ix >= lo && ix <= hi) << "image count " << ix;
    }
  }

  // fix eq/contacts (optionally with pair eq/elastic) driven by fix move
  // (0.4 per step) or fix eq/quasistatic (max 0.4) over `steps` steps;
  // the total of breaks and the force
  Outcome contacts(bool tri, bool pair, bool qs, int steps, int ix)
  {
    HIDE_OUTPUT([&] {
      slider_box(6, tri, ix);
      if (pair) {
        command("pair_style eq/elastic 2.5");
        command("pair_coeff 1 1 0.06 2.5");
      }
      command("fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25 reform delta 0.0");
      if (qs) {
        command("fix q all eq/quasistatic c max 0.4");
      } else {
        command("fix m all move linear 0.4 0.0 0.0 units box");
        command("timestep 1.0");
      }
      command("thermo 0");
      command("run " + std::to_string(steps) + " post no");
    });
    LAMMPS_NS::Fix *c = lmp->modify->fix[lmp->modify->find_fix("c")];
    return {c->compute_vector(2), c->compute_vector(0), 0.0};
  }

  // blocks of fix eq/substrate or fix eq/meso, each driven by a spring to
  // a stage that moves by 0.2 per step (5000 steps: 1000 box lengths);
  // the mean displacement and the total force
  Outcome blocks(bool meso, bool tri, bool pair, int ix)
  {
    HIDE_OUTPUT([&] {
      slider_box(3, tri, ix);
      command("comm_modify cutoff 2.0");
      if (pair) {
        command("pair_style eq/elastic 2.0");
        command("pair_coeff 1 1 0.05 2.0");
      }
      if (meso)
        command("fix s all eq/meso 20 0.05 threshold uniform 0.75 1.25 reform delta 0.0 "
                "drive 1.0 4.0");
      else
        command("fix s all eq/substrate 1.0 sawtooth 1.0 drive 1.0 4.0");
      command("fix n all nve");
      command("fix v all viscous 2.0");
      command("timestep 0.05");
      command("thermo 0");
      command("run 5000 post no");
    });
    LAMMPS_NS::Fix *s = lmp->modify->fix[lmp->modify->find_fix("s")];
    // fix eq/substrate: [4] mean displacement, [5] F_s; eq/meso: [3], [0]
    return {0.0, s->compute_vector(meso ? 0 : 5), s->compute_vector(meso ? 3 : 4)};
  }
};

// the total of breaks is a count, the force a sum over 6 contacts
TEST_F(EQLongSliding, ContactsOrthogonalBox)
{
  const Outcome a = contacts(false, false, false, 2500, 0);
  check_images(-24, -24);    // 1000 crossings: wrapped
  const Outcome b = contacts(false, false, false, 2500, -511);
  check_images(489, 489);
  EXPECT_GT(a.breaks, 5000.0);
  EXPECT_EQ(a.breaks, b.breaks);
  EXPECT_NEAR(a.force, b.force, 1e-9);
}

// domain->unmap() wraps as well: the jump was not undone in triclinic
// boxes ("contact 1 broke more than 1000 times in one step")
TEST_F(EQLongSliding, ContactsTriclinicBox)
{
  const Outcome a = contacts(true, false, false, 2500, 0);
  check_images(-24, -24);    // 1000 crossings: wrapped
  const Outcome b = contacts(true, false, false, 2500, -511);
  EXPECT_EQ(a.breaks, b.breaks);
  EXPECT_NEAR(a.force, b.force, 1e-9);
}

TEST_F(EQLongSliding, ContactsWithElasticInteraction)
{
  for (const bool tri : {false, true}) {
    const Outcome a = contacts(tri, true, false, 2500, 0);
    check_images(-24, -24);    // 1000 crossings: wrapped
    const Outcome b = contacts(tri, true, false, 2500, -511);
    EXPECT_EQ(a.breaks, b.breaks) << "triclinic " << tri;
    EXPECT_NEAR(a.force, b.force, 1e-9) << "triclinic " << tri;
  }
}

TEST_F(EQLongSliding, ContactsQuasistatic)
{
  for (const bool tri : {false, true})
    for (const bool pair : {false, true}) {
      const Outcome a = contacts(tri, pair, true, 4000, 0);
      const Outcome b = contacts(tri, pair, true, 4000, -511);
      EXPECT_EQ(a.breaks, b.breaks) << "triclinic " << tri << " pair " << pair;
      EXPECT_NEAR(a.force, b.force, 1e-9) << "triclinic " << tri << " pair " << pair;
    }
}

// Blocks' displacements grow without bound: folding them by the wrap
// length made them jump by 1024 box lengths at the wrap (lost atoms).
// Enable with the call-site change of the block fixes to
// EQUtil::Unwrap::displacement() (eq_fix_blocks.cpp, fix_eq_substrate.cpp,
// fix_eq_meso.cpp).
TEST_F(EQLongSliding, BlocksSlideFar)
{
  for (const bool meso : {false, true})
    for (const bool tri : {false, true})
      for (const bool pair : {false, true}) {
        const Outcome a = blocks(meso, tri, pair, 0);
        check_images(-40, -20);    // wrapped
        const Outcome b = blocks(meso, tri, pair, -511);
        check_images(470, 490);
        const std::string what = std::string(meso ? "meso" : "substrate") +
            (tri ? " triclinic" : "") + (pair ? " pair" : "");
        EXPECT_GT(a.disp, 990.0) << what;
        EXPECT_NEAR(a.disp, b.disp, 1e-6) << what;
        EXPECT_NEAR(a.force, b.force, 1e-6) << what;
      }
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
