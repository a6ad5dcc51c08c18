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
   FRICTION-EQ package: one-dimensional probability distributions used by
   the EQ model (breaking thresholds P_c, re-forming stretches R,
   per-contact stiffness factors) and by the master-equation solver.

   LAMMPS-free.  Every distribution provides its density, both tails of its
   cumulative distribution with full relative precision, both inverse
   tails, and the exact integrals the master-equation solver needs.
------------------------------------------------------------------------- */

#ifndef FEQ_DISTRIBUTION_H
#define FEQ_DISTRIBUTION_H

#include "eq_random.h"

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace feq {

// Error in a user's specification (bad value, missing file, ...).
// The message names the keyword and, where it applies, the allowed values.
class SpecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A token that reads as a number whose value is not usable (NaN, infinite,
// beyond the range of a double, subnormal, below the subnormal range):
// parse_number() throws it with the cause ("value '<token>' is ..."), so
// that callers name the cause rather than "expected a number".
class NumberError : public SpecError {
 public:
  using SpecError::SpecError;
};

// The family of a distribution, for behaviour that depends on it (the
// display text describe() is for people, never for decisions).
enum class DistKind { UNIFORM, GAUSSIAN, REALISTIC, DELTA, TABLE };

class Distribution {
 public:
  virtual ~Distribution() = default;

  virtual DistKind kind() const = 0;
  virtual std::string describe() const = 0;    // e.g. "uniform 0.75 1.25"
  virtual double lower() const = 0;            // support [lower, upper], may be infinite
  virtual double upper() const = 0;
  virtual double pdf(double x) const = 0;      // density (0 for a point mass)
  virtual double cdf(double x) const = 0;      // P(X <= x)
  virtual double sf(double x) const = 0;       // P(X > x), full precision in the upper tail
  virtual double quantile(double p) const = 0; // smallest x with cdf(x) >= p
  virtual double isf(double q) const = 0;      // x with sf(x) = q
  virtual double sf_integral(double a, double b) const = 0;     // int_a^b sf(x) dx
  virtual double partial_mean(double a, double b) const = 0;    // int_a^b x dP(x), (a,b]
  virtual double mean() const = 0;
  virtual double second_moment() const = 0;
  bool is_point() const { return kind() == DistKind::DELTA; }    // a point mass
  // points where the density is not smooth (quadrature break points)
  virtual std::vector<double> breakpoints() const { return {}; }

  double variance() const { return second_moment() - mean() * mean(); }
  // upper() when finite, else where the survival function underflows
  // (sf < 1e-300): no draw can land above it
  double effective_upper() const;
  double hazard(double x) const;    // pdf/sf: breaking rate per unit stretch

  // Inverse-transform draw from a uniform variate (the tail with the
  // better precision is used).  A family may override it with the same
  // numbers, faster
  virtual double sample(const Uniform &u) const;
  // Draw conditioned on X > lo.  Returns NaN when P(X > lo) = 0.
  double sample_above(double lo, const Uniform &u) const;
};

using DistributionPtr = std::shared_ptr<const Distribution>;

DistributionPtr make_uniform(double lo, double hi);
// normal(mean, sd) truncated to x > trunc (trunc may be -infinity)
DistributionPtr make_gaussian(double mean, double sd, double trunc);
// P_c0(x) = (2/xs) u^3 exp(-u^2), u = x/xs (the paper's realistic thresholds)
DistributionPtr make_realistic(double xs);
DistributionPtr make_delta(double x0);
// density linear between the points (x_k, p_k), zero outside, normalized
DistributionPtr make_table(const std::vector<double> &x, const std::vector<double> &p,
                           const std::string &label);

// Read the section KEYWORD of a table file:
//   # comment lines
//   KEYWORD
//   N n
//   (blank line)
//   1 x_1 p_1
//   ...
//   n x_n p_n
// Throws SpecError naming the file, keyword and line on any problem.
void read_table_file(const std::string &path, const std::string &keyword, std::vector<double> &x,
                     std::vector<double> &p);
// The same from the file's contents (name: for messages).
void read_table_text(const std::string &text, const std::string &name, const std::string &keyword,
                     std::vector<double> &x, std::vector<double> &p);
// The contents of a file; throws SpecError "cannot open table file '...'"
// with the cause (a directory, the system's reason).
std::string load_file(const std::string &path);

// Standard normal helpers (exposed for tests).
double normal_cdf(double z);
double normal_sf(double z);
double normal_quantile(double p);    // Wichura AS241 (PPND16), ~1e-16 relative

/* ----------------------------------------------------------------------
   Keyword parsing shared by fix eq/contacts, the eq/me command and the
   eq-me tool, so that all three accept the same syntax and report the
   same errors.
------------------------------------------------------------------------- */

enum class Role { THRESHOLD, REFORM, STIFFNESS };

struct DistributionSpec {
  DistributionPtr dist;    // null for "reform none" (contacts never re-form)
  std::string text;        // canonical text, e.g. "uniform 0.75 1.25" (for display)

  // the point mass at 1: "stiffness constant" (the default), k_i = k_c
  // exactly, nothing drawn
  bool constant() const { return dist && dist->is_point() && dist->mean() == 1.0; }
};

// number parser: converts one token or throws (LAMMPS passes utils::numeric)
using NumberParser = std::function<double(const std::string &)>;
// file loader: returns the contents of a table file named in the input, or
// throws SpecError.  LAMMPS reads it on rank 0 (with its potential-file
// search path) and broadcasts it, so every rank sees the same file or the
// same error; the default reads the named file.
using FileLoader = std::function<std::string(const std::string &)>;

// What the messages of parse_distribution call the keyword and the numbers
// it expects: by default the role's keyword and "a number" (fix
// eq/substrate's disorder keyword parses a stiffness distribution of
// finite numbers: "disorder", "a finite number").
struct SpecWording {
  explicit SpecWording(std::string keyword_ = std::string(), std::string number_ = "a number") :
      keyword(std::move(keyword_)), number(std::move(number_))
  {
  }
  std::string keyword;    // empty: role_keyword(role)
  std::string number;
};

// Parses the values after a keyword, starting at args[pos]; advances pos.
DistributionSpec parse_distribution(Role role, const std::vector<std::string> &args, size_t &pos,
                                    const NumberParser &number, const FileLoader &load = {},
                                    const SpecWording &wording = SpecWording());

// Probability that a re-forming stretch r lies at or beyond the largest
// breaking threshold, |r| >= max x_s (0 when P_c is unbounded): such a
// contact could never hold.  check_reform throws a SpecError naming the
// reform keyword when that probability exceeds REFORM_BEYOND_TOLERANCE;
// below it, fix eq/contacts draws r from R truncated to |r| < max x_s.
constexpr double REFORM_BEYOND_TOLERANCE = 1e-12;
double reform_beyond_thresholds(const Distribution &Pc, const Distribution &R);
void check_reform(const Distribution &Pc, const DistributionSpec &reform);

// Strict default number parser (whole token, finite, normal or 0), also
// the numbers of threshold and substrate tables (read_table_text): throws
// SpecError "expected a number, got '<token>'" or, for a number strtod
// reads that is no usable double, NumberError "value '<token>' is ..."
// with the cause (subnormal, below the subnormal range, beyond the range,
// infinite, NaN).
double parse_number(const std::string &token);

const char *role_keyword(Role role);
const char *role_styles(Role role);

}    // namespace feq

#endif
