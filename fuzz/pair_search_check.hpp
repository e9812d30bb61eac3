#pragma once

// The checks the planar and point-kind targets run on each query: the
// query at a separation d >= 0 decided with the searches of docs/design.md
// §5a (lab::Settings{}) and with both switched off (the box search over
// (t, u, v), or the exact stage, decides instead), in both certified modes,
// against each other and against exact truth. Each broken invariant aborts
// with its name and the numbers involved.
//
// What may be compared (options.hpp, Mode):
// - exact mode: a decision that is not counted undecided is a proof, so two
//   proven decisions are equal; an undecided hit (d > 0: the closest
//   approach within 2^-40 of the size above d) may stand against a proven
//   miss, never a proven miss against a proven hit. At d = 0 their TOIs
//   (each at most 2^-40 before the first contact, never after it) lie
//   within 2^-40 of each other;
// - conservative mode: every proven contact found, at d = 0 at a TOI no
//   later (false positives within tolerance are allowed);
// - truth: at d = 0 the exact stage alone; at d > 0 the exact labels of
//   tests/exact_distance.hpp (a rational witness, or a certified lower bound
//   of the distance over [0, 1]). A labelled hit at or before tmax is found
//   by every call at a TOI no later than the witness, and no TOI lies
//   inside a contact (exact distance at least d there); after a labelled
//   miss, exact mode reports a hit only when undecided in its band and
//   conservative mode only within its tolerance.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>

#include "batchccd/batch.hpp"
#include "batchccd/lab.hpp"
#include "exact/exact_solver.hpp"
#include "exact_distance.hpp"
#include "fuzz_check.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::fuzz {

inline constexpr double kExactToiWidth = 0x1p-40;

// One query decided alone through the batch call of the scalar path, which
// also says whether its hit is a decision (Counters::undecided). The box
// search at d > 0 gets 2^14 boxes rather than 2^20: where the searches of
// §5a stay uncertain (docs/design.md §5a, "With a separation") it may spend
// seconds on one query under the sanitizers, and a query it cannot settle
// is an undecided hit, which the checks allow.
inline constexpr std::int64_t kBoxBudget = 1 << 14;

struct Decision {
  QueryResult result;
  bool undecided = false;
  bool proven_hit() const { return result.hit && !undecided; }
  bool proven_miss() const { return !result.hit; }
};

inline Decision decide(Kind kind, const Query& query, double separation, Mode mode, double tmax,
                       const lab::Settings& settings) {
  Options options;
  options.mode = mode;
  options.tmax = tmax;
  options.isa = Isa::scalar;
  options.threads = 1;
  options.max_iterations = kBoxBudget;
  const double separations[] = {separation};
  BatchResult out;
  lab::batch_ccd(kind, std::span<const Query>(&query, 1), separations, options, settings, out);
  return {out.results.at(0), out.counters.undecided > 0};
}

// The library's settings, and the same with the searches of §5a off.
inline lab::Settings with_pair_searches() { return {}; }
inline lab::Settings box_search_only() {
  lab::Settings settings;
  settings.planar_path = false;
  settings.point_search = false;
  return settings;
}

inline void require_near(bool holds, const char* invariant, double a, double b) {
  if (holds) return;
  char detail[96];
  std::snprintf(detail, sizeof detail, "(%.17g against %.17g)", a, b);
  fail(invariant, detail);
}

