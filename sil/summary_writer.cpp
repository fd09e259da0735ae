// summary_writer.cpp: summary.json (summary_writer.hpp).
#include "summary_writer.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "codec.h"

namespace uvms::sil {

const char *FailureName(std::int32_t code) {
  switch (code) {
    case UVMS_RUN_STATUS_T_OK: return "";
    case UVMS_RUN_STATUS_T_CONTROLLER_SILENT: return "controller_silent";
    case UVMS_RUN_STATUS_T_INTEGRATOR_FAILURE: return "integrator_failure";
    case UVMS_RUN_STATUS_T_CONTACT: return "contact";
    case UVMS_RUN_STATUS_T_BAD_INPUT: return "bad_input";
    case UVMS_RUN_STATUS_T_CONFIG_REJECTED: return "config_rejected";
    case UVMS_RUN_STATUS_T_NO_CONTROLLER: return "no_controller";
    default: return "unknown";
  }
}

void WriteSummaryJson(const RunSummary &s, const std::string &path) {
  nlohmann::ordered_json j;
  j["scenario"] = s.scenario;
  j["name"] = s.name;
  j["transport"] = s.transport;
  j["drive"] = s.drive;
  j["status"] = s.status;
  j["failure"] = s.failure;
  j["reason"] = s.reason;
  j["ticks"] = s.ticks;
  j["ticks_planned"] = s.ticks_planned;
  j["missed_ticks"] = s.missed_ticks;
  j["duration_s"] = s.duration_s;
  j["mean_ee_error_m"] = s.mean_ee_error_m;
  j["max_ee_error_m"] = s.max_ee_error_m;
  j["final_ee_error_m"] = s.final_ee_error_m;
  j["thruster_energy_J"] = s.thruster_energy_J;
  j["thruster_energy_signed_J"] = s.thruster_energy_signed_J;
  j["manipulator_energy_J"] = s.manipulator_energy_J;
  j["propulsive_energy_J"] = s.propulsive_energy_J;
  j["max_attitude_error_rad"] = s.max_attitude_error_rad;
  j["min_clearance_m"] = std::isfinite(s.min_clearance_m) ? nlohmann::ordered_json(s.min_clearance_m)
                                                          : nlohmann::ordered_json(nullptr);
  j["final_ee_position_m"] = s.final_ee_position_m;
  j["final_barycenter_m"] = s.final_barycenter_m;
  j["initial_barycenter_m"] = s.initial_barycenter_m;
  j["final_vehicle_position_m"] = s.final_vehicle_position_m;
  j["initial_vehicle_position_m"] = s.initial_vehicle_position_m;
  j["rx_rejected"] = s.rx_rejected;
  j["rx_out_of_sequence"] = s.rx_out_of_sequence;
  j["missing_telemetry"] = s.missing_telemetry;
  j["config_retries"] = s.config_retries;
  j["controller_rx_rejected"] = s.controller_rx_rejected;
  j["controller_rx_out_of_sequence"] = s.controller_rx_out_of_sequence;
  j["controller_rx_unconfigured"] = s.controller_rx_unconfigured;
  j["controller_error_ticks"] = s.controller_error_ticks;
  j["controller_flags_seen"] = s.controller_flags_seen;
  j["alloc_min_rank"] = s.alloc_min_rank;
  j["uncontrollable_axes_seen"] = s.uncontrollable_axes_seen;
  j["saturated_ticks"] = s.saturated_ticks;
  j["sensor_held_ticks"] = s.sensor_held_ticks;
  j["sensor_hold_expired_ticks"] = s.sensor_hold_expired_ticks;
  j["max_force_shortfall_N"] = s.max_force_shortfall_N;
  j["max_moment_shortfall_Nm"] = s.max_moment_shortfall_Nm;
  j["target_instructions_median"] = s.target_instructions_median;
  j["target_instructions_max"] = s.target_instructions_max;
  j["integrator_steps"] = s.integrator_steps;
  j["integrator_rhs_evals"] = s.integrator_rhs_evals;
  const FaultCounters &fc = s.faults;
  j["faults"] = {{"sensors_dropped", fc.sensors_dropped},
                 {"sensors_delayed", fc.sensors_delayed},
                 {"sensors_duplicated", fc.sensors_duplicated},
                 {"sensors_corrupted", fc.sensors_corrupted},
                 {"actuators_dropped", fc.actuators_dropped},
                 {"actuators_delayed", fc.actuators_delayed},
                 {"actuators_duplicated", fc.actuators_duplicated},
                 {"actuators_corrupted", fc.actuators_corrupted},
                 {"sensor_samples_perturbed", fc.sensor_samples_perturbed},
                 {"thruster_fault_ticks", fc.thruster_fault_ticks}};
  nlohmann::ordered_json prov = nlohmann::ordered_json::object();
  for (const auto &kv : s.provenance) prov[kv.first] = kv.second;
  j["provenance"] = prov;
  j["wall_time_s"] = s.wall_time_s;
  j["real_time_factor"] = s.real_time_factor;
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << std::setw(2) << j << '\n';
  if (!f) throw std::runtime_error("writing " + path + " failed");
}

}  // namespace uvms::sil
