// SPDX-License-Identifier: Apache-2.0
// model_cmd.hpp: the `uvms model` subcommand. Evaluates the controller's arm model (firmware
// library: Newton–Euler of SPEC §4 and the feedforward wrenches of SPEC §7.1) at one state
// read as JSON from stdin, and writes the results as one JSON object on stdout.
//
// The steps are separate functions so that tests can call each one:
//   ParseModelArgs    command line → options            (UsageError)
//   LoadModelParams   SPEC §3 parameters + --config file  (InputError)
//   ParseJsonText     text → JSON value                   (InputError)
//   ParseModelInput   JSON value → firmware inputs        (InputError)
//   ComputeModel      firmware calls                      (InputError on a firmware status)
//   ModelResultToJson results → output JSON
//   RunModelCli       all of the above with streams; returns the exit status
#pragma once

#include <cstddef>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/exit_status.hpp"
#include "uvms/arm_model.h"
#include "uvms/feedforward.h"

namespace uvms::cli {

using uvms::kExitBadInput;  // invalid JSON, bad field, bad config, firmware error
using uvms::kExitOk;
using uvms::kExitUsage;

/** Bad command line: one message line; the caller adds the usage line, exits kExitUsage. */
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/** Bad input, config or parameters: one message line naming the field; exit kExitBadInput. */
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/** Options of `uvms model`. */
struct ModelOptions {
  bool help{};              ///< --help / -h given
  std::string config_path;  ///< --config FILE; empty: SPEC §3 parameters only
};

/** One state, converted to the firmware's types (uvms_real_t). */
struct ModelInput {
  uvms_base_state_t base{};  ///< pose (R0 from the normalised quaternion), twist, accelerations
  uvms_real_t q_rad[UVMS_MAX_JOINTS]{};       ///< θ_1..θ_N [rad]
  uvms_real_t qd_rad_s[UVMS_MAX_JOINTS]{};    ///< θ̇ [rad/s]
  uvms_real_t qdd_rad_s2[UVMS_MAX_JOINTS]{};  ///< θ̈ [rad/s²]
  std::size_t num_joints{};                   ///< N
  uvms_fluid_t fluid{};                       ///< density, flow, gravity, angle of attack
  uvms_real_t payload_kg{};                   ///< point payload at the EE [kg]
};

/** Everything the subcommand computes. */
struct ModelResult {
  std::size_t num_joints{};
  /** Workspace after uvms_arm_rnea at the input accelerations: ee_m, barycenter_m, p_m[0],
   *  com_m[1..N], f_N[1], n_Nm[1], tau_Nm[1..N], drag_N[0]. */
  uvms_arm_data_t rnea{};
  uvms_feedforward_t ff_vehicle{};     ///< uvms_feedforward, UVMS_REF_VEHICLE
  uvms_feedforward_t ff_barycenter{};  ///< uvms_feedforward, UVMS_REF_BARYCENTER
};

/** The text `uvms model --help` prints (input, output and config schemas). */
const std::string &ModelHelpText();

/** The one-line usage summary printed after a usage error. */
const char *ModelUsageLine();

/** Parse the arguments after `model`. @throws UsageError */
ModelOptions ParseModelArgs(const std::vector<std::string> &args);

/**
 * Parse JSON text that must hold exactly one value, with no key twice in any object. @p source
 * names the text in the error ("stdin", a file name). @throws InputError "<source>: invalid
 * JSON: ...", or "<source>: duplicate key "<path>": ..." naming the key's path.
 */
nlohmann::json ParseJsonText(const std::string &text, const std::string &source);

/**
 * Apply a config object (schema in ModelHelpText) to @p params. @p source (the file name)
 * prefixes every error, which names the offending key. Does not validate the physics; see
 * ValidateModelParams. @throws InputError
 */
void ApplyModelConfig(const nlohmann::json &config, const std::string &source,
                      uvms_arm_params_t *params);

/** uvms_arm_model_init on @p params. @throws InputError naming the status (uvms_status_str). */
void ValidateModelParams(const uvms_arm_params_t &params, const std::string &source);

/**
 * SPEC §3 parameters (uvms_arm_params_paper), overridden by the config file at
 * @p config_path unless it is empty, then validated. @throws InputError
 */
uvms_arm_params_t LoadModelParams(const std::string &config_path);

/**
 * Convert the input object (schema in ModelHelpText) for a model with @p num_joints joints.
 * Every field is required; unknown fields, wrong types, wrong lengths, non-finite numbers,
 * negative density or payload and a quaternion of norm < 1e-6 are errors naming the field.
 * @throws InputError; std::invalid_argument if num_joints is not 1..UVMS_MAX_JOINTS
 */
ModelInput ParseModelInput(const nlohmann::json &input, std::size_t num_joints);

/**
 * Run the firmware: uvms_arm_rnea at the input accelerations, then uvms_feedforward under
 * both references. The model is @p params with payload_kg from @p input.
 * @throws InputError on a firmware error status or a non-finite result
 */
ModelResult ComputeModel(const uvms_arm_params_t &params, const ModelInput &input);

/** The output object documented in ModelHelpText (numbers as double). */
nlohmann::ordered_json ModelResultToJson(const ModelResult &result);

/**
 * The whole subcommand. @p args are the arguments after `model`. Writes the result (one line)
 * to @p out, or one error line "uvms model: error: ..." to @p err (plus a usage line for
 * usage errors). @return kExitOk, kExitBadInput or kExitUsage
 */
int RunModelCli(const std::vector<std::string> &args, std::istream &in, std::ostream &out,
                std::ostream &err);

}  // namespace uvms::cli
