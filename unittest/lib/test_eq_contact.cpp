// Unit tests: the break engine of the EQ model (lib/eq_contact).  The
// references are independent of the engine's own loops: closed forms of
// the renewal process, a sequential (one break at a time) cascade written
// here, a mock field recomputed from scratch after every change, and the
// Abelian property of exact crossing.
#include "eq_contact.h"
#include "eq_distribution.h"
#include "eq_random.h"
#include "eq_thermal.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace feq;

namespace {

DistributionSpec spec(DistributionPtr d, const std::string &text)
{
  DistributionSpec s;
  s.dist = std::move(d);
  s.text = text;
  return s;
}

DistributionSpec none()
{
  return DistributionSpec{};
}

ContactModel model(bool exact, bool reform_force, DistributionSpec reform,
                   DistributionSpec stiffness = DistributionSpec{})
{
  return ContactModel(1.0, 4711, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"),
                      std::move(reform), std::move(stiffness), exact, reform_force, false);
}

std::vector<double> fresh_row(const ContactModel &m, uint64_t tag, double xu)
{
  std::vector<double> row(CS_NCOL, 0.0);
  m.form(row.data(), tag, xu);
  return row;
}

// a field h_i = sum_j k_ij (s_i - s_j) over a dense symmetric matrix,
// recomputed from the stretches after every change (no incremental
// update).  name_changed: after a change set it names the rows whose h
// changed (the broken ones and their partners, k_ij != 0), as pair
// eq/elastic does; else it names none (any row may have changed).
class DenseField : public AvalancheHooks {
 public:
  DenseField(std::vector<std::vector<double>> kmat, std::vector<double *> rows,
             bool name = false) :
      k(std::move(kmat)), rows(std::move(rows)), h(k.size(), 0.0), K(k.size(), 0.0),
      name_changed(name)
  {
    recompute();
  }
  void recompute()
  {
    const size_t n = k.size();
    for (size_t i = 0; i < n; ++i) {
      h[i] = K[i] = 0.0;
      if (!in_field(i)) continue;
      for (size_t j = 0; j < n; ++j) {
        if (j == i || !in_field(j)) continue;
        K[i] += k[i][j];
        h[i] += k[i][j] * (rows[i][CS_STRETCH] - rows[j][CS_STRETCH]);
      }
    }
  }
  // formed, and not waiting to re-form (thermal_rows: rows of CT_NCOL)
  bool in_field(size_t i) const
  {
    return rows[i][CS_THRESHOLD] > 0.0 && !(thermal_rows && rows[i][CT_WAIT] > 0.0);
  }
  AvalancheField view(bool named)
  {
    AvalancheField f;
    f.h = h.data();
    f.k = K.data();
    if (named) {
      f.changed = names.data();
      f.nchanged = static_cast<int>(names.size());
    }
    return f;
  }
  void global_sum(long *, int) override {}    // one rank
  AvalancheField field() override { return view(false); }
  AvalancheField changed(const int *list, int n, const double *, bool exact) override
  {
    ++nchanged;
    last_exact = exact;
    nbroken += n;
    recompute();
    names.clear();
    for (int m = 0; m < n; ++m) {
      const int i = list[m];
      names.push_back(i);
      for (size_t j = 0; j < k.size(); ++j)
        if (k[i][j] != 0.0) names.push_back(static_cast<int>(j));
    }
    return view(name_changed);
  }
  AvalancheField detached(const int *list, int n, bool exact) override
  {
    ++ndetached;
    last_exact = exact;
    left.assign(list, list + n);
    recompute();
    return view(false);
  }
  uint64_t tag(int i) const override { return 100 + i; }

  std::vector<std::vector<double>> k;
  std::vector<double *> rows;
  std::vector<double> h, K;
  bool name_changed;
  bool thermal_rows = false;
  std::vector<int> names, left;
  int nchanged = 0, ndetached = 0;
  bool last_exact = true;
  long nbroken = 0;
};

// n fresh contacts (tags 100 + i) with the stretches stretch(i, x_s of
// contact i): their rows, and pointers to them in the avalanche's layout
struct Rows {
  std::vector<std::vector<double>> a;
  std::vector<double *> r;
};
template <class F> Rows rows_with(const ContactModel &m, int n, F stretch)
{
  Rows c;
  c.a.resize(n);
  for (int i = 0; i < n; ++i) {
    c.a[i] = fresh_row(m, 100 + i, 0.0);
    c.a[i][CS_STRETCH] = stretch(i, c.a[i][CS_THRESHOLD]);
  }
  for (auto &row : c.a) c.r.push_back(row.data());
  return c;
}

// chain of n contacts, nearest neighbours coupled by g, periodic
std::vector<std::vector<double>> chain_matrix(int n, double g)
{
  std::vector<std::vector<double>> k(n, std::vector<double>(n, 0.0));
  for (int i = 0; i < n; ++i) {
    k[i][(i + 1) % n] += g;
    k[(i + 1) % n][i] += g;
  }
  return k;
}

}    // namespace

// a new contact: relaxed at the atom, threshold from the stateless draw of
// event 0 (the inverse transform of the uniform variate, written out here)
TEST(ContactModel, FormsRelaxedWithTheEventZeroThreshold)
{
  const ContactModel m = model(true, true, spec(make_delta(0.0), "delta 0"));
  const auto row = fresh_row(m, 17, 3.25);
  const Uniform u = draw(4711, 17, 0, STREAM_THRESHOLD);
  // uniform on [0.75, 1.25]: sample() maps u < 1/2 to the upper tail
  const double expect = u.u < 0.5 ? 1.25 - 0.5 * u.u : 0.75 + 0.5 * u.one_minus_u;
  EXPECT_NEAR(row[CS_THRESHOLD], expect, 1e-15);
  EXPECT_EQ(row[CS_STRETCH], 0.0);
  EXPECT_EQ(row[CS_ANCHOR], 3.25);
  EXPECT_EQ(row[CS_NBREAK], 0.0);
  EXPECT_EQ(row[CS_STIFFNESS], 1.0);
}

// A re-entry into the group draws from the re-entry streams: not the
// threshold of the first formation
TEST(ContactModel, ReentryDrawsNewNumbers)
{
  const ContactModel m = model(true, true, spec(make_delta(0.0), "delta 0"));
  auto row = fresh_row(m, 17, 0.0);
  const double first = row[CS_THRESHOLD];
  m.depart(row.data());
  EXPECT_EQ(row[CS_THRESHOLD], 0.0);
  EXPECT_LT(row[CS_STIFFNESS], 0.0);
  m.form(row.data(), 17, 1.0);
  EXPECT_GT(row[CS_THRESHOLD], 0.75);
  EXPECT_NE(row[CS_THRESHOLD], first);
  EXPECT_EQ(row[CS_ANCHOR], 1.0);
}

// Exact crossing, R = delta(0): a displacement D resolved in one step
// leaves the stretch D - (sum of the thresholds passed), the renewal
// identity; the same D in 1, 3 and 17 equal steps gives the same breaks
// and the same stretch (the step size drops out: Abelian in time)
TEST(ContactModel, ExactCrossingIndependentOfTheStep)
{
  const ContactModel m = model(true, false, spec(make_delta(0.0), "delta 0"));
  const double D = 7.3;
  double s_ref = 0.0;
  long nb_ref = 0;
  for (int nsteps : {1, 3, 17}) {
    auto row = fresh_row(m, 5, 0.0);
    double x = 0.0, passed = 0.0;
    long nb = 0;
    for (int k = 1; k <= nsteps; ++k) {
      const double xn = D * k / nsteps;
      double s = row[CS_STRETCH] + (xn - x);
      // thresholds passed in this step: read them as the contact renews
      double th = row[CS_THRESHOLD];
      const long before = nb;
      s = m.resolve(row.data(), 5, s, 0.0, nb);
      // reconstruct the passed thresholds from the draws of the events
      for (long e = before; e < nb; ++e) {
        passed += th;
        th = make_uniform(0.75, 1.25)->sample_above(0.0, draw(4711, 5, e + 1, STREAM_THRESHOLD));
      }
      row[CS_STRETCH] = s;
      x = xn;
    }
    EXPECT_NEAR(row[CS_STRETCH], D - passed, 1e-12) << nsteps;
    EXPECT_NEAR(nb, std::floor(D / 1.0), 2) << nsteps;    // mean threshold 1
    if (nsteps == 1) {
      s_ref = row[CS_STRETCH];
      nb_ref = nb;
    } else {
      EXPECT_NEAR(row[CS_STRETCH], s_ref, 1e-12) << nsteps;
      EXPECT_EQ(nb, nb_ref) << nsteps;
    }
  }
}

// Step crossing: every break re-forms at r = 0 at the end of the step, so
// a step that passes a threshold leaves the stretch exactly 0
TEST(ContactModel, StepCrossingResets)
{
  const ContactModel m = model(false, false, spec(make_delta(0.0), "delta 0"));
  auto row = fresh_row(m, 9, 0.0);
  long nb = 0;
  const double s = m.resolve(row.data(), 9, 1.3, 0.0, nb);
  EXPECT_EQ(nb, 1);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(row[CS_NBREAK], 1.0);
}

// A contact broken with negative stretch re-forms with the mirrored
// stretch: -r plus the (negative) carry
TEST(ContactModel, NegativeBreakMirrors)
{
  const ContactModel m = model(true, false, spec(make_delta(0.1), "delta 0.1"));
  auto row = fresh_row(m, 3, 0.0);
  const double th = row[CS_THRESHOLD];
  long nb = 0;
  const double s = m.resolve(row.data(), 3, -(th + 0.05), 0.0, nb);
  EXPECT_EQ(nb, 1);
  EXPECT_NEAR(s, -0.1 - 0.05, 1e-14);
}

// reform none: the contact detaches for good
TEST(ContactModel, ReformNoneDetaches)
{
  const ContactModel m = model(true, false, none());
  auto row = fresh_row(m, 3, 0.0);
  long nb = 0;
  EXPECT_EQ(m.resolve(row.data(), 3, 2.0, 0.0, nb), 0.0);
  EXPECT_EQ(nb, 1);
  EXPECT_LT(row[CS_THRESHOLD], 0.0);
}

