// ValidationReport: lookups and the human-readable form.
#include <algorithm>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/quality/validate.h"

namespace afmesh {
namespace {

std::string_view outcome_label(CheckOutcome outcome) {
  switch (outcome) {
    case CheckOutcome::kPassed:
      return "PASS";
    case CheckOutcome::kWarning:
      return "WARN";
    case CheckOutcome::kFailed:
      return "FAIL";
    case CheckOutcome::kNotRun:
      return "SKIP";
  }
  return "?";
}

}  // namespace

bool ValidationReport::valid() const {
  return std::none_of(checks.begin(), checks.end(), [](const Check& c) {
    return c.outcome == CheckOutcome::kFailed;
  });
}

const Check* ValidationReport::find(std::string_view name) const {
  for (const Check& c : checks) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

std::string ValidationReport::to_string() const {
  std::string text;
  for (const Check& c : checks) {
    absl::StrAppendFormat(&text, "[%s] %s: %s\n", outcome_label(c.outcome), c.name, c.summary);
    for (const Finding& f : c.findings) absl::StrAppend(&text, "    ", f.message, "\n");
    const std::int64_t more = c.finding_count - static_cast<std::int64_t>(c.findings.size());
    if (more > 0) absl::StrAppend(&text, "    ... and ", more, " more\n");
  }
  return text;
}

}  // namespace afmesh
