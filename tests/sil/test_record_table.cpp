// SPDX-License-Identifier: Apache-2.0
// The table of per-tick record fields (sil/msg/record_table.h) against the .lcm files and the
// codec it generates:
//   - every row is a `double name[n];` (or `double name;`) field of its message, with the row's
//     element count, and the field's comment (with its continuation lines) states the row's
//     unit in brackets;
//   - every double field of sensors_t, actuators_t, telemetry_t and truth_t has a row (so the .lcm files
//     and the table cannot drift apart silently in either direction);
//   - a distinct value in every element of every row survives firmware -> message -> firmware
//     (sensors from the message; command and telemetry to the messages), so no row is dropped
//     or crossed with another by the generated mappings.
#include <catch2/catch.hpp>

#include <cstddef>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "msg/codec.h"
#include "msg/record_table.h"

namespace {

struct Row {
  std::string message, name, unit;
  std::size_t count;
};

#define ROW_(msg, name, dims, unit, doc)                                                  \
  Row{#msg, #name, unit, sizeof(((uvms_##msg##_t *)nullptr)->name) / sizeof(double)},
#define SENSOR_ROW_(name, dims, unit, doc) ROW_(sensors, name, dims, unit, doc)
#define ACTUATOR_ROW_(name, dims, unit, doc) ROW_(actuators, name, dims, unit, doc)
#define TELEMETRY_ROW_(name, dims, unit, doc) ROW_(telemetry, name, dims, unit, doc)
#define TRUTH_ROW_(name, dims, unit, doc) ROW_(truth, name, dims, unit, doc)
const std::vector<Row> kRows = {
    UVMS_SENSOR_FIELDS(SENSOR_ROW_) UVMS_ACTUATOR_FIELDS(ACTUATOR_ROW_)
        UVMS_REFERENCE_FIELDS(TELEMETRY_ROW_) UVMS_TELEMETRY_FIELDS(TELEMETRY_ROW_)
            UVMS_TRUTH_FIELDS(TRUTH_ROW_)};

struct LcmField {
  std::size_t count;
  std::string comment;
};

// The double fields of lcmtypes/<message>_t.lcm: name -> (element count, comment).
std::map<std::string, LcmField> DoubleFields(const std::string &message) {
  std::ifstream in(std::string(UVMS_SOURCE_DIR) + "/lcmtypes/" + message + "_t.lcm");
  REQUIRE(in.good());
  const std::regex field(R"(^\s*double\s+(\w+)(?:\[(\d+)\])?\s*;\s*(?://\s*(.*))?$)");
  const std::regex continuation(R"(^\s*//\s*(.*)$)");  // a comment line under a field
  std::map<std::string, LcmField> out;
  std::string line, last;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, field)) {
      last = m[1];
      out[last] = {m[2].matched ? std::stoul(m[2]) : 1u, m[3].matched ? m[3].str() : ""};
    } else if (!last.empty() && std::regex_match(line, m, continuation)) {
      out[last].comment += " " + m[1].str();
    } else {
      last.clear();
    }
  }
  return out;
}

}  // namespace

TEST_CASE("EveryRowIsItsMessageFieldWithItsShapeAndUnit", "[record_table]") {
  for (const Row &r : kRows) {
    INFO(r.message << "_t." << r.name);
    const auto fields = DoubleFields(r.message);
    const auto f = fields.find(r.name);
    REQUIRE(f != fields.end());
    CHECK(f->second.count == r.count);
    if (r.unit != "1") CHECK(f->second.comment.find("[" + r.unit + "]") != std::string::npos);
  }
}

TEST_CASE("EveryDoubleFieldOfTheTickMessagesHasARow", "[record_table]") {
  for (const char *message : {"sensors", "actuators", "telemetry", "truth"}) {
    std::set<std::string> rows;
    for (const Row &r : kRows)
      if (r.message == message) rows.insert(r.name);
    for (const auto &[name, field] : DoubleFields(message)) {
      INFO(message << "_t." << name << " (" << field.comment << ")");
      CHECK(rows.count(name) == 1);
    }
  }
}

namespace {

// Element e of field number f: distinct across all rows, exact in float.
double Distinct(int f, std::size_t e) { return 1.0 + f * 0.0625 + double(e) * 0.001953125; }

template <typename S>
void FillReals(S *s, std::size_t bytes_offset, std::size_t n, int f) {
  auto *p = reinterpret_cast<uvms_real_t *>(reinterpret_cast<char *>(s) + bytes_offset);
  for (std::size_t e = 0; e < n; ++e) p[e] = uvms_real_t(Distinct(f, e));
}

}  // namespace

TEST_CASE("EveryRowSurvivesTheGeneratedMappings", "[record_table]") {
  uvms_sensors_t sm{};
  int f = 0;
#define FILL_SENSOR_MSG_(name, dims, unit, doc)                                        \
  for (std::size_t e = 0; e < sizeof sm.name / sizeof(double); ++e)                   \
    reinterpret_cast<double *>(&sm.name)[e] = Distinct(f, e);                           \
  ++f;
  UVMS_SENSOR_FIELDS(FILL_SENSOR_MSG_)
  uvms_ctrl_sensors_t s;
  uvms_sensors_from_msg(&sm, &s);
  f = 0;
#define CHECK_SENSOR_(name, dims, unit, doc)                                            \
  for (std::size_t e = 0; e < sizeof s.name / sizeof(uvms_real_t); ++e)                \
    CHECK(double(reinterpret_cast<const uvms_real_t *>(&s.name)[e]) == Distinct(f, e)); \
  ++f;
  UVMS_SENSOR_FIELDS(CHECK_SENSOR_)

  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  std::memset(&cmd, 0, sizeof cmd);
  std::memset(&tlm, 0, sizeof tlm);
  f = 100;
#define FILL_CMD_(name, dims, unit, doc) \
  FillReals(&cmd, offsetof(uvms_ctrl_command_t, name), sizeof cmd.name / sizeof(uvms_real_t), f++);
#define FILL_TLM_(name, dims, unit, doc) \
  FillReals(&tlm, offsetof(uvms_ctrl_telemetry_t, name), sizeof tlm.name / sizeof(uvms_real_t), f++);
  UVMS_ACTUATOR_FIELDS(FILL_CMD_) UVMS_REFERENCE_FIELDS(FILL_CMD_) UVMS_TELEMETRY_FIELDS(FILL_TLM_)
  uvms_actuators_t act;
  uvms_telemetry_t tel;
  uvms_outputs_to_msgs(&sm, 0, &cmd, &tlm, &act, &tel);
  f = 100;
#define CHECK_MSG_(msg, name)                                                           \
  for (std::size_t e = 0; e < sizeof msg.name / sizeof(double); ++e)                   \
    CHECK(reinterpret_cast<const double *>(&msg.name)[e] == Distinct(f, e));            \
  ++f;
#define CHECK_ACT_(name, dims, unit, doc) CHECK_MSG_(act, name)
#define CHECK_TEL_(name, dims, unit, doc) CHECK_MSG_(tel, name)
  UVMS_ACTUATOR_FIELDS(CHECK_ACT_) UVMS_REFERENCE_FIELDS(CHECK_TEL_) UVMS_TELEMETRY_FIELDS(CHECK_TEL_)
}