// the breaking test with a tolerance: a contact within tol of its
// threshold breaks (quasi-static driving lands exactly on it)
TEST(ContactModel, ToleranceBreaksAtTheThreshold)
{
  const ContactModel m = model(true, false, spec(make_delta(0.0), "delta 0"));
  auto row = fresh_row(m, 4, 0.0);
  const double th = row[CS_THRESHOLD];
  row[CS_STRETCH] = th * (1.0 - 1e-13);
  long nb = 0;
  m.resolve(row.data(), 4, row[CS_STRETCH], 0.0, nb);
  EXPECT_EQ(nb, 0);
  const double tol = ContactModel::tolerance(row.data(), 1e-12);
  EXPECT_NEAR(tol, 1e-12 * (1.0 + th * (1.0 - 1e-13)), 1e-25);
  m.resolve(row.data(), 4, row[CS_STRETCH], 1e-12, nb);
  EXPECT_EQ(nb, 1);
}

TEST(ContactModel, RunawayAndNonFiniteAreErrors)
{
  const ContactModel m = model(true, false, spec(make_delta(0.0), "delta 0"));
  auto row = fresh_row(m, 4, 0.0);
  long nb = 0;
  EXPECT_THROW(m.resolve(row.data(), 4, 5000.0, 0.0, nb), BreakError);
  // the message gives the stretch the step ended with (after the 1000
  // breaks it is only what was left of it)
  row = fresh_row(m, 4, 0.0);
  try {
    m.resolve(row.data(), 4, 5000.0, 0.0, nb);
    FAIL();
  } catch (const BreakError &e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("contact 4 broke more than 1000 times in one step (stretch 5000 at the end "
                        "of the step, ", 0), 0u) << msg;
    EXPECT_NE(msg.find(" after 1000 breaks, threshold "), std::string::npos) << msg;
    EXPECT_NE(msg.find("); reduce the timestep or check the reform and threshold distributions"),
              std::string::npos) << msg;
  }
  row = fresh_row(m, 4, 0.0);
  EXPECT_THROW(m.resolve(row.data(), 4, std::numeric_limits<double>::infinity(), 0.0, nb),
               BreakError);
  EXPECT_THROW(m.break_once(row.data(), 4, std::nan(""), 0.0, 0.0), BreakError);
}

// the interacting path with zero coupling is the plain path
TEST(ContactModel, BreakOnceWithoutFieldEqualsResolve)
{
  const ContactModel m = model(true, true, spec(make_gaussian(0.0, 0.05, -INFINITY), "gaussian"));
  auto a = fresh_row(m, 21, 0.0), b = a;
  long nb = 0;
  const double sa = m.resolve(a.data(), 21, 1.3, 0.0, nb);
  ASSERT_EQ(nb, 1);
  b[CS_STRETCH] = 1.3;
  const double sb = m.break_once(b.data(), 21, 1.3, 0.0, 0.0);
  EXPECT_EQ(sa, sb);
  EXPECT_EQ(a[CS_THRESHOLD], b[CS_THRESHOLD]);
}

// reform_as force: the re-formed contact carries force k (r + carry) with
// the field included: k s' + h' = k target, h' = h + K (s' - s)
TEST(ContactModel, ReformAsForceBalancesTheField)
{
  const ContactModel m = model(true, true, spec(make_delta(0.0), "delta 0"));
  auto row = fresh_row(m, 8, 0.0);
  const double th = row[CS_THRESHOLD];
  const double s = 0.9, h = th + 0.02 - s, K = 0.3;    // k = 1: e = s + h = th + 0.02
  row[CS_STRETCH] = s;
  const double e = s + h;
  const double sn = m.break_once(row.data(), 8, e, h, K);
  const double hn = h + K * (sn - s);
  EXPECT_NEAR(1.0 * sn + hn, e - th, 1e-14);    // target = r + carry = 0 + (e - x_s)
  EXPECT_NEAR(row[CS_ANCHOR], s - sn, 1e-14);
}

// Avalanche rounds: a chain at stretches just below threshold, one
// contact pushed over.  Checked against a sequential cascade written here
// (one break at a time, lowest index first, field recomputed): with exact
// crossing and reform_as force every break lowers the stretch by
// k (r - x_s)/(k + K) whatever the state, so the set of breaks and the
// final state do not depend on the order (Abelian cascade).  Every round
// breaks exactly the contacts over their thresholds at its start, and
// none is over its threshold at the end.
TEST(Avalanche, SynchronousEqualsSequentialForExactCrossing)
{
  const int n = 24;
  const ContactModel m = model(true, true, spec(make_delta(0.0), "delta 0"));
  for (double g : {0.005, 0.3, 1.5}) {
    std::vector<std::vector<double>> a(n), b(n);
    for (int i = 0; i < n; ++i) {
      a[i] = fresh_row(m, 100 + i, 0.0);
      // stretch just below threshold, contact 7 over it
      const double th = a[i][CS_THRESHOLD];
      a[i][CS_STRETCH] = i == 7 ? th + 0.2 : th - 0.01 * (1 + i % 3);
      a[i][CS_ANCHOR] = -a[i][CS_STRETCH];
      b[i] = a[i];
    }
    std::vector<double *> ra, rb;
    for (int i = 0; i < n; ++i) ra.push_back(a[i].data()), rb.push_back(b[i].data());
    DenseField fa(chain_matrix(n, g), ra), fb(chain_matrix(n, g), rb);

    // contacts over their thresholds in the initial field: the first round
    long over = 0;
    for (int i = 0; i < n; ++i)
      if (!(std::fabs(a[i][CS_STRETCH] + fa.h[i]) < a[i][CS_THRESHOLD])) ++over;

    // engine
    std::vector<int> members(n), list;
    for (int i = 0; i < n; ++i) members[i] = i;
    std::vector<double> ds;
    const AvalancheResult res = avalanche(m, ra.data(), members.data(), n, 0.0, fa, list, ds);

    // sequential reference
    long seq = 0;
    for (int guard = 0; guard < 100000; ++guard) {
      int who = -1;
      for (int i = 0; i < n && who < 0; ++i) {
        const double e = b[i][CS_STRETCH] + fb.h[i] / b[i][CS_STIFFNESS];
        if (!(std::fabs(e) < b[i][CS_THRESHOLD])) who = i;
      }
      if (who < 0) break;
      const double e = b[who][CS_STRETCH] + fb.h[who] / b[who][CS_STIFFNESS];
      m.break_once(b[who].data(), 100 + who, e, fb.h[who], fb.K[who]);
      fb.recompute();
      ++seq;
    }
    EXPECT_EQ(res.size, seq) << g;
    EXPECT_EQ(res.local, seq) << g;
    EXPECT_GE(res.rounds, 1);
    EXPECT_EQ(res.trigger, over) << g;
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(a[i][CS_NBREAK], b[i][CS_NBREAK]) << g << " " << i;
      EXPECT_NEAR(a[i][CS_STRETCH], b[i][CS_STRETCH], 1e-12) << g << " " << i;
      const double e = a[i][CS_STRETCH] + fa.h[i] / a[i][CS_STIFFNESS];
      EXPECT_LT(std::fabs(e), a[i][CS_THRESHOLD]) << g << " " << i;
    }
    // weak coupling: only the pushed contact breaks; strong: the avalanche
    // runs through the chain over several rounds
    if (g == 0.005) {
      EXPECT_EQ(res.size, 1);
    }
    if (g == 1.5) {
      EXPECT_GT(res.rounds, 2);
    }
  }
}

// rounds are synchronous: two contacts over threshold at the start both
// break in round 1 (trigger 2), whatever their order
TEST(Avalanche, RoundsAreSynchronous)
{
  const ContactModel m = model(false, false, spec(make_delta(0.0), "delta 0"));
  const int n = 4;
  Rows c = rows_with(m, n, [](int i, double) { return (i == 1 || i == 2) ? 1.3 : 0.1; });
  auto &a = c.a;
  auto &ra = c.r;
  DenseField f(chain_matrix(n, 0.01), ra);
  std::vector<int> members{0, 1, 2, 3}, list;
  std::vector<double> ds;
  const AvalancheResult res = avalanche(m, ra.data(), members.data(), n, 0.0, f, list, ds);
  EXPECT_EQ(res.trigger, 2);
  EXPECT_EQ(res.size, 2);
  EXPECT_EQ(res.rounds, 1);
  EXPECT_EQ(f.nchanged, 1);
  // step crossing, reform_as stretch: both re-formed at exactly 0
  EXPECT_EQ(a[1][CS_STRETCH], 0.0);
  EXPECT_EQ(a[2][CS_STRETCH], 0.0);
}

// a field that names the rows whose h changed lets the later rounds test
// only those: the same breaks, in the same order, to the last bit, as
// testing every contact in every round; for the order-independent model
// (exact crossing, reform_as force) and for one whose cascade depends on
// the order of breaks (step crossing, reform_as stretch)
TEST(Avalanche, NamedChangesGiveTheSameAvalancheAsFullScans)
{
  const int n = 40;
  for (const bool exact : {true, false}) {
    const ContactModel m = model(exact, exact, spec(make_uniform(-0.3, 0.3), "uniform -0.3 0.3"));
    for (double g : {0.05, 0.3, 1.2}) {
      auto stretch = [](int i, double th) {
        return (i % 13 == 5) ? th + 0.1 : th * (0.55 + 0.4 * ((i * 7) % 10) / 10.0);
      };
      Rows ca = rows_with(m, n, stretch), cb = rows_with(m, n, stretch);
      auto &a = ca.a;
      auto &b = cb.a;
      auto &ra = ca.r;
      auto &rb = cb.r;
      DenseField full(chain_matrix(n, g), ra), named(chain_matrix(n, g), rb, true);
      std::vector<int> members(n), la, lb;
      for (int i = 0; i < n; ++i) members[i] = i;
      std::vector<double> da, db;
      const AvalancheResult ra_ = avalanche(m, ra.data(), members.data(), n, 0.0, full, la, da);
      const AvalancheResult rb_ = avalanche(m, rb.data(), members.data(), n, 0.0, named, lb, db);
      EXPECT_EQ(ra_.size, rb_.size) << exact << " " << g;
      EXPECT_EQ(ra_.rounds, rb_.rounds) << exact << " " << g;
      EXPECT_EQ(ra_.trigger, rb_.trigger) << exact << " " << g;
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < CS_NCOL; ++c) EXPECT_EQ(a[i][c], b[i][c]) << exact << g << i << c;
      if (g == 1.2) {
        EXPECT_GT(ra_.rounds, 2) << exact;    // a cascade, not one round
      }
    }
  }
}

