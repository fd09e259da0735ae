// SPDX-License-Identifier: Apache-2.0
// scenario_reader.hpp: the TOML side of the scenario reader (internal to sil/scenario/scenario.cpp):
// the document with its --set overrides, typed access to its keys with errors that name
// FILE:LINE and the dotted key, the unknown-key check, and the generic read of one key of the
// table of configuration fields (type, then range rule; sil/msg/config_table.h).
#pragma once

#include <toml++/toml.h>

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "scenario/config_schema.hpp"
#include "scenario/scenario.hpp"

namespace uvms::sil {

/// x with up to 12 significant digits (the numbers in error messages).
std::string Num(double x);

/// "a table", "an integer", ...: what a node is, for error messages.
std::string TypeName(const toml::node &n);

/// "FILE:LINE" of a node; an override's region is named by its "--set KEY=VALUE" text.
std::string Where(const toml::node *n, const std::string &fallback);

/// "a, b, c"
std::string Join(const std::vector<std::string> &v);

/// The file's stem ("case_VII_unsteady"), or `source` when it has none.
std::string Stem(const std::string &source);

/// Input bounds checked on the raw text before toml++ sees it (toml++ recurses on nesting and
/// dotted keys: a 50,000-part dotted key overflows its stack).
/// ScenarioError "SOURCE:LINE: ..." when `text` exceeds a bound of sil/scenario/toml_bounds.hpp (size,
/// nesting depth, dotted-key parts) or holds a NUL byte; strings and comments are skipped.
void CheckTomlBounds(std::string_view text, const std::string &source);

/// The bytes of a scenario or campaign file: ScenarioError unless it is a regular file (not a
/// directory, a device such as /dev/urandom, a FIFO) of at most kMaxTomlBytes.
std::string ReadTomlFile(const std::string &path);

/// The TOML document with the overrides applied ("section.key=value", value in TOML syntax,
/// each parsed as the document "v = VALUE" and put at its dotted key with the source region
/// "--set KEY=VALUE"). ScenarioError for a syntax error or a malformed override.
toml::table ParseDocument(std::string_view toml_text, const std::string &source,
                          const std::vector<std::string> &overrides);

/// A key looked up in a section: `node` is null when absent; `anchor` is the section's table
/// (or null), used to place errors about an absent key.
struct Item {
  const toml::node *node{nullptr};
  const toml::node *anchor{nullptr};
  std::string key;  ///< dotted, e.g. "environment.unsteady_flow.enabled"
  explicit operator bool() const { return node != nullptr; }
};

/// A section (table) of the document; `table` is null when the file does not have it.
struct Sec {
  const toml::table *table{nullptr};
  std::string key;  ///< dotted; "" for the root
};

/// Typed access to the document. Every key asked for is recorded as a known key of its table
/// and, when present, as used; CheckUnknown then reports the first node nobody asked for.
class Reader {
 public:
  Reader(const toml::table &root, std::string source) : root_(root), source_(std::move(source)) {}

  Sec Root() const { return Sec{&root_, ""}; }
  const std::string &source() const { return source_; }

  /// Throw the ScenarioError "WHERE: key "K": what" for an item (placed at its node, or at its
  /// section when absent).
  [[noreturn]] void Fail(const Item &it, const std::string &what) const;

  /// Look up `name` in `sec` (recorded as a known key of that table; marked used if present).
  Item Get(const Sec &sec, const std::string &name);
  /// A sub-table (null table when absent); an error when `name` is not a table.
  Sec Sub(const Sec &sec, const std::string &name);
  /// An array of tables ([[section.name]] or [{...}, ...]): one Sec per element.
  std::vector<Sec> Tables(const Sec &sec, const std::string &name);

  double Real(const Item &it, double def) const;            ///< a finite number
  std::int64_t Int(const Item &it, std::int64_t def) const;  ///< an integer
  bool Bool(const Item &it, bool def) const;
  std::string Str(const Item &it, const std::string &def) const;
  std::vector<double> Reals(const Item &it, std::size_t n) const;  ///< exactly n finite numbers
  plant::Vec3 Vec(const Item &it, const plant::Vec3 &def) const;

  /// Every node of the document nobody asked for is an unknown key: report the first in the
  /// file (overrides after file keys).
  void CheckUnknown() const;

 private:
  struct Unknown {
    const toml::node *node;
    const toml::table *parent;
    std::string key;
  };
  void Walk(const toml::table &t, const std::string &prefix, std::vector<Unknown> &found) const;

  const toml::table &root_;
  std::string source_;
  std::set<const toml::node *> used_;
  std::map<const toml::table *, std::vector<std::string>> known_;
};

/// The value of one key of the table, read by its row's type and checked against its range
/// rule: null when absent, and for the rows a rule reads itself (SPECIAL range, arrays of
/// tables). Reals and vectors as numbers, integers as integers, enums as their value.
Json ReadKey(const Reader &rd, const Item &it, const ConfigRow &row);

}  // namespace uvms::sil