inline void check_window(Kind kind, const Query& query, double separation, double tmax,
                         const testing::Labelled& truth) {
  const Decision exact = decide(kind, query, separation, Mode::exact, tmax, with_pair_searches());
  const Decision exact_box = decide(kind, query, separation, Mode::exact, tmax, box_search_only());
  const Decision conservative = decide(kind, query, separation, Mode::conservative, tmax, with_pair_searches());
  const Decision conservative_box = decide(kind, query, separation, Mode::conservative, tmax, box_search_only());
  for (const Decision* d : {&exact, &exact_box, &conservative, &conservative_box})
    require(d->result.status == Status::ok, "finite input is evaluated");

  // (a) The two procedures against each other. TOIs are compared at d = 0
  // only: at d > 0 the box search locates the first time within its band
  // (d + 2^-40 of the size), which on a slow approach comes more than 2^-40
  // before the first time within d; there each TOI is checked in (b).
  const bool compare_tois = separation == 0;
  const auto agree = [&](const Decision& a, const Decision& b) {
    if (a.proven_hit() && b.proven_miss()) fail("exact mode: a proven hit against a proven miss");
    if (compare_tois && a.proven_hit() && b.result.hit)
      require_near(b.result.toi <= a.result.toi + 2 * kExactToiWidth, "exact mode: TOI no later than a proven one",
                   b.result.toi, a.result.toi);
  };
  agree(exact, exact_box);
  agree(exact_box, exact);
  if (compare_tois && exact.proven_hit() && exact_box.proven_hit())
    require_near(std::fabs(exact.result.toi - exact_box.result.toi) <= 2 * kExactToiWidth,
                 "exact mode: proven TOIs within 2^-40", exact.result.toi, exact_box.result.toi);
  for (const Decision* proven : {&exact, &exact_box}) {
    if (!proven->proven_hit()) continue;
    for (const Decision* c : {&conservative, &conservative_box}) {
      require(c->result.hit, "conservative mode finds every proven contact");
      if (compare_tois)
        require_near(c->result.toi <= proven->result.toi + 2 * kExactToiWidth,
                     "conservative TOI no later than a proven contact", c->result.toi, proven->result.toi);
    }
  }

  // (b) Exact truth.
  if (separation == 0) {
    const exact::ExactOutcome stage = exact::solve_exactly(reference::evaluated_kind(kind), query, true, tmax);
    if (stage.bound_reached) return;
    for (const Decision* d : {&exact, &exact_box}) {
      require(d->result.hit == stage.hit, "exact mode at d = 0 decides as the exact stage");
      if (stage.hit)
        require_near(std::fabs(d->result.toi - stage.toi) <= 2 * kExactToiWidth,
                     "exact mode at d = 0: TOI within 2^-40 of the exact stage's", d->result.toi, stage.toi);
    }
    if (stage.hit)
      for (const Decision* c : {&conservative, &conservative_box}) {
        require(c->result.hit, "conservative mode at d = 0 finds every contact");
        require_near(c->result.toi <= stage.toi + 2 * kExactToiWidth, "conservative TOI at d = 0 no later",
                     c->result.toi, stage.toi);
      }
    return;
  }
  // A TOI is never after the first contact: the primitives are not within
  // d there, exactly (or it is 0).
  const testing::Rational d2 = testing::Rational(separation) * separation;
  for (const Decision* d : {&exact, &exact_box, &conservative, &conservative_box})
    if (d->result.hit && d->result.toi > 0)
      require_near(testing::squared_distance_at(reference::evaluated_kind(kind), query, d->result.toi) >= d2,
                   "the TOI is not inside a contact", d->result.toi, separation);
  if (truth.label == testing::Label::hit && truth.witness <= tmax) {
    for (const Decision* d : {&exact, &exact_box, &conservative, &conservative_box}) {
      require(d->result.hit, "a labelled contact is found");
      require_near(d->result.toi <= truth.witness, "TOI no later than the exact witness", d->result.toi,
                   truth.witness);
    }
  }
  if (truth.label == testing::Label::miss) {
    // The bands' upper ends, with room for the labeller's rounded bounds.
    const double exact_band = separation + 2 * kExactToiWidth * truth.size;
    const double tolerance_band = separation + 2 * Options{}.tolerance * truth.size;
    for (const Decision* d : {&exact, &exact_box})
      if (d->result.hit) {
        require(d->undecided, "exact mode: a labelled miss reported as a proven hit");
        require_near(truth.lower_bound <= exact_band, "exact mode: an undecided hit outside its band",
                     truth.lower_bound, exact_band);
      }
    for (const Decision* c : {&conservative, &conservative_box})
      if (c->result.hit && !c->undecided)
        require_near(truth.lower_bound <= tolerance_band, "conservative mode: a false positive beyond tolerance",
                     truth.lower_bound, tolerance_band);
  }
}

// The checks above on one query at one separation, at each time window in
// `windows` (the exact labels are computed once: they cover [0, 1]).
inline void check_at_separation(Kind kind, const Query& query, double separation, std::span<const double> windows) {
  const Kind evaluated = reference::evaluated_kind(kind);
  testing::Labelled label;
  if (separation > 0) label = testing::label(evaluated, query, separation);
  for (const double tmax : windows) check_window(kind, query, separation, tmax, label);
}

}  // namespace batchccd::fuzz