// after the first round, only the rows the field names are tested: a
// contact over its threshold that the field does not name stays (the
// contract pair eq/elastic keeps by naming every row whose h changed)
TEST(Avalanche, LaterRoundsTestOnlyTheNamedRows)
{
  class Unnamed : public DenseField {
   public:
    using DenseField::DenseField;
    AvalancheField changed(const int *list, int n, const double *ds, bool exact) override
    {
      DenseField::changed(list, n, ds, exact);
      names.clear();
      return view(true);    // names none
    }
  };
  const ContactModel m = model(true, true, spec(make_delta(0.0), "delta 0"));
  const int n = 3;
  auto stretch = [](int i, double th) { return th * (i == 0 ? 1.3 : 0.99); };
  Rows ca = rows_with(m, n, stretch), cb = rows_with(m, n, stretch);
  auto &ra = ca.r;
  auto &rb = cb.r;
  Unnamed f(chain_matrix(n, 0.5), ra);
  DenseField full(chain_matrix(n, 0.5), rb);
  std::vector<int> members{0, 1, 2}, list;
  std::vector<double> ds;
  const AvalancheResult res = avalanche(m, ra.data(), members.data(), n, 0.0, f, list, ds);
  const AvalancheResult ref = avalanche(m, rb.data(), members.data(), n, 0.0, full, list, ds);
  EXPECT_EQ(res.size, 1);
  EXPECT_EQ(res.rounds, 1);
  // tested anew, contacts over their thresholds after the first break
  // break in later rounds
  EXPECT_GT(ref.size, 1);
  EXPECT_GT(ref.rounds, 1);
}

// on one rank of several: rounds in which only other ranks break (the
// global count is positive, this rank's list empty) go on without touching
// this rank's contacts; its scratch keeps no index of an earlier call
TEST(Avalanche, RoundsWithBreaksOnOtherRanksOnly)
{
  class OtherRanks : public DenseField {
   public:
    using DenseField::DenseField;
    void global_sum(long *v, int) override { v[0] += calls++ < 2 ? 3 : 0; }
    int calls = 0;
  };
  const ContactModel m = model(true, true, spec(make_delta(0.0), "delta 0"));
  const int n = 4;
  Rows c = rows_with(m, n, [](int, double) { return 0.1; });
  auto &a = c.a;
  auto &ra = c.r;
  OtherRanks f(chain_matrix(n, 0.01), ra);
  std::vector<int> members{0, 1, 2, 3}, list(64, 5000);    // stale entries of an earlier use
  list.clear();
  std::vector<double> ds;
  const AvalancheResult res = avalanche(m, ra.data(), members.data(), n, 0.0, f, list, ds);
  EXPECT_EQ(res.rounds, 2);
  EXPECT_EQ(res.size, 6);
  EXPECT_EQ(res.local, 0);
  EXPECT_EQ(f.nchanged, 2);    // the field follows every round (collective)
  EXPECT_LE(ds.size(), static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) EXPECT_EQ(a[i][CS_NBREAK], 0.0);
}

// a change far larger than the stretch it leads to (a stretch of 1e12
// re-formed at 0) is flagged, so that the field recomputes instead of
// following it (1e12 x 1e-16 of rounding in every partner); ordinary
// breaks are not
TEST(Avalanche, ChangesTooLargeToFollowAreFlagged)
{
  // step crossing, reform_as stretch: the contact re-forms at exactly 0
  const ContactModel m = model(false, false, spec(make_delta(0.0), "delta 0"));
  const int n = 3;
  for (const double s0 : {1.3, 1.0e12}) {
    Rows c = rows_with(m, n, [s0](int i, double) { return i == 1 ? s0 : 0.1; });
    auto &ra = c.r;
    DenseField f(chain_matrix(n, 0.01), ra);
    std::vector<int> members{0, 1, 2}, list;
    std::vector<double> ds;
    avalanche(m, ra.data(), members.data(), n, 0.0, f, list, ds);
    ASSERT_GE(f.nchanged, 1);
    EXPECT_EQ(f.last_exact, s0 < 10.0) << s0;
  }
}

// reform none: the field is rebuilt without the detached contacts
TEST(Avalanche, DetachedContactsLeaveTheField)
{
  const ContactModel m = model(true, true, none());
  const int n = 3;
  Rows c = rows_with(m, n, [](int i, double) { return i == 0 ? 2.0 : 0.1; });
  auto &ra = c.r;
  DenseField f(chain_matrix(n, 0.01), ra);
  std::vector<int> members{0, 1, 2}, list;
  std::vector<double> ds;
  const AvalancheResult res = avalanche(m, ra.data(), members.data(), n, 0.0, f, list, ds);
  EXPECT_EQ(res.size, 1);
  EXPECT_EQ(f.ndetached, 1);
  EXPECT_EQ(f.K[0], 0.0);
  EXPECT_NEAR(f.K[1], 0.01, 1e-15);    // only contact 2 left as its partner
}

// reform_as stretch with a coupling far above k: a re-formed contact
// carries its partners' force past its threshold again, without end
TEST(Avalanche, RunawayIsAnError)
{
  const ContactModel m = model(true, false, spec(make_delta(0.0), "delta 0"));
  const int n = 2;
  Rows c = rows_with(m, n, [](int i, double) { return i == 0 ? 1.3 : -1.3; });
  auto &ra = c.r;
  DenseField f(chain_matrix(n, 50.0), ra);
  std::vector<int> members{0, 1}, list;
  std::vector<double> ds;
  EXPECT_THROW(avalanche(m, ra.data(), members.data(), n, 0.0, f, list, ds), BreakError);
}

// the rounds of a model without temperature or aging at tol = 0 take a
// test of their own (without the general one's loads and branches): the
// same avalanche, to the last bit, as the general test, reached here with
// a tolerance of 1e-300 (below the rounding of any threshold here, so
// that x_s - tol = x_s), for contacts at and within 1e-17 of their
// thresholds, both signs, every round testing every contact or the named
// ones
TEST(Avalanche, ThePlainTestIsTheGeneralOne)
{
  const int n = 30;
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long breaks = 0;
  for (const bool exact : {true, false}) {
    const ContactModel m = model(exact, exact, spec(make_uniform(-0.3, 0.3), "uniform -0.3 0.3"));
    for (int trial = 0; trial < 60; ++trial) {
      // (g = 0: h = 0, and the contacts at gap 0 exactly at |e| = x_s)
      const double g = trial % 10 == 9 ? 0.0 : std::pow(10.0, -3.0 + 3.0 * u(rng));
      const bool named = trial % 2 == 0;
      std::vector<double> gap(n);
      for (int i = 0; i < n; ++i)
        gap[i] = i % 7 == 3 ? -0.05 : (i % 5 == 0 ? 0.0 : std::pow(10.0, -17.0 + 10.0 * u(rng)));
      auto stretch = [&gap](int i, double th) { return th * (1.0 - gap[i]) * (i % 2 ? 1.0 : -1.0); };
      Rows ca = rows_with(m, n, stretch), cb = rows_with(m, n, stretch);
      DenseField fa(chain_matrix(n, g), ca.r, named), fb(chain_matrix(n, g), cb.r, named);
      std::vector<int> members(n);
      for (int i = 0; i < n; ++i) members[i] = i;
      std::vector<int> la, lb;
      std::vector<double> da, db;
      const AvalancheResult plain = avalanche(m, ca.r.data(), members.data(), n, 0.0, fa, la, da);
      const AvalancheResult general =
          avalanche(m, cb.r.data(), members.data(), n, 1.0e-300, fb, lb, db);
      EXPECT_EQ(plain.size, general.size) << exact << " " << trial;
      EXPECT_EQ(plain.rounds, general.rounds) << exact << " " << trial;
      breaks += plain.size;
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < CS_NCOL; ++c)
          EXPECT_EQ(ca.a[i][c], cb.a[i][c]) << exact << " " << trial << " " << i << " " << c;
    }
  }
  EXPECT_GT(breaks, 2 * 60 * 4);
}

/* ----------------------------------------------------------------------
   thermal breaking by thinning (ContactModel::advance()): the law of the
   break times and stretches against the analytic survival exp(-int nu dt)
   (Kolmogorov-Smirnov over many contacts, fixed draws), for steps small
   and large (exact in law for any dt), barrier forms and aging; and the
   rate bound it rests on
------------------------------------------------------------------------- */

namespace {

ContactModel thermal_model(const ThermalSpec &t, bool exact,
                           DistributionSpec threshold = spec(make_delta(1.0), "delta 1"),
                           uint64_t seed = 4711)
{
  return ContactModel(1.0, seed, std::move(threshold), spec(make_delta(0.0), "delta 0"),
                      DistributionSpec{}, exact, true, false, t);
}

ThermalSpec theta_spec(double theta, double p = 0.0, double q = 0.0)
{
  ThermalSpec t;
  t.theta = theta;
  t.p = p;
  t.q = q;
  return t;
}

// sup |F_n - F| of the sample against the distribution function F
template <class F> double ks_distance(std::vector<double> x, F cdf)
{
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double c = cdf(x[i]);
    d = std::max(d, std::max(std::fabs(c - i / n), std::fabs((i + 1) / n - c)));
  }
  return d;
}

// the KS bound at level 1e-3 (Kolmogorov: P(sqrt(n) D > 1.95) = 0.001)
double ks_bound(size_t n)
{
  return 1.95 / std::sqrt(static_cast<double>(n));
}

}    // namespace

// the bound of the rate holds at every stretch within it and every
// threshold above its own, for all barrier forms, and is attained (to its
// margin) where the rate is largest
TEST(Thinning, RateBoundHoldsAndIsTight)
{
  for (const double p : {0.0, 2.0})
    for (const double q : {0.0, 0.25, 1.0}) {
      ThermalSpec t = theta_spec(0.02, p, q);
      t.omega = 3.0;
      const ThermalModel m(t);
      for (const double xs : {0.6, 1.0, 1.3})
        for (const double s : {0.0, 0.2, 0.7, 0.95, 0.999, 1.0, 1.2, 1e308}) {
          const double bound = m.rate_bound(s * xs, xs);
          double top = 0.0;
          for (int i = 0; i <= 4000; ++i) {
            const double x = std::min(s, 1.5) * xs * i / 4000.0;
            for (const double up : {1.0, 1.0001, 1.1})
              if (x <= s * xs) {
                const double nu = m.rate(x, xs * up);
                ASSERT_LE(nu, bound) << p << " " << q << " " << xs << " " << s << " " << x;
                top = std::max(top, nu);
              }
          }
          EXPECT_GE(top, bound * (1.0 - 1e-3)) << p << " " << q << " " << xs << " " << s;
        }
    }
}

