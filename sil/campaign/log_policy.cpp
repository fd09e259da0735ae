// SPDX-License-Identifier: Apache-2.0
// log_policy.cpp: which runs keep their run.lcmlog (log_policy.hpp).
#include "campaign/log_policy.hpp"

#include <fnmatch.h>

#include <stdexcept>

namespace uvms::sil {
namespace {

bool Matches(const std::string &pattern, const std::string &id) {
  return fnmatch(pattern.c_str(), id.c_str(), 0) == 0;
}

}  // namespace

bool LogPolicy::KeepsFinished(const std::string &id) const {
  switch (mode) {
    case Mode::kAll: return true;
    case Mode::kFailed:
    case Mode::kNone: return false;
    case Mode::kIds: break;
  }
  for (const std::string &p : patterns)
    if (Matches(p, id)) return true;
  return false;
}

std::string LogPolicy::Text() const {
  switch (mode) {
    case Mode::kAll: return "all";
    case Mode::kFailed: return "failed";
    case Mode::kNone: return "none";
    case Mode::kIds: break;
  }
  std::string s;
  for (const std::string &p : patterns) s += (s.empty() ? "" : ",") + p;
  return s;
}

LogPolicy ParseLogPolicy(const std::string &value) {
  LogPolicy p;
  if (value == "all") return p;
  if (value == "failed" || value == "none") {
    p.mode = value == "failed" ? LogPolicy::Mode::kFailed : LogPolicy::Mode::kNone;
    return p;
  }
  if (value.empty())
    throw std::invalid_argument("--logs needs all, failed, none or run ids (ID[,ID...])");
  p.mode = LogPolicy::Mode::kIds;
  size_t start = 0;
  while (start <= value.size()) {
    const size_t comma = value.find(',', start);
    const std::string id = value.substr(start, comma == std::string::npos ? std::string::npos
                                                                          : comma - start);
    if (id.empty())
      throw std::invalid_argument("--logs " + value + ": an empty run id (two commas, or a "
                                  "comma at an end)");
    p.patterns.push_back(id);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return p;
}

void CheckLogPolicy(const LogPolicy &policy, const Campaign &c) {
  if (policy.mode != LogPolicy::Mode::kIds) return;
  for (const std::string &p : policy.patterns) {
    bool any = false;
    for (const CampaignRun &r : c.runs) any = any || Matches(p, r.id);
    if (any) continue;
    std::string some;
    for (size_t k = 0; k < c.runs.size() && k < 5; ++k) some += (k ? ", " : "") + c.runs[k].id;
    if (c.runs.size() > 5) some += ", ...";
    throw CampaignError("--logs: " + p + " names no run of " + c.name + " (its runs: " + some +
                        "; uvms campaign --dry-run lists them all)");
  }
}

}  // namespace uvms::sil
