// SPDX-License-Identifier: Apache-2.0
// override_key.hpp: the one definition of how the key of an override "section.key=value" is
// read, shared by `--set` (scenario_reader.cpp) and campaign files (campaign.cpp: [set],
// [[sweep]] and [replicates] keys), so that two spellings a campaign could compare as
// different keys are never applied as the same one. A key is read by trimming the blanks
// (spaces and tabs) around it; it must then be a dotted key: parts of letters, digits, '_' and
// '-', joined by single dots.
#pragma once

#include <string>
#include <string_view>

namespace uvms::sil {

/// `s` without the spaces and tabs around it.
inline std::string TrimBlanks(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  return std::string(s.substr(b, s.find_last_not_of(" \t") - b + 1));
}

/// Whether `key` is a dotted key ("run.seed", "environment.unsteady_flow.enabled").
inline bool IsDottedKey(std::string_view key) {
  if (key.empty() || key.front() == '.' || key.back() == '.') return false;
  for (size_t i = 0; i < key.size(); ++i) {
    const char c = key[i];
    const bool bare = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '-';
    if (c == '.' ? key[i - 1] == '.' : !bare) return false;
  }
  return true;
}

/// The key as an override applies it (TrimBlanks); "" when that is not a dotted key.
inline std::string NormalizedKey(std::string_view raw) {
  std::string k = TrimBlanks(raw);
  return IsDottedKey(k) ? k : std::string();
}

}  // namespace uvms::sil