// held contacts (crossing exact) break after times Exp(nu), for steps
// much smaller and much larger than 1/nu; with crossing step at the end
// of the step in which the break happened (geometric in steps)
TEST(Thinning, HeldContactsBreakAfterExponentialTimes)
{
  for (const auto &form : {std::make_pair(0.0, 0.0), std::make_pair(2.0, 0.25)})
    for (const double dt : {0.01, 0.37, 3.0, 40.0})
      for (const bool exact : {true, false}) {
        const ContactModel m = thermal_model(theta_spec(0.1, form.first, form.second), exact);
        const double x = 0.6, nu = m.thermal_model().rate(x, 1.0);
        std::vector<double> times;
        for (uint64_t tag = 1; tag <= 4000; ++tag) {
          std::vector<double> r(m.columns(), 0.0);
          m.form(r.data(), tag, 0.0);
          r[CS_STRETCH] = x;
          long nb = 0;
          int k = 0;
          while (nb == 0) {
            m.advance(r.data(), tag, x, dt, nb);
            ++k;
          }
          times.push_back(k * dt - r[CT_AGE]);
        }
        double d = 0.0;
        if (exact) {
          d = ks_distance(times, [&](double t) { return -std::expm1(-nu * t); });
        } else {    // whole steps: P(K <= k) = 1 - e^{-nu dt k}, compared at each k
          std::vector<double> count;
          for (const double t : times) {
            const size_t k = static_cast<size_t>(std::lround(t / dt));
            ASSERT_NEAR(t, k * dt, 1e-9 * t) << "at the end of a step";
            if (count.size() <= k) count.resize(k + 1, 0.0);
            count[k] += 1.0;
          }
          double cum = 0.0;
          for (size_t k = 0; k < count.size(); ++k) {
            cum += count[k] / times.size();
            d = std::max(d, std::fabs(cum + std::expm1(-nu * dt * k)));
          }
        }
        // (crossing step: the law is discrete, the KS bound conservative)
        EXPECT_LT(d, ks_bound(times.size())) << dt << " " << exact << " q " << form.second;
      }
}

// contacts loaded at constant velocity from stretch 0 break at stretch x
// with P(X > x) = exp(-(1/v) int_0^x nu), or at their threshold (an atom
// of that weight); with crossing exact the break is placed within the
// step, and the law holds for any step (thinning is exact in law)
TEST(Thinning, LoadedContactsBreakWithTheAnalyticSurvival)
{
  struct Case {
    double theta, p, q, beta, dX;
  };
  const double v = 1e-3;
  for (const Case c : {Case{0.05, 0, 0, 0, 0.02}, Case{0.05, 0, 0, 0, 0.3},
                       Case{0.02, 2, 0.25, 0, 0.05}, Case{0.05, 0, 0, 0.05, 0.01},
                       Case{0.05, 0, 0.25, 0.05, 0.4}}) {
    ThermalSpec t = theta_spec(c.theta, c.p, c.q);
    if (c.beta > 0.0) {
      t.aging = AgingLaw::LOG;
      t.beta = c.beta;
      t.tau_a = 1.0;
    }
    const ContactModel m = thermal_model(t, true);
    const ThermalModel &th = m.thermal_model();
    // the threshold at stretch x (age x / v) and the cumulative hazard
    // on a fine grid up to the stretch x* where x = x_s(x / v)
    auto xs_at = [&](double x) { return th.factor(x / v); };
    const int n = 200000;
    double xstar = 1.0;
    while (xstar < xs_at(xstar)) xstar = xs_at(xstar);    // fixed point (A grows slowly)
    std::vector<double> H(n + 1, 0.0);
    for (int j = 0; j < n; ++j) {
      const double a = xstar * j / n, b = xstar * (j + 1) / n, mid = 0.5 * (a + b);
      const double nu = th.rate(a, xs_at(a)) + 4.0 * th.rate(mid, xs_at(mid)) + th.rate(b, xs_at(b));
      H[j + 1] = H[j] + nu * (b - a) / 6.0 / v;
    }
    auto cdf = [&](double x) {
      const double jf = std::min(x / xstar * n, double(n));
      const int j = std::min(static_cast<int>(jf), n - 1);
      return -std::expm1(-(H[j] + (jf - j) * (H[j + 1] - H[j])));
    };
    const double dt = c.dX / v;
    std::vector<double> breaks;
    int at_threshold = 0;
    const int ncontacts = 4000;
    for (uint64_t tag = 1; tag <= static_cast<uint64_t>(ncontacts); ++tag) {
      std::vector<double> r(m.columns(), 0.0);
      m.form(r.data(), tag, 0.0);
      long nb = 0;
      double x = 0.0;
      while (nb == 0) {
        x += c.dX;
        const ThermalStepResult res = m.advance(r.data(), tag, x - r[CS_ANCHOR], dt, nb);
        if (res.renewed) r[CS_ANCHOR] = x - res.stretch;
      }
      const double xb = x - v * r[CT_AGE];
      ASSERT_GT(xb, x - c.dX - 1e-9) << tag;    // within the step
      ASSERT_LE(xb, x + 1e-9) << tag;
      if (xb >= xstar * (1.0 - 1e-9)) ++at_threshold;
      breaks.push_back(std::min(xb, xstar));
    }
    // the atom at x*: KS over the whole law (a jump of F at x*)
    const double d = ks_distance(breaks, [&](double x) { return x >= xstar * (1.0 - 1e-9) ? 1.0 : cdf(x); });
    const double p_atom = std::exp(-H[n]);
    EXPECT_LT(d, ks_bound(breaks.size())) << c.theta << " " << c.q << " " << c.beta << " " << c.dX;
    EXPECT_LT(std::fabs(at_threshold - ncontacts * p_atom),
              4.0 * std::sqrt(ncontacts * p_atom * (1.0 - p_atom)) + 1.0)
        << c.theta << " " << c.q << " " << c.beta << " " << c.dX;
  }
}

// the thinning's work in the bench scene (bench_thermal.py: theta 0.02,
// uniform thresholds, v = 1, dt = 0.01): candidates and refreshes of the
// bound per life
TEST(Thinning, FewCandidatesAndRefreshesPerLife)
{
  ThermalSpec barrier = theta_spec(0.02, 2.0, 0.25), all = theta_spec(0.02);
  all.aging = AgingLaw::LOG;
  all.beta = 0.05;
  all.delay = DelayKind::EXPONENTIAL;
  all.tau = 0.1;
  for (const ThermalSpec &t : {theta_spec(0.02), barrier, all}) {
    const ContactModel m =
        thermal_model(t, true, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
    const double v = 1.0, dt = 0.01;
    long nb = 0, steps = 0;
    for (uint64_t tag = 1; tag <= 2000; ++tag) {
      std::vector<double> r(m.columns(), 0.0);
      m.form(r.data(), tag, 0.0);
      for (int k = 1; k <= 1000; ++k, ++steps) {
        const double x = v * dt * k;
        const ThermalStepResult res = m.step(r.data(), tag, x - r[CS_ANCHOR], dt, nb);
        if (!res.attached && r[CS_THRESHOLD] > 0.0) r[CS_ANCHOR] = x;
        else if (res.renewed) r[CS_ANCHOR] = x - res.stretch;
      }
    }
    const ContactModel::SamplerCounts &c = m.sampler_counts();
    const double lives = static_cast<double>(nb);
    std::printf("p %g q %g aging %d: per life %.2f candidates, %.2f refreshes; %.1f steps per "
                "life\n", t.p, t.q, t.aging != AgingLaw::NONE, c.candidates / lives,
                c.refreshes / lives, steps / lives);
    EXPECT_LT(c.candidates / lives, 3.0);
    EXPECT_LT(c.refreshes / lives, 6.0);
  }
}

// the prefactor u^q (barrier 0 q): slow loading (v = 1e-3) of one
// threshold, where the band's level once fell below the stretch and the
// bound crept on (5e3 bounds per life at q = 0.5, 6e4 at q = 1, 8e4 at
// q = 2 and theta = 0.1): a few bounds and candidates per life, as q = 0
TEST(Thinning, PrefactorKeepsFewBoundsPerLife)
{
  for (const double q : {0.0, 0.5, 1.0, 2.0}) {
    const double theta = q == 2.0 ? 0.1 : 0.02;
    const ContactModel m = thermal_model(theta_spec(theta, 0.0, q), true,
                                         spec(make_delta(1.0), "delta 1.0"));
    const double v = 1e-3, dt = 0.1;
    long nb = 0;
    for (uint64_t tag = 1; tag <= 50; ++tag) {
      std::vector<double> r(m.columns(), 0.0);
      m.form(r.data(), tag, 0.0);
      for (int k = 1; k <= 20000; ++k) {
        const double x = v * dt * k;
        const ThermalStepResult res = m.step(r.data(), tag, x - r[CS_ANCHOR], dt, nb);
        if (!res.attached && r[CS_THRESHOLD] > 0.0) r[CS_ANCHOR] = x;
        else if (res.renewed) r[CS_ANCHOR] = x - res.stretch;
      }
    }
    const ContactModel::SamplerCounts &c = m.sampler_counts();
    const double lives = static_cast<double>(nb);
    std::printf("q %g theta %g: %.0f lives, per life %.2f candidates, %.2f bounds\n", q, theta,
                lives, c.candidates / lives, c.refreshes / lives);
    ASSERT_GT(lives, 50.0);
    EXPECT_LT(c.candidates / lives, 6.0) << "q " << q;
    EXPECT_LT(c.refreshes / lives, 12.0) << "q " << q;
  }
}

// the bound follows the contact's path and draws, not the steps: a
// contact loaded at constant velocity breaks at the same stretch (to
// rounding) whatever the step, with crossing exact
TEST(Thinning, BreaksDoNotDependOnTheStep)
{
  const ContactModel m = thermal_model(theta_spec(0.03, 2.0, 0.25), true,
                                       spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
  const double v = 1e-2;
  std::vector<std::vector<double>> at(3);
  const double steps[3] = {0.001, 0.013, 0.2};
  for (int k = 0; k < 3; ++k) {
    for (uint64_t tag = 1; tag <= 200; ++tag) {
      std::vector<double> r(m.columns(), 0.0);
      m.form(r.data(), tag, 0.0);
      long nb = 0;
      double x = 0.0;
      while (nb < 5) {    // five lives
        const long before = nb;
        x += steps[k];
        const ThermalStepResult res = m.step(r.data(), tag, x - r[CS_ANCHOR], steps[k] / v, nb);
        if (res.renewed) r[CS_ANCHOR] = x - res.stretch;
        if (nb > before) at[k].push_back(x - v * r[CT_AGE]);
      }
    }
  }
  ASSERT_EQ(at[0].size(), at[1].size());
  ASSERT_EQ(at[0].size(), at[2].size());
  for (size_t i = 0; i < at[0].size(); ++i) {
    EXPECT_NEAR(at[1][i], at[0][i], 1e-9 * (1.0 + at[0][i])) << i;
    EXPECT_NEAR(at[2][i], at[0][i], 1e-9 * (1.0 + at[0][i])) << i;
  }
}

// a new run with the parameters that made the rows changes nothing (a
// restart, or run after run, continues to the bit), and a row copied
// midway (an atom that migrates, a restart) goes on as the original
TEST(Thinning, NewRunAndCopiesContinueToTheBit)
{
  ThermalSpec t = theta_spec(0.05, 2.0, 0.25);
  t.aging = AgingLaw::LOG;
  t.beta = 0.05;
  const ContactModel m = thermal_model(t, true, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
  for (uint64_t tag = 1; tag <= 50; ++tag) {
    std::vector<double> a(m.columns(), 0.0);
    m.form(a.data(), tag, 0.0);
    long na = 0, nb = 0;
    std::vector<double> b;
    for (int k = 1; k <= 3000; ++k) {
      const double x = 0.004 * k + 0.2 * std::sin(0.01 * k);
      if (k == 1500) {
        b = a;
        const std::vector<double> before = a;
        m.new_run(a.data());
        ASSERT_EQ(0, std::memcmp(a.data(), before.data(), a.size() * sizeof(double))) << tag;
      }
      for (std::vector<double> *r : {&a, &b}) {
        if (r->empty()) continue;
        const ThermalStepResult res = m.step(r->data(), tag, x - (*r)[CS_ANCHOR], 0.5, r == &a ? na : nb);
        if (!res.attached && (*r)[CS_THRESHOLD] > 0.0) (*r)[CS_ANCHOR] = x;
        else if (res.renewed) (*r)[CS_ANCHOR] = x - res.stretch;
      }
    }
    ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double))) << tag;
    EXPECT_GT(na, 3);
  }
}

