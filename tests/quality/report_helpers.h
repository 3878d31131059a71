// Helpers for asserting on validation reports.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string_view>
#include <vector>

#include "core/quality/validate.h"

namespace afmesh::testing {

// The check named `name`; a test failure (and a not-run placeholder) when the report lacks it.
inline Check check_of(const ValidationReport& report, std::string_view name) {
  if (const Check* c = report.find(name)) return *c;
  ADD_FAILURE() << "report has no check " << name << "\n" << report.to_string();
  Check missing;
  missing.outcome = CheckOutcome::kNotRun;
  return missing;
}

inline CheckOutcome outcome_of(const ValidationReport& report, std::string_view name) {
  return check_of(report, name).outcome;
}

inline bool contains(const std::vector<Index>& ids, Index id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

// Number of findings of `check` whose message contains `text`.
inline int findings_mentioning(const Check& check, std::string_view text) {
  return static_cast<int>(std::count_if(
      check.findings.begin(), check.findings.end(),
      [&](const Finding& f) { return f.message.find(text) != std::string::npos; }));
}

// True when some finding has exactly these tet / triangle lists (in the order given).
inline bool has_finding_with_tets(const Check& check, const std::vector<Index>& tets) {
  return std::any_of(check.findings.begin(), check.findings.end(),
                     [&](const Finding& f) { return f.tets == tets; });
}
inline bool has_finding_with_triangles(const Check& check, const std::vector<Index>& triangles) {
  return std::any_of(check.findings.begin(), check.findings.end(),
                     [&](const Finding& f) { return f.triangles == triangles; });
}

// Every check passed (warnings allowed), except those in `not_run`, which must not have run.
inline void expect_all_passed(const ValidationReport& report,
                              const std::vector<std::string_view>& not_run = {}) {
  EXPECT_TRUE(report.valid()) << report.to_string();
  for (const Check& c : report.checks) {
    const bool skipped = std::find(not_run.begin(), not_run.end(), c.name) != not_run.end();
    if (skipped) {
      EXPECT_EQ(c.outcome, CheckOutcome::kNotRun) << c.name << "\n" << report.to_string();
    } else {
      EXPECT_EQ(c.outcome, CheckOutcome::kPassed) << c.name << "\n" << report.to_string();
      EXPECT_EQ(c.finding_count, 0) << c.name;
    }
  }
}

}  // namespace afmesh::testing