// another temperature in a new run (a restart with other settings): the
// bound is made anew, valid for it
TEST(Thinning, NewRunWithOtherParametersRemakesTheBound)
{
  const ContactModel cold = thermal_model(theta_spec(0.01), true);
  const ContactModel hot = thermal_model(theta_spec(0.1), true);
  std::vector<double> r(cold.columns(), 0.0);
  cold.form(r.data(), 7, 0.0);
  long nb = 0;
  for (int k = 1; k <= 10; ++k) cold.step(r.data(), 7, 0.05 * k, 0.1, nb);
  ASSERT_GE(r[CT_BOUND_S], 0.0);
  hot.new_run(r.data());
  EXPECT_EQ(r[CT_BOUND_RATE], hot.thermal_model().rate_bound(r[CT_BOUND_S], r[CT_XS_LOW]));
  EXPECT_GE(r[CT_BOUND_RATE], hot.thermal_model().rate(r[CS_STRETCH], r[CS_THRESHOLD]));
}

// the rise of a bound's log rate as level() computed it before the
// shortcut (ContactModel::bound_rise()): two logarithms
double bound_rise_formula(double k, double psi, double d)
{
  const double lk = std::log(k) - psi;
  double r = ContactModel::BOUND_LOG_STEP;
  if (lk > 1.0) r = std::max(r, lk - std::log(lk));
  return std::min(r, d - d / ContactModel::BOUND_LADDER);
}

// the bound's rise in log rate with the logs skipped where the ladder's
// cap decides equals the formula with them, to the bit, over decades of
// K and psi and at the edges (0, subnormal, infinite, NaN)
TEST(ContactModel, BoundRiseShortcutIsExact)
{
  auto same = [](double a, double b) {
    return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0;
  };
  std::vector<double> ks = {0.0, -1.0, 4.9e-324, 1e-310, HUGE_VAL, NAN, 1.0, 2.0};
  for (int e = -300; e <= 300; e += 7)
    for (double m : {1.0, 1.2345, 1.5, 1.9999999})
      ks.push_back(m * std::ldexp(1.0, e));
  std::vector<double> psis = {-HUGE_VAL, NAN};
  for (double p = -800.0; p <= 3.0; p += 0.37) psis.push_back(p);
  const double ln_omega = 2.5;
  long shortcut_cases = 0, n = 0;
  for (double k : ks)
    for (double psi : psis) {
      const double d = ln_omega - psi;
      if (!(d > 0.5 * ContactModel::BOUND_LOG_STEP) && !std::isnan(d)) continue;
      const double want = bound_rise_formula(k, psi, d);
      const double got = ContactModel::bound_rise(k, psi, d);
      ++n;
      if (same(got, d - d / ContactModel::BOUND_LADDER)) ++shortcut_cases;
      ASSERT_TRUE(same(got, want)) << "K = " << k << ", psi = " << psi << ": " << got << " vs "
                                   << want;
    }
  // the cap decides in most of this sweep (the case the shortcut serves)
  EXPECT_GT(shortcut_cases, n / 2);
}

// at T > 0 the common step (quick_attached<true>()) takes no contact that
// is not attached, without testing the threshold or the delay: a contact
// not formed, departed from the group, detached for good or waiting has
// no bound, and a new run clears a bound such a row still carries
TEST(Thinning, NoBoundForAContactNotAttached)
{
  ThermalSpec t = theta_spec(0.05);
  t.delay = DelayKind::FIXED;
  t.tau = 0.5;
  const ContactModel waits = thermal_model(t, true);
  const ContactModel once(1.0, 4711, spec(make_delta(1.0), "delta 1"), none(), DistributionSpec{},
                          true, true, false, theta_spec(0.05));
  const double dt = 0.01;
  auto quick = [&](const ContactModel &m, std::vector<double> r, double s) {
    return m.quick_attached<true>(r.data(), s, dt);
  };
  std::vector<double> fresh(waits.columns(), 0.0);
  EXPECT_FALSE(quick(waits, fresh, 0.0));    // not formed (a zeroed row)
  for (const ContactModel *m : {&waits, &once}) {
    std::vector<double> r(m->columns(), 0.0);
    m->form(r.data(), 9, 0.0);
    long nb = 0;
    double x = 0.0;
    for (int k = 0; k < 40; ++k) m->step(r.data(), 9, (x += 0.01) - r[CS_ANCHOR], dt, nb);
    ASSERT_GE(r[CT_BOUND_S], 0.0);
    ASSERT_TRUE(quick(*m, r, r[CS_STRETCH]));    // attached, within its bound
    std::vector<double> gone = r;
    m->depart(gone.data());
    EXPECT_FALSE(quick(*m, gone, 0.0));
    while (nb == 0) m->step(r.data(), 9, (x += 0.05) - r[CS_ANCHOR], dt, nb);
    if (m == &waits) ASSERT_GT(r[CT_WAIT], 0.0);
    else ASSERT_LT(r[CS_THRESHOLD], 0.0);
    for (double s : {0.0, 1e-3, -1e-3}) EXPECT_FALSE(quick(*m, r, s));
    // a row whose bound survived (written otherwise): a new run drops it
    r[CT_BOUND_S] = 0.5;
    r[CT_XS_LOW] = 1.0;
    m->new_run(r.data());
    EXPECT_LT(r[CT_BOUND_S], 0.0);
    EXPECT_FALSE(quick(*m, r, 0.0));
  }
}

// the shortcut at its edge: K an exact power of 2 and lk just below a
// power of 2 make both of its inequalities tight; caps at the largest
// value where it would fire without its margin, and at the largest where
// it fires with it, a few ulps either side.  There the margin (far above
// the logs' rounding) keeps the result the formula's to the bit: without
// it, the rounded e ln 2 and logs put the formula below the cap the
// shortcut returns (about 1 case in 1000 here)
TEST(ContactModel, BoundRiseShortcutAtItsEdge)
{
  const double ln2 = 0.69314718055994530942;
  auto cap_of = [](double d) { return d - d / ContactModel::BOUND_LADDER; };
  // the largest d whose cap is at most c
  auto d_at = [&](double c) {
    double d = c / (1.0 - 1.0 / ContactModel::BOUND_LADDER);
    while (cap_of(d) > c) d = std::nextafter(d, 0.0);
    while (cap_of(std::nextafter(d, HUGE_VAL)) <= c) d = std::nextafter(d, HUGE_VAL);
    return d;
  };
  long n = 0;
  for (int e = -60; e <= 60; ++e)
    for (int m = 2; m <= 40; ++m)
      for (double below : {0.0, 4e-16, 1e-15, 1e-14, 1e-12}) {
        const double k = std::ldexp(1.0, e);
        const double psi = e * ln2 - std::ldexp(1.0 - below, m);
        const double y = e * ln2 - psi;
        if (!(y > 2.0)) continue;
        const double bound = y - (std::ilogb(y) + 1) * ln2;
        const double edge = (bound - 1e-9) / (1.0 + 1e-9);    // about where the margin lets it fire
        for (double c : {bound, edge})
          for (int u = -3; u <= 3; ++u) {
            double d = d_at(c);
            for (int t = 0; t < std::abs(u); ++t) d = std::nextafter(d, u < 0 ? 0.0 : HUGE_VAL);
            if (!(cap_of(d) > ContactModel::BOUND_LOG_STEP)) continue;
            const double want = bound_rise_formula(k, psi, d);
            const double got = ContactModel::bound_rise(k, psi, d);
            ++n;
            ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0)
                << "K = 2^" << e << ", psi = " << psi << ", d = " << d << ": " << got << " vs "
                << want;
          }
      }
  EXPECT_GT(n, 100000);
}

// interacting contacts at T > 0: probe() samples the same thermal break as
// advance() (the same draws, up to the aged threshold), and break_once()
// at the effective stretch where it broke re-forms the contact as
// advance() does: on that side (also where e changes sign within the
// step), the motion after the break carried (crossing exact), the new
// life of age (1 - f) dt; with crossing step at the end of the step, age
// 0.  advance() samples the new life over the rest of the step too: the
// contacts whose new life breaks again in that rest are left out
TEST(Thinning, ProbeAndBreakOnceEqualAdvance)
{
  ThermalSpec t = theta_spec(0.3, 2.0, 0.25);
  t.aging = AgingLaw::LOG;
  t.beta = 0.05;
  t.tau_a = 1.0;
  for (const bool exact : {true, false}) {
    const ContactModel m(1.0, 4711, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"),
                         spec(make_uniform(-0.3, 0.3), "uniform -0.3 0.3"), DistributionSpec{},
                         exact, true, false, t);
    int broke = 0, held = 0, across = 0;
    for (uint64_t tag = 1; tag <= 10000; ++tag) {
      std::vector<double> a(m.columns(), 0.0);
      m.form(a.data(), tag, 0.0);
      // from -0.6 ... 0.6, moving up or down by 0.8 or less
      const double e0 = -0.6 + 1.2 * (tag % 13) / 12.0, dt = 0.5 + (tag % 5);
      const double e1 = e0 + (tag % 2 ? 0.8 : -0.8) * (tag % 3) / 2.0;
      a[CS_STRETCH] = e0;
      a[CT_AGE] = 2.0;
      std::vector<double> b = a;
      long nb = 0;
      const ThermalStepResult r = m.advance(a.data(), tag, e1, dt, nb);
      const ContactModel::ThermalProbe p = m.probe(b.data(), tag, e0, e1, dt);
      if (nb == 0) {    // held: both aged by dt, the same sampler state
        ASSERT_FALSE(p.broke) << tag;
        EXPECT_EQ(b[CT_AGE], a[CT_AGE]) << tag;
        EXPECT_EQ(b[CT_BUDGET], a[CT_BUDGET]) << tag;
        EXPECT_EQ(b[CT_CANDIDATE], a[CT_CANDIDATE]) << tag;
        EXPECT_EQ(b[CS_STRETCH], e0) << tag;    // the stretch is the caller's
        ++held;
        continue;
      }
      // no thermal break: advance() broke at the aged threshold
      const double xs_end = b[CS_THRESHOLD] * m.thermal_model().factor(2.0 + dt);
      if (!p.broke) {
        EXPECT_GE(std::fabs(e1), xs_end * (1.0 - 1e-12)) << tag;
        continue;
      }
      if (nb > 1) continue;    // its new life broke again within the step
      ASSERT_GT(p.frac, 0.0);
      ASSERT_LT(p.frac, 1.0);
      const double eb = e0 + (e1 - e0) * p.frac;
      const double s = m.break_once(b.data(), tag, e1, 0.0, 0.0, eb, (1.0 - p.frac) * dt);
      EXPECT_NEAR(s, r.stretch, 1e-12) << tag;
      EXPECT_EQ(b[CS_THRESHOLD], a[CS_THRESHOLD]) << tag;
      EXPECT_EQ(b[CS_NBREAK], a[CS_NBREAK]) << tag;
      EXPECT_NEAR(b[CT_AGE], a[CT_AGE], 1e-12 * dt) << tag;
      if (!exact) EXPECT_EQ(b[CT_AGE], 0.0) << tag;
      EXPECT_EQ(b[CT_XS_LOW], b[CS_THRESHOLD]) << tag;    // a new life
      ++broke;
      if ((eb < 0.0) != (e1 < 0.0)) ++across;
    }
    // (enough of each case to compare)
    EXPECT_GT(broke, 500) << exact;
    EXPECT_GT(held, 500) << exact;
    EXPECT_GT(across, 50) << exact;
  }
}

// probe()'s inline common case, where it applies (a second step, once a
// first one made the rate bound), is probe() to the bit; on the row in
// stored form (from the first probe's end, at dt) stored_quick_probe()
// decides the same (to rounding) and writes nothing
TEST(Thinning, QuickProbeIsProbe)
{
  ThermalSpec t = theta_spec(0.1, 2.0, 0.25);
  t.aging = AgingLaw::LOG;
  t.beta = 0.05;
  t.tau_a = 1.0;
  const ContactModel m =
      thermal_model(t, true, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
  int quick = 0, slow = 0;
  for (uint64_t tag = 1; tag <= 4000; ++tag) {
    std::vector<double> a(m.columns(), 0.0);
    m.form(a.data(), tag, 0.0);
    const double e0 = -0.7 + 1.4 * (tag % 11) / 10.0, dt = 0.2 + (tag % 3);
    if (m.probe(a.data(), tag, 0.0, e0, dt).broke) continue;
    const double e1 = e0 + 0.01 * dt * (tag % 2 ? 1.0 : -1.0);
    std::vector<double> b = a, c = a, d = a;
    from_engine(d.data(), dt);
    const std::vector<double> stored = d;
    const ContactModel::ThermalProbe p = m.probe(b.data(), tag, e0, e1, dt);
    const bool q = m.quick_probe<true>(c.data(), e0, e1, dt);
    EXPECT_EQ(q, ContactModel::stored_quick_probe<true>(d.data(), e0, e1, 2.0 * dt)) << tag;
    EXPECT_EQ(d, stored) << tag;    // untouched
    if (q) {
      ASSERT_FALSE(p.broke) << tag;
      EXPECT_EQ(c, b) << tag;
      const StoredForm now = to_engine(d.data(), 2.0 * dt);
      EXPECT_NEAR(now.age, c[CT_AGE], 1e-12) << tag;
      EXPECT_NEAR(now.budget, c[CT_BUDGET], 1e-12) << tag;
      ++quick;
    } else {
      EXPECT_EQ(c, a) << tag;    // untouched
      ++slow;
    }
  }
  EXPECT_GT(quick, 1000);
  EXPECT_GT(slow, 100);
}

// the threshold the avalanche tests is the aged one; break_once() at it
// carries e - x_s0 A(age) and starts a life of age 0; a delay is refused
TEST(Thinning, BreakOnceAtTheAgedThreshold)
{
  ThermalSpec t;
  t.aging = AgingLaw::LOG;
  t.beta = 0.1;
  t.tau_a = 1.0;
  const ContactModel m =
      thermal_model(t, true, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
  std::vector<double> a(m.columns(), 0.0);
  m.form(a.data(), 5, 0.0);
  a[CT_AGE] = 100.0;
  const double xs = a[CS_THRESHOLD] * (1.0 + 0.1 * std::log1p(100.0));
  EXPECT_DOUBLE_EQ(m.threshold_now(a.data()), xs);
  a[CS_STRETCH] = xs + 0.01;
  const double s = m.break_once(a.data(), 5, xs + 0.01, 0.0, 0.0);
  EXPECT_NEAR(s, 0.01, 1e-14);    // reform delta 0 plus the overshoot
  EXPECT_EQ(a[CT_AGE], 0.0);
  EXPECT_EQ(m.threshold_now(a.data()), a[CS_THRESHOLD]);
  t.delay = DelayKind::EXPONENTIAL;
  t.tau = 3.0;
  const ContactModel d =
      thermal_model(t, true, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
  std::vector<double> b(d.columns(), 0.0);
  d.form(b.data(), 5, 0.0);
  // with a delay it leaves the field (DelayedBreakOnceAndRejoinAreAdvance)
  EXPECT_EQ(d.break_once(b.data(), 5, 2.0, 0.0, 0.0), 0.0);
  EXPECT_TRUE(d.waiting(b.data()));
}

// A life's hazard budget is the Exp(1) of the second half of the Philox
// block that draws its threshold: at formation (event 0), at a re-entry
// into the group (the re-entry streams) and after a break (advance();
// with crossing step the new life starts at the step's end and has used
// none of it).  At T = 0 with aging the budget is drawn alike (a restart
// at T > 0 finds it); an athermal row is written only within its width
TEST(Thinning, BudgetComesWithTheThreshold)
{
  ThermalSpec aged = theta_spec(0.0);
  aged.aging = AgingLaw::LOG;
  aged.beta = 0.05;
  aged.tau_a = 1.0;
  for (const ThermalSpec &t : {theta_spec(0.05), aged}) {
    const ContactModel m =
        thermal_model(t, false, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
    std::vector<double> r(m.columns(), 0.0);
    m.form(r.data(), 17, 0.0);
    EXPECT_EQ(r[CT_BUDGET], exponential(draw_pair(4711, 17, 0, STREAM_THRESHOLD).second));
    EXPECT_EQ(r[CS_THRESHOLD],
              make_uniform(0.75, 1.25)->sample_above(0.0, draw(4711, 17, 0, STREAM_THRESHOLD)));
    m.depart(r.data());
    m.form(r.data(), 17, 1.0);
    EXPECT_EQ(r[CT_BUDGET],
              exponential(draw_pair(4711, 17, 0, STREAM_THRESHOLD + STREAM_REENTRY).second));
    long nb = 0;
    m.step(r.data(), 17, 2.0, 1.0, nb);    // over any threshold: one break at the step's end
    ASSERT_EQ(nb, 1);
    const uint64_t event = static_cast<uint64_t>(r[CS_NBREAK]);
    EXPECT_EQ(event, 1u);
    EXPECT_EQ(r[CT_BUDGET], exponential(draw_pair(4711, 17, event, STREAM_THRESHOLD).second));
    EXPECT_NE(r[CT_BUDGET], exponential(draw(4711, 17, event, STREAM_BUDGET)));
  }
  const ContactModel cold = model(true, true, spec(make_delta(0.0), "delta 0"));
  ASSERT_EQ(cold.columns(), static_cast<int>(CS_NCOL));
  std::vector<double> guarded(CS_NCOL + 8, -7.0);
  cold.form(guarded.data(), 17, 0.0);
  long nb = 0;
  cold.resolve(guarded.data(), 17, 5.0, 0.0, nb);
  EXPECT_GE(nb, 4);
  for (int k = CS_NCOL; k < CS_NCOL + 8; ++k) EXPECT_EQ(guarded[k], -7.0) << k;
}

// formation delays with an interacting field (issue 23): a broken contact
// leaves the field and waits; break_once() gives it the wait and the
// re-forming stretch that advance() gives it (crossing step: both break
// at the end of the step), and rejoin() re-forms it as advance() does,
// at the instant its delay ends with crossing exact, the rest of the
// motion carried
TEST(Thinning, DelayedBreakOnceAndRejoinAreAdvance)
{
  for (const DelayKind kind : {DelayKind::FIXED, DelayKind::EXPONENTIAL}) {
    ThermalSpec t;
    t.delay = kind;
    t.tau = 2.0;
    for (const bool exact : {false, true}) {
      const ContactModel m(1.0, 4711, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"),
                           spec(make_uniform(0.1, 0.3), "uniform 0.1 0.3"), DistributionSpec{},
                           exact, true, false, t);
      ASSERT_TRUE(m.leaves_field());
      int rejoined = 0;
      for (uint64_t tag = 1; tag <= 200; ++tag) {
        std::vector<double> a(m.columns(), 0.0);
        m.form(a.data(), tag, 0.0);
        const double xs = a[CS_THRESHOLD];
        const double sign = tag % 2 ? 1.0 : -1.0;
        a[CS_STRETCH] = sign * 0.5 * xs;
        a[CS_ANCHOR] = 3.0;
        std::vector<double> b = a;
        // a step that carries the stretch past the threshold
        const double m1 = sign * (xs + 0.01), dt = 0.1;
        long nb = 0;
        m.advance(a.data(), tag, m1, dt, nb);
        ASSERT_EQ(nb, 1);
        ASSERT_TRUE(m.waiting(a.data()));
        EXPECT_EQ(m.break_once(b.data(), tag, m1, 0.0, 0.0), 0.0);
        ASSERT_TRUE(m.waiting(b.data()));
        EXPECT_EQ(b[CS_STRETCH], 0.0);
        EXPECT_EQ(b[CS_ANCHOR], 3.0 + 0.5 * sign * xs);    // at its atom
        EXPECT_EQ(b[CT_PENDING], a[CT_PENDING]) << tag;
        EXPECT_EQ(b[CS_THRESHOLD], a[CS_THRESHOLD]) << tag;
        EXPECT_EQ(b[CS_NBREAK], a[CS_NBREAK]) << tag;
        EXPECT_EQ(b[CT_PENDING] * sign > 0.0, true) << tag;    // on the side it broke
        // advance() waited the rest of the step after its crossing
        const double waited = exact ? b[CT_WAIT] - a[CT_WAIT] : 0.0;
        EXPECT_GE(waited, 0.0);
        EXPECT_LE(waited, dt * (1.0 + 1e-12));
        if (kind == DelayKind::FIXED) EXPECT_NEAR(b[CT_WAIT], 2.0, 1e-15);
        // the step in which the delay ends, motion 0.3: re-forms at the
        // same instant as advance(), with the same stretch at its end
        const double dt2 = 0.4, m2 = 0.3;
        a[CT_WAIT] = b[CT_WAIT] = 0.1 + 0.25 * (tag % 5) * dt2 / 4.0;
        std::vector<double> c = a;
        long nb2 = 0;
        const ThermalStepResult r = m.advance(a.data(), tag, m2, dt2, nb2);
        if (nb2 > 0) continue;    // broke again within the step: not compared
        ASSERT_TRUE(r.attached && r.renewed);
        const double s = m.rejoin(c.data(), m2, dt2);
        EXPECT_NEAR(s, r.stretch, 1e-15) << tag;
        EXPECT_NEAR(c[CT_AGE], a[CT_AGE], 1e-15) << tag;
        EXPECT_FALSE(m.waiting(c.data()));
        if (!exact) EXPECT_EQ(s, b[CT_PENDING]);    // re-formed at the end of the step
        ++rejoined;
      }
      EXPECT_GT(rejoined, 150);
    }
  }
}

// a model with formation delays (uniform thresholds, re-forming at 0),
// and three of its contacts in a chain (k_ij = 0.01), the first over its
// threshold: their rows and field after one avalanche
namespace {
ContactModel delay_model(DelayKind kind, double tau, uint64_t seed)
{
  ThermalSpec t;
  t.delay = kind;
  t.tau = tau;
  return ContactModel(1.0, seed, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"),
                      spec(make_delta(0.0), "delta 0"), DistributionSpec{}, true, true, false, t);
}
struct DelayChain {
  std::vector<std::vector<double>> a;
  std::unique_ptr<DenseField> f;
  AvalancheResult res;
  explicit DelayChain(const ContactModel &m) : a(3)
  {
    std::vector<double *> ra;
    for (int i = 0; i < 3; ++i) {
      a[i].assign(m.columns(), 0.0);
      m.form(a[i].data(), 100 + i, 0.0);
      a[i][CS_STRETCH] = i == 0 ? 2.0 : 0.1;
      ra.push_back(a[i].data());
    }
    f.reset(new DenseField(chain_matrix(3, 0.01), ra));
    f->thermal_rows = true;
    f->recompute();
    std::vector<int> members{0, 1, 2}, list;
    std::vector<double> ds;
    res = avalanche(m, f->rows.data(), members.data(), 3, 0.0, *f, list, ds);
  }
};
}    // namespace

// a break that does not leave the field although the model's breaks do
// (a wait that rounds to 0: the contact re-forms at once) is named as a
// change the field cannot follow as a leave (exact false: recompute);
// one that leaves is followable.  tau = the smallest denormal: tau Exp(1)
// rounds to 0 for draws below 1/2, to tau above
TEST(Avalanche, BreakThatDoesNotLeaveIsNotFollowable)
{
  int left = 0, stayed = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const ContactModel m =
        delay_model(DelayKind::EXPONENTIAL, std::numeric_limits<double>::denorm_min(), seed);
    ASSERT_TRUE(m.leaves_field());
    const DelayChain c(m);
    ASSERT_GE(c.f->ndetached, 1);
    const bool waits = m.waiting(c.a[0].data());
    EXPECT_EQ(c.f->last_exact, waits) << "seed " << seed;
    (waits ? left : stayed) += 1;
  }
  EXPECT_GT(left, 0);
  EXPECT_GT(stayed, 0);
}

// with delays every break leaves the field: the avalanche recomputes it
// without the waiting contact (detached()), which no round tests again
TEST(Avalanche, WaitingContactsLeaveTheField)
{
  const ContactModel m = delay_model(DelayKind::FIXED, 5.0, 4711);
  const DelayChain c(m);
  const DenseField &f = *c.f;
  EXPECT_EQ(c.res.size, 1);
  EXPECT_EQ(f.ndetached, 1);
  EXPECT_EQ(f.left, std::vector<int>{0});    // the leaver named
  EXPECT_TRUE(f.last_exact);
  EXPECT_EQ(f.nchanged, 0);
  EXPECT_TRUE(m.waiting(c.a[0].data()));
  EXPECT_EQ(c.a[0][CT_WAIT], 5.0);
  EXPECT_EQ(c.a[0][CS_STRETCH], 0.0);
  EXPECT_EQ(f.K[0], 0.0);
  EXPECT_NEAR(f.K[1], 0.01, 1e-15);    // only contact 2 left as its partner
  EXPECT_NEAR(f.h[1], 0.0, 1e-15);
}

/* ----------------------------------------------------------------------
   the stored form of a thermal row (to_engine(), from_engine(),
   stored_quick()): fix eq/contacts keeps the budget and the age as times
   on its clock, so that its common step writes neither.  Its contacts
   must live the lives of the engine form: the same breaks at the same
   steps, the same ages and budgets to rounding
------------------------------------------------------------------------- */

namespace {

// the specs the stored form is checked with: temperature with a barrier
// form, with log aging, with an exponential delay; aging alone at T = 0
std::vector<ThermalSpec> stored_specs()
{
  std::vector<ThermalSpec> v;
  v.push_back(theta_spec(0.05, 2.0, 0.25));
  ThermalSpec aged = theta_spec(0.05);
  aged.aging = AgingLaw::LOG;
  aged.beta = 0.1;
  aged.tau_a = 0.5;
  v.push_back(aged);
  ThermalSpec delayed = theta_spec(0.05);
  delayed.delay = DelayKind::EXPONENTIAL;
  delayed.tau = 3.0;
  v.push_back(delayed);
  ThermalSpec cold = theta_spec(0.0);
  cold.aging = AgingLaw::EXP;
  cold.beta = 0.3;
  cold.tau_a = 2.0;
  v.push_back(cold);
  // hot enough for the top bound (any stretch): rejected candidates leave
  // the bound and its rate as they were, with a new budget
  v.push_back(theta_spec(1.0));
  return v;
}

// a contact's anchor after a step that left it renewed or waiting (as fix
// eq/contacts' took_step()); the step of a stored row in engine form
void follow(std::vector<double> &r, const ThermalStepResult &res, double x)
{
  if (!res.attached && r[CS_THRESHOLD] > 0.0) r[CS_ANCHOR] = x;
  else if (res.renewed) r[CS_ANCHOR] = x - res.stretch;
}

}    // namespace

// the engine form (a, stepped as before the stored form), the stored
// form with the fix's common step (b), and the stored form sent through
// the engine at every third step or so whether or not the common step
// would do (c): a and b live the same lives, and c keeps b's stored row
// to the bit (its times do not depend on when it was converted)
TEST(StoredForm, ContactsLiveTheLivesOfTheEngineForm)
{
  for (const ThermalSpec &t : stored_specs()) {
    const ContactModel m(1.0, 4711, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"),
                         spec(make_uniform(-0.3, 0.3), "uniform -0.3 0.3"), DistributionSpec{},
                         true, true, false, t);
    const bool hot = t.thermal();
    const double dt = 0.05;
    long quick = 0, total = 0, breaks = 0;
    for (uint64_t tag = 1; tag <= 60; ++tag) {
      std::vector<double> a(m.columns(), 0.0);
      m.form(a.data(), tag, 0.0);
      std::vector<double> b = a;
      from_engine(b.data(), 0.0);
      std::vector<double> c = b;
      long na = 0, nb = 0, nc = 0;
      int top = 0;
      double clock = 0.0;
      for (int k = 1; k <= 4000; ++k) {
        // slow drift and a swing: stretches up and down, breaks both ways
        const double x = 0.002 * k + 0.4 * std::sin(0.003 * k * (1.0 + 0.1 * (tag % 7)));
        follow(a, m.step(a.data(), tag, x - a[CS_ANCHOR], dt, na), x);
        const double t_end = clock + dt;
        const double s = x - b[CS_ANCHOR];
        const bool attached = b[CS_THRESHOLD] > 0.0 && !(b[CT_WAIT] > 0.0);
        ++total;
        if (attached && (hot ? ContactModel::stored_quick<true>(b.data(), s, t_end)
                             : ContactModel::stored_quick<false>(b.data(), s, t_end))) {
          ++quick;
        } else {
          const StoredForm was = to_engine(b.data(), clock);
          follow(b, m.step(b.data(), tag, s, dt, nb), x);
          from_engine(b.data(), t_end, was);
        }
        if ((k * tag) % 3 == 0 || !(attached && (hot ? ContactModel::stored_quick<true>(c.data(), s, t_end)
                                                     : ContactModel::stored_quick<false>(c.data(), s, t_end)))) {
          const StoredForm was = to_engine(c.data(), clock);
          follow(c, m.step(c.data(), tag, s, dt, nc), x);
          from_engine(c.data(), t_end, was);
        }
        clock = t_end;
        ASSERT_EQ(na, nb) << "tag " << tag << " step " << k;
        ASSERT_EQ(a[CS_NBREAK], b[CS_NBREAK]) << "tag " << tag << " step " << k;
        ASSERT_EQ(0, std::memcmp(b.data(), c.data(), b.size() * sizeof(double)))
            << "tag " << tag << " step " << k;
        if (b[CT_BOUND_S] == ContactModel::BOUND_ALL) ++top;
      }
      if (t.theta >= 1.0) EXPECT_GT(top, 1000) << tag;    // the top bound is exercised
      breaks += na;
      // the same contact now: its stretch, threshold and anchor to
      // rounding, its age and budget through the clock
      EXPECT_NEAR(a[CS_STRETCH], b[CS_STRETCH], 1e-9) << tag;
      EXPECT_EQ(a[CS_THRESHOLD], b[CS_THRESHOLD]) << tag;
      EXPECT_NEAR(a[CS_ANCHOR], b[CS_ANCHOR], 1e-9) << tag;
      EXPECT_EQ(a[CT_WAIT] > 0.0, b[CT_WAIT] > 0.0) << tag;
      const StoredForm now = to_engine(b.data(), clock);
      EXPECT_NEAR(now.age, a[CT_AGE], 1e-9 * (1.0 + clock)) << tag;
      EXPECT_NEAR(now.budget, a[CT_BUDGET], 1e-9) << tag;
    }
    // the common step is the common case, and the lives are many
    EXPECT_GT(quick, total * 7 / 10);
    EXPECT_GT(breaks, 60 * 5);
  }
}

// a call in which no time passes and nothing changes leaves the stored
// row as it was, to the bit (the set-up of a run, run 0, a restart)
TEST(StoredForm, NoTimeAndNoChangeKeepTheBits)
{
  for (const ThermalSpec &t : stored_specs()) {
    const ContactModel m = thermal_model(t, true, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"));
    for (uint64_t tag = 1; tag <= 40; ++tag) {
      std::vector<double> b(m.columns(), 0.0);
      m.form(b.data(), tag, 0.0);
      from_engine(b.data(), 0.0);
      double clock = 0.0;
      long nb = 0;
      for (int k = 1; k <= 137 * static_cast<int>(tag); ++k) {
        const double x = 0.003 * k;
        const StoredForm was = to_engine(b.data(), clock);
        follow(b, m.step(b.data(), tag, x - b[CS_ANCHOR], 0.1, nb), x);
        clock += 0.1;
        from_engine(b.data(), clock, was);
      }
      const std::vector<double> before = b;
      const StoredForm was = to_engine(b.data(), clock);
      m.new_run(b.data());
      from_engine(b.data(), clock, was);
      ASSERT_EQ(0, std::memcmp(b.data(), before.data(), b.size() * sizeof(double))) << tag;
    }
  }
}

// the budget is counted down only while a bound with a rate holds it; a
// waiting contact is of age 0 and forms when its wait ends
TEST(StoredForm, BudgetAndAgeThroughTheClock)
{
  const ContactModel m = thermal_model(theta_spec(0.05), true);
  std::vector<double> r(m.columns(), 0.0);
  m.form(r.data(), 7, 0.0);
  ASSERT_LT(r[CT_BOUND_S], 0.0);    // no bound yet
  const double budget = r[CT_BUDGET];
  r[CT_AGE] = 1.5;
  from_engine(r.data(), 10.0);
  EXPECT_EQ(r[CT_RUNOUT], -budget);    // not counted down: minus the budget
  EXPECT_EQ(r[CT_FORMED], 8.5);
  StoredForm w = to_engine(r.data(), 30.0);
  EXPECT_EQ(w.budget, budget);    // held
  EXPECT_EQ(w.age, 21.5);
  // a bound of rate 0.25: the budget runs out budget/0.25 later
  r[CT_BOUND_S] = 0.5;
  r[CT_BOUND_RATE] = 0.25;
  from_engine(r.data(), 30.0, w);
  EXPECT_DOUBLE_EQ(r[CT_RUNOUT], 30.0 + budget / 0.25);
  w = to_engine(r.data(), 31.0);
  EXPECT_NEAR(w.budget, budget - 0.25, 1e-14);
  EXPECT_EQ(w.age, 22.5);
  // the quick test: within the bound and before the run-out
  from_engine(r.data(), 31.0, w);
  const double out = r[CT_RUNOUT];
  EXPECT_TRUE(ContactModel::stored_quick<true>(r.data(), 0.2, std::nextafter(out, 0.0)));
  EXPECT_FALSE(ContactModel::stored_quick<true>(r.data(), 0.2, out));
  EXPECT_FALSE(ContactModel::stored_quick<true>(r.data(), 0.6, 31.1));    // beyond the bound
  EXPECT_FALSE(ContactModel::stored_quick<true>(r.data(), 1.2, 31.1));    // beyond x_s
  // broken at 40 with a wait of 4 (as break_once() leaves it): formed when
  // the wait ends, of age 0 until then, its new budget held
  w = to_engine(r.data(), 40.0);
  r[CT_WAIT] = 4.0;
  r[CT_AGE] = 0.0;
  r[CT_BUDGET] = 0.7;
  r[CT_BOUND_S] = ContactModel::NO_BOUND;
  from_engine(r.data(), 40.0, w);
  EXPECT_EQ(r[CT_FORMED], 44.0);
  EXPECT_EQ(r[CT_RUNOUT], -0.7);
  // a budget of 0 not counted down (-0.0) is told from a run-out at 0
  r[CT_BUDGET] = 0.0;
  r[CT_AGE] = 0.0;
  from_engine(r.data(), 40.0);
  EXPECT_TRUE(std::signbit(r[CT_RUNOUT]));
  EXPECT_EQ(to_engine(r.data(), 41.0).budget, 0.0);
  r[CT_BUDGET] = 0.7;
  r[CT_AGE] = 0.0;
  from_engine(r.data(), 40.0);
  r[CT_WAIT] -= 1.0;    // a step of 1 (quick_wait())
  w = to_engine(r.data(), 41.0);
  EXPECT_EQ(w.age, 0.0);
  EXPECT_EQ(w.budget, 0.7);
}

// a contact that leaves the group and comes back (the same break count)
// starts a life of its own at its return
TEST(StoredForm, ReentryIsANewLife)
{
  const ContactModel m = thermal_model(theta_spec(0.05), true);
  std::vector<double> r(m.columns(), 0.0);
  m.form(r.data(), 9, 0.0);
  from_engine(r.data(), 2.0);
  StoredForm w = to_engine(r.data(), 5.0);
  m.depart(r.data());
  from_engine(r.data(), 5.0, w);
  w = to_engine(r.data(), 8.0);
  m.form(r.data(), 9, 1.0);    // the re-entry: event 0 again, another stream
  ASSERT_EQ(r[CS_NBREAK], 0.0);
  from_engine(r.data(), 8.0, w);
  EXPECT_EQ(r[CT_FORMED], 8.0);
  EXPECT_EQ(to_engine(r.data(), 9.5).age, 1.5);
}

// the avalanche on rows in stored form (its clock given) breaks what it
// breaks on the same rows in engine form: the aged thresholds from the
// formation times, and the new lives' times on the clock (a thermal
// break of the step: its new life already 0.3 old)
TEST(StoredForm, AvalancheOfStoredRows)
{
  ThermalSpec t = theta_spec(0.05);
  t.aging = AgingLaw::LOG;
  t.beta = 0.3;
  t.tau_a = 1.0;
  const ContactModel m(1.0, 4711, spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"),
                       spec(make_uniform(-0.2, 0.2), "uniform -0.2 0.2"), DistributionSpec{},
                       true, true, false, t);
  const int n = 12;
  int broke = 0, aged = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<std::vector<double>> a(n), b(n);
    std::vector<double *> ra, rb;
    const double clock = 50.0 + trial;
    for (int i = 0; i < n; ++i) {
      a[i].assign(m.columns(), 0.0);
      m.form(a[i].data(), 1000 * trial + i, 0.0);
      a[i][CT_AGE] = 0.5 * ((i * 7 + trial) % 13);    // aged thresholds up to 1 + 0.3 ln 7
      // stretched to between x_s0 and 1.1 x_s0 A(age): some over the aged threshold
      a[i][CS_STRETCH] = a[i][CS_THRESHOLD] * (1.0 + 0.1 * ((i * 5 + trial) % 11) / 10.0 *
                                                         m.thermal_model().factor(a[i][CT_AGE]));
      b[i] = a[i];
      from_engine(b[i].data(), clock);
      ra.push_back(a[i].data());
      rb.push_back(b[i].data());
      if (std::fabs(a[i][CS_STRETCH]) < m.threshold_now(a[i].data())) ++aged;
    }
    DenseField fa(chain_matrix(n, 0.002), ra), fb(chain_matrix(n, 0.002), rb);
    fa.thermal_rows = fb.thermal_rows = true;
    fa.recompute();
    fb.recompute();
    std::vector<int> members(n), list;
    for (int i = 0; i < n; ++i) members[i] = i;
    std::vector<double> ds, hot(n, NAN), hot_age(n, 0.0);
    const int j = trial % n;
    hot[j] = 0.5 * a[j][CS_STRETCH];
    hot_age[j] = 0.3;
    const AvalancheResult x =
        avalanche(m, ra.data(), members.data(), n, 0.0, fa, list, ds, hot.data(), hot_age.data());
    const AvalancheResult y = avalanche(m, rb.data(), members.data(), n, 0.0, fb, list, ds,
                                        hot.data(), hot_age.data(), clock);
    ASSERT_EQ(x.size, y.size) << trial;
    ASSERT_EQ(x.rounds, y.rounds) << trial;
    broke += x.size;
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(a[i][CS_NBREAK], b[i][CS_NBREAK]) << trial << " " << i;
      EXPECT_EQ(a[i][CS_THRESHOLD], b[i][CS_THRESHOLD]) << trial << " " << i;
      EXPECT_NEAR(a[i][CS_STRETCH], b[i][CS_STRETCH], 1e-12) << trial << " " << i;
      EXPECT_NEAR(to_engine(b[i].data(), clock).age, a[i][CT_AGE], 1e-12) << trial << " " << i;
    }
    EXPECT_GE(a[j][CS_NBREAK], 1.0);    // the thermal break
  }
  EXPECT_GT(broke, 20);    // breaks, and contacts that aging kept from breaking
  EXPECT_GT(aged, 40);
}
