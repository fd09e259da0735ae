// SPDX-License-Identifier: Apache-2.0
// Scenario module (sil/scenario/scenario.hpp): defaults against the firmware's and the plant's own paper
// configurations, every shipped paper scenario, error reporting (file, line, key), --set
// overrides, and the mappings that are not one-to-one (density error, automatic θF, unsteady
// flow period and seed, trim ballast).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scenario/config_schema.hpp"
#include "scenario/motor_sets.hpp"
#include "scenario/scenario.hpp"
#include "scenario/toml_bounds.hpp"
#include "cli/scenario_cmd.hpp"
#include "uvms_plant/plant.hpp"

#ifndef UVMS_SCENARIO_DIR
#error "UVMS_SCENARIO_DIR (sil/scenarios/paper) must be defined by the build"
#endif

using uvms::sil::ParseScenario;
using uvms::sil::Scenario;
using uvms::sil::ScenarioError;

namespace {

const char *const kRoman[8] = {"I", "II", "III", "IV", "V", "VI", "VII", "VIII"};

/// The message of the ScenarioError that parsing `text` throws ("" if it does not throw).
std::string ErrorOf(const std::string &text, const std::vector<std::string> &sets = {}) {
  try {
    (void)ParseScenario(text, "x.toml", sets);
  } catch (const ScenarioError &e) {
    return e.what();
  }
  return "";
}

std::string CaseText(const char *roman) { return std::string("[control]\ncase = \"") + roman + "\"\n"; }

// Controller reals: exact in double; within a few ulps in the float build (degrees → radians
// is computed once in float by the firmware, once in double and rounded by the scenario).
#define CHECK_REAL(a, b) CHECK(static_cast<double>(a) == Approx(static_cast<double>(b)).epsilon(1e-6).margin(1e-12))

void CheckSameController(const uvms_ctrl_config_t &a, const uvms_ctrl_config_t &b) {
  // arm
  REQUIRE(a.arm.num_joints == b.arm.num_joints);
  for (size_t i = 0; i < b.arm.num_joints; ++i) {
    const uvms_link_params_t &x = a.arm.link[i], &y = b.arm.link[i];
    CHECK_REAL(x.alpha_rad, y.alpha_rad);
    CHECK_REAL(x.a_m, y.a_m);
    CHECK_REAL(x.d_m, y.d_m);
    CHECK_REAL(x.mass_kg, y.mass_kg);
    for (int k = 0; k < 3; ++k) {
      CHECK_REAL(x.com_m[k], y.com_m[k]);
      CHECK_REAL(x.inertia_kg_m2[k], y.inertia_kg_m2[k]);
    }
    CHECK_REAL(x.diameter_m, y.diameter_m);
    CHECK_REAL(x.drag_coeff, y.drag_coeff);
    CHECK_REAL(x.joint_min_rad, y.joint_min_rad);
    CHECK_REAL(x.joint_max_rad, y.joint_max_rad);
  }
  const uvms_vehicle_params_t &va = a.arm.vehicle, &vb = b.arm.vehicle;
  CHECK_REAL(va.mass_kg, vb.mass_kg);
  CHECK_REAL(va.volume_m3, vb.volume_m3);
  CHECK_REAL(va.frontal_area_m2, vb.frontal_area_m2);
  CHECK_REAL(va.drag_coeff, vb.drag_coeff);
  CHECK_REAL(va.ballast_kg, vb.ballast_kg);
  for (int k = 0; k < 6; ++k) {
    CHECK_REAL(va.linear_damping[k], vb.linear_damping[k]);
    CHECK_REAL(va.quadratic_damping[k], vb.quadratic_damping[k]);
  }
  for (int k = 0; k < 3; ++k) {
    CHECK_REAL(va.inertia_kg_m2[k], vb.inertia_kg_m2[k]);
    CHECK_REAL(va.cob_m[k], vb.cob_m[k]);
    CHECK_REAL(va.base_offset_m[k], vb.base_offset_m[k]);
    CHECK_REAL(va.ballast_offset_m[k], vb.ballast_offset_m[k]);
    CHECK_REAL(a.arm.payload_offset_m[k], b.arm.payload_offset_m[k]);
  }
  CHECK_REAL(a.arm.payload_kg, b.arm.payload_kg);
  for (int k = 0; k < 36; ++k) CHECK_REAL(a.arm.added_mass_coeff[k], b.arm.added_mass_coeff[k]);
  // fluid
  CHECK_REAL(a.fluid.density_kg_m3, b.fluid.density_kg_m3);
  for (int k = 0; k < 3; ++k) {
    CHECK_REAL(a.fluid.flow_m_s[k], b.fluid.flow_m_s[k]);
    CHECK_REAL(a.fluid.gravity_m_s2[k], b.fluid.gravity_m_s2[k]);
  }
  CHECK(a.fluid.angle_of_attack == b.fluid.angle_of_attack);
  // thrusters
  REQUIRE(a.thrusters.num_thrusters == b.thrusters.num_thrusters);
  for (size_t j = 0; j < b.thrusters.num_thrusters; ++j)
    for (int k = 0; k < 3; ++k) {
      CHECK_REAL(a.thrusters.position_m[j][k], b.thrusters.position_m[j][k]);
      CHECK_REAL(a.thrusters.direction[j][k], b.thrusters.direction[j][k]);
    }
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    INFO("thruster " << j);
    const uvms_thruster_params_t &ta = a.thruster[j], &tb = b.thruster[j];
    CHECK_REAL(ta.diameter_m, tb.diameter_m);
    CHECK_REAL(ta.ct1, tb.ct1);
    CHECK_REAL(ta.ct2, tb.ct2);
    CHECK_REAL(ta.cq1, tb.cq1);
    CHECK_REAL(ta.cq2, tb.cq2);
    CHECK_REAL(ta.resistance_ohm, tb.resistance_ohm);
    CHECK_REAL(ta.inductance_H, tb.inductance_H);
    CHECK_REAL(ta.torque_constant_Nm_A, tb.torque_constant_Nm_A);
    CHECK_REAL(ta.viscous_friction_Nm_s, tb.viscous_friction_Nm_s);
    CHECK_REAL(ta.rotor_inertia_kg_m2, tb.rotor_inertia_kg_m2);
    CHECK_REAL(ta.speed_gain_1_s, tb.speed_gain_1_s);
    CHECK_REAL(ta.current_gain_1_s, tb.current_gain_1_s);
    CHECK_REAL(ta.voltage_limit_V, tb.voltage_limit_V);
  }
  // gains, switches, servo, tick
  CHECK_REAL(a.gains.kpf_N_m, b.gains.kpf_N_m);
  CHECK_REAL(a.gains.kdf_N_s_m, b.gains.kdf_N_s_m);
  CHECK_REAL(a.gains.kpn_Nm_rad, b.gains.kpn_Nm_rad);
  CHECK_REAL(a.gains.kdn_Nm_s_rad, b.gains.kdn_Nm_s_rad);
  CHECK(a.switches.attitude_control == b.switches.attitude_control);
  CHECK(a.switches.position_reference == b.switches.position_reference);
  CHECK(a.switches.position_feedforward == b.switches.position_feedforward);
  CHECK(a.switches.position_feedback == b.switches.position_feedback);
  CHECK_REAL(a.joint_kq_1_s2, b.joint_kq_1_s2);
  CHECK_REAL(a.joint_kqd_1_s, b.joint_kqd_1_s);
  CHECK_REAL(a.tick_s, b.tick_s);
  // trajectory
  CHECK(a.traj_mode == b.traj_mode);
  for (int j = 0; j < UVMS_MAX_JOINTS; ++j) {
    CHECK_REAL(a.theta_start_rad[j], b.theta_start_rad[j]);
    CHECK_REAL(a.theta_final_rad[j], b.theta_final_rad[j]);
  }
  CHECK_REAL(a.traj_start_s, b.traj_start_s);
  CHECK_REAL(a.traj_duration_s, b.traj_duration_s);
  CHECK_REAL(a.cart.distance_m, b.cart.distance_m);
  for (int k = 0; k < 3; ++k) CHECK_REAL(a.cart.direction[k], b.cart.direction[k]);
  CHECK_REAL(a.cart.duration_s, b.cart.duration_s);
  CHECK(a.cart.reference == b.cart.reference);
  CHECK_REAL(a.cart.damping_m, b.cart.damping_m);
  CHECK_REAL(a.cart.position_gain_1_s, b.cart.position_gain_1_s);
  CHECK_REAL(a.cart.nullspace_gain_1_s, b.cart.nullspace_gain_1_s);
  CHECK_REAL(a.cart.max_joint_rate_rad_s, b.cart.max_joint_rate_rad_s);
}

void CheckSamePlant(const uvms::plant::PlantParams &a, const uvms::plant::PlantParams &b) {
  REQUIRE(a.links.size() == b.links.size());
  for (size_t i = 0; i < b.links.size(); ++i) {
    const auto &x = a.links[i], &y = b.links[i];
    CHECK(x.alpha_rad == y.alpha_rad);
    CHECK(x.a_m == y.a_m);
    CHECK(x.d_m == y.d_m);
    CHECK(x.mass_kg == y.mass_kg);
    CHECK(x.com_m == y.com_m);
    CHECK(x.inertia_kg_m2 == y.inertia_kg_m2);
    CHECK(x.diameter_m == y.diameter_m);
    CHECK(x.drag_coeff == y.drag_coeff);
  }
  const auto &va = a.vehicle, &vb = b.vehicle;
  CHECK(va.mass_kg == vb.mass_kg);
  CHECK(va.volume_m3 == vb.volume_m3);
  CHECK(va.frontal_area_m2 == vb.frontal_area_m2);
  CHECK(va.drag_coeff == vb.drag_coeff);
  for (int k = 0; k < 6; ++k) {
    CHECK(va.linear_damping[k] == vb.linear_damping[k]);
    CHECK(va.quadratic_damping[k] == vb.quadratic_damping[k]);
  }
  CHECK(va.inertia_kg_m2 == vb.inertia_kg_m2);
  CHECK(va.cob_m == vb.cob_m);
  CHECK(va.base_offset_m == vb.base_offset_m);
  CHECK(va.hull_size_m == vb.hull_size_m);
  CHECK(va.hull_center_m == vb.hull_center_m);
  CHECK(a.payload_kg == b.payload_kg);
  CHECK(a.payload_offset_m == b.payload_offset_m);
  CHECK(a.added_mass_coeff == b.added_mass_coeff);
  REQUIRE(a.thrusters.size() == b.thrusters.size());
  for (size_t j = 0; j < b.thrusters.size(); ++j) {
    CHECK(a.thrusters[j].position_m == b.thrusters[j].position_m);
    CHECK(a.thrusters[j].direction == b.thrusters[j].direction);
  }
  const auto &pa = a.propulsion, &pb = b.propulsion;
  CHECK(pa.diameter_m == pb.diameter_m);
  CHECK(pa.ct1 == pb.ct1);
  CHECK(pa.ct2 == pb.ct2);
  CHECK(pa.cq1 == pb.cq1);
  CHECK(pa.cq2 == pb.cq2);
  CHECK(pa.resistance_ohm == pb.resistance_ohm);
  CHECK(pa.inductance_H == pb.inductance_H);
  CHECK(pa.torque_constant_Nm_A == pb.torque_constant_Nm_A);
  CHECK(pa.viscous_friction_Nm_s == pb.viscous_friction_Nm_s);
  CHECK(pa.rotor_inertia_kg_m2 == pb.rotor_inertia_kg_m2);
  const auto &ea = a.env, &eb = b.env;
  CHECK(ea.density_kg_m3 == eb.density_kg_m3);
  CHECK(ea.steady_flow_m_s == eb.steady_flow_m_s);
  CHECK(ea.unsteady.enabled == eb.unsteady.enabled);
  CHECK(ea.unsteady.amplitude_m_s == eb.unsteady.amplitude_m_s);
  CHECK(ea.unsteady.harmonics == eb.unsteady.harmonics);
  CHECK(ea.unsteady.seed == eb.unsteady.seed);
  CHECK(ea.unsteady.period_s == eb.unsteady.period_s);
  CHECK(ea.gravity_m_s2 == eb.gravity_m_s2);
  CHECK(ea.angle_of_attack == eb.angle_of_attack);
  CHECK(ea.variable_coefficients == eb.variable_coefficients);
  CHECK(ea.coeff_table.size() == eb.coeff_table.size());
  CHECK(ea.trim == eb.trim);
  CHECK(ea.trim_payload_kg == eb.trim_payload_kg);
  CHECK(a.integrator.method == b.integrator.method);
  CHECK(a.integrator.rel_tol == b.integrator.rel_tol);
  CHECK(a.integrator.abs_tol == b.integrator.abs_tol);
  CHECK(a.integrator.max_steps == b.integrator.max_steps);
  CHECK(a.contact.enabled == b.contact.enabled);
  CHECK(a.contact.clearance_m == b.contact.clearance_m);
  CHECK(a.contact.self_collision == b.contact.self_collision);
  CHECK(a.contact.obstacles.size() == b.contact.obstacles.size());
}

std::array<double, 7> ThetaFinalDeg(const Scenario &s) {
  std::array<double, 7> deg{};
  for (int j = 0; j < 7; ++j) deg[j] = static_cast<double>(s.controller.theta_final_rad[j]) * 180.0 / M_PI;
  return deg;
}

}  // namespace

TEST_CASE("DefaultsOfEveryCaseEqualTheFirmwareAndPlantPaperConfigurations", "[scenario]") {
  for (int k = 1; k <= 8; ++k) {
    INFO("case " << kRoman[k - 1]);
    const Scenario s = ParseScenario(CaseText(kRoman[k - 1]), "defaults.toml");
    uvms_ctrl_config_t paper;
    REQUIRE(uvms_ctrl_config_paper(&paper, k) == UVMS_OK);
    CheckSameController(s.controller, paper);
    CheckSamePlant(s.plant, uvms::plant::PaperPlantParams());
    CHECK(s.case_number == k);
    CHECK(s.name == "defaults");
    CHECK(s.duration_s == 60.0);  // SPEC §3.5
    CHECK(s.tick_s == 0.03);
    CHECK(uvms::sil::ScenarioTicks(s) == 2000);  // 60 s / 0.03 s
    CHECK_FALSE(s.density_error);
    const uvms::sil::LinkSettings link_defaults;
    CHECK(s.link.timeout_s == link_defaults.timeout_s);
    CHECK(s.link.max_missed == link_defaults.max_missed);
    CHECK(s.link.realtime_factor == link_defaults.realtime_factor);
    CHECK(s.link.spin_us == link_defaults.spin_us);
    // The plant starts at rest at the origin with the joints at the controller's θI.
    REQUIRE(s.initial.q_rad.size() == 7);
    for (int j = 0; j < 7; ++j) CHECK_REAL(s.initial.q_rad[j], paper.theta_start_rad[j]);
    CHECK(s.initial.r0_m == uvms::plant::Vec3::Zero());
    CHECK(s.initial.attitude.isApprox(Eigen::Quaterniond::Identity()));
  }
}

TEST_CASE("IntegratorDefaultsAreThePlantsOwn", "[scenario]") {
  const Scenario s = ParseScenario(CaseText("IV"), "x.toml");
  const uvms::plant::IntegratorParams d;
  CHECK(s.plant.integrator.method == d.method);
  CHECK(s.plant.integrator.rel_tol == d.rel_tol);
  CHECK(s.plant.integrator.abs_tol == d.abs_tol);
  CHECK(s.plant.integrator.max_steps == d.max_steps);
}

TEST_CASE("EveryShippedPaperScenarioParses", "[scenario]") {
  std::set<std::string> stems;
  for (const auto &entry : std::filesystem::directory_iterator(UVMS_SCENARIO_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    const std::string stem = entry.path().stem().string();
    INFO(entry.path().string());
    Scenario s;
    REQUIRE_NOTHROW(s = uvms::sil::LoadScenario(entry.path().string()));
    stems.insert(stem);
    CHECK(s.name == stem);
    REQUIRE(s.case_number >= 1);
    CHECK(stem == std::string("case_") + kRoman[s.case_number - 1] +
                      (s.density_error ? "_unsteady" : "_stagnant"));
    // SPEC §9.1: (a) stagnant, no density error; (b) unsteady flow plus density error.
    CHECK(s.plant.env.unsteady.enabled == s.density_error);
    CHECK(s.plant.env.density_kg_m3 == 1025.0);
  }
  CHECK(stems.size() == 16);  // 8 cases × 2 conditions
}

TEST_CASE("UnknownKeyFailsNamingKeyAndLine", "[scenario]") {
  const std::string text =
      "[control]\n"           // 1
      "case = \"IV\"\n"       // 2
      "\n"                    // 3
      "[environment]\n"       // 4
      "density_kg_m3 = 1025\n"// 5
      "densty_error = true\n";// 6: the typo
  const std::string msg = ErrorOf(text);
  CHECK_THAT(msg, Catch::Contains("x.toml:6:"));
  CHECK_THAT(msg, Catch::Contains("key \"environment.densty_error\""));
  CHECK_THAT(msg, Catch::Contains("unknown key"));
  CHECK_THAT(msg, Catch::Contains("density_error"));  // the valid keys are listed

  const std::string nested = ErrorOf(CaseText("IV") + "[environment.unsteady_flow]\nenabled = true\nperiod_s = 3\n");
  CHECK_THAT(nested, Catch::Contains("x.toml:5:"));
  CHECK_THAT(nested, Catch::Contains("\"environment.unsteady_flow.period_s\""));

  const std::string section = ErrorOf(CaseText("IV") + "[bogus]\nx = 1\n");
  CHECK_THAT(section, Catch::Contains("x.toml:3:"));
  CHECK_THAT(section, Catch::Contains("key \"bogus\""));

  const std::string obstacle =
      ErrorOf(CaseText("IV") + "[[contact.obstacle]]\nradius_m = 0.4\ncolour = \"red\"\n");
  CHECK_THAT(obstacle, Catch::Contains("x.toml:5:"));
  CHECK_THAT(obstacle, Catch::Contains("\"contact.obstacle[0].colour\""));

  // The scene message holds at most kMaxObstacles obstacles with names of kMaxObstacleName bytes.
  std::string many = CaseText("IV");
  for (size_t k = 0; k < uvms::sil::kMaxObstacles; ++k)
    many += "[[contact.obstacle]]\nname = \"" + std::string(uvms::sil::kMaxObstacleName, 'n') + "\"\n";
  CHECK(ErrorOf(many).empty());
  CHECK_THAT(ErrorOf(many + "[[contact.obstacle]]\n"),
             Catch::Contains("more than " + std::to_string(uvms::sil::kMaxObstacles) + " obstacles"));
  const std::string long_name = ErrorOf(CaseText("IV") + "[[contact.obstacle]]\nname = \"" +
                                        std::string(uvms::sil::kMaxObstacleName + 1, 'n') + "\"\n");
  CHECK_THAT(long_name, Catch::Contains("x.toml:4:"));
  CHECK_THAT(long_name, Catch::Contains("obstacle name of 49 bytes"));

  const std::string faults =
      ErrorOf(CaseText("IV") + "[faults.link]\ndrop_rate = 0.1\nloss_rate = 0.2\n");
  CHECK_THAT(faults, Catch::Contains("x.toml:5:"));
  CHECK_THAT(faults, Catch::Contains("\"faults.link.loss_rate\""));
}

TEST_CASE("FaultSectionsParseAndRejectNonsense", "[scenario]") {
  const Scenario s = ParseScenario(CaseText("VII") +
                                       "[[faults.thruster]]\nthruster = 5\nmode = \"off\"\nstart_s = 10\n"
                                       "[[faults.thruster]]\nthruster = 2\nmode = \"efficiency\"\n"
                                       "efficiency = 0.3\nreported = false\n"
                                       "[faults.sensors]\nposition_noise_m = 0.001\njoint_position_bias_rad = 0.01\n"
                                       "[faults.link]\ndrop_rate = 0.02\ncorrupt_rate = 0.01\nactuators = false\n",
                                   "x.toml");
  REQUIRE(s.faults.thrusters.size() == 2);
  CHECK(s.faults.thrusters[0].thruster == 5);
  CHECK(s.faults.thrusters[0].mode == uvms::sil::ThrusterFault::Mode::kOff);
  CHECK(s.faults.thrusters[0].start_s == 10.0);
  CHECK(s.faults.thrusters[1].efficiency == 0.3);
  CHECK_FALSE(s.faults.thrusters[1].reported);
  CHECK(s.faults.sensors.position_m.std == 0.001);
  CHECK(s.faults.sensors.joint_position_rad.bias == 0.01);
  CHECK(s.faults.sensors.any());
  CHECK(s.faults.link.drop_rate == 0.02);
  CHECK_FALSE(s.faults.link.actuators);
  CHECK(s.faults.link.sensors);
  // No [faults]: nothing injected.
  const Scenario clean = ParseScenario(CaseText("VII"), "x.toml");
  CHECK(clean.faults.thrusters.empty());
  CHECK_FALSE(clean.faults.sensors.any());
  CHECK_FALSE(clean.faults.link.any());

  CHECK_THAT(ErrorOf(CaseText("IV") + "[[faults.thruster]]\nthruster = 9\n"),
             Catch::Contains("\"faults.thruster[0].thruster\"") && Catch::Contains("1..8"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[[faults.thruster]]\nmode = \"off\"\n"),
             Catch::Contains("faults.thruster[0].thruster") && Catch::Contains("missing"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[[faults.thruster]]\nthruster = 1\nmode = \"melted\"\n"),
             Catch::Contains("\"melted\""));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[[faults.thruster]]\nthruster = 1\nmode = \"off\"\nefficiency = 0.5\n"),
             Catch::Contains("only for mode = \"efficiency\""));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[[faults.thruster]]\nthruster = 1\nmode = \"efficiency\"\nefficiency = 1.2\n"),
             Catch::Contains("[0, 1)"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[faults.link]\ndrop_rate = 0.7\ndelay_rate = 0.6\n"),
             Catch::Contains("add up to"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[faults.sensors]\nposition_noise_m = -1\n"),
             Catch::Contains("faults.sensors.position_noise_m"));
}

TEST_CASE("WrongTypeFails", "[scenario]") {
  const std::string tick = ErrorOf(CaseText("IV") + "[run]\ntick_s = \"fast\"\n");
  CHECK_THAT(tick, Catch::Contains("x.toml:4: key \"run.tick_s\": expected a number, got a string"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[run]\nseed = 1.5\n"), Catch::Contains("\"run.seed\": expected an integer"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[environment]\ndensity_error = 1\n"),
             Catch::Contains("\"environment.density_error\": expected a boolean"));
  CHECK_THAT(ErrorOf("[control]\ncase = 7.5\n"), Catch::Contains("\"control.case\""));
  CHECK_THAT(ErrorOf("run = 3\n" + CaseText("IV")), Catch::Contains("\"run\": expected a table"));
}

TEST_CASE("OutOfRangeFails", "[scenario]") {
  CHECK_THAT(ErrorOf(CaseText("IV") + "[payload]\nmass_kg = -1\n"),
             Catch::Contains("x.toml:4: key \"payload.mass_kg\": got -1 (expected a number >= 0)"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[run]\ntick_s = 0\n"), Catch::Contains("\"run.tick_s\": got 0"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[run]\nduration_s = 0.01\n"),
             Catch::Contains("\"run.duration_s\": duration_s 0.01 s is shorter than tick_s"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[run]\nduration_s = nan\n"),
             Catch::Contains("expected a finite number"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[trajectory]\ntheta_start_deg = [0, 0, 0, 0, 0, 0]\n"),
             Catch::Contains("\"trajectory.theta_start_deg\": got 6 elements (expected an array of 7"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[trajectory]\nmode = \"spline\"\n"),
             Catch::Contains("expected one of: joint_cycloid, cartesian_line, hold"));
  CHECK_THAT(ErrorOf("[control]\ncase = \"IX\"\n"), Catch::Contains("expected one of I..VIII"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[environment]\ngravity_m_s2 = \"mars\"\n"),
             Catch::Contains("\"environment.gravity_m_s2\""));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[link]\nspin_us = -1\n"),
             Catch::Contains("x.toml:4: key \"link.spin_us\": got -1 (expected an integer in 0..100000)"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[link]\nspin_us = 100001\n"), Catch::Contains("\"link.spin_us\": got 100001"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[link]\nspin_us = 0.5\n"), Catch::Contains("\"link.spin_us\": expected an integer"));
}

TEST_CASE("ContradictionsFail", "[scenario]") {
  // Case VII holds the barycenter: naming it and the vehicle reference contradicts.
  const std::string msg = ErrorOf("[control]\ncase = \"VII\"\nposition_reference = \"vehicle\"\n");
  CHECK_THAT(msg, Catch::Contains("x.toml:3: key \"control.position_reference\""));
  CHECK_THAT(msg, Catch::Contains("contradicts"));
  // A switch that agrees with the case is accepted.
  CHECK(ErrorOf("[control]\ncase = \"VII\"\nposition_reference = \"barycenter\"\n").empty());
  // Density error means the model uses 1000 kg/m³: another model density contradicts it.
  CHECK_THAT(ErrorOf(CaseText("IV") + "[environment]\ndensity_error = true\nmodel_density_kg_m3 = 990\n"),
             Catch::Contains("\"environment.model_density_kg_m3\": got 990, which contradicts"));
  // No case: all four switches are needed; none at all names the case key.
  CHECK_THAT(ErrorOf("[control]\nattitude = true\n"), Catch::Contains("\"control.position_reference\": missing"));
  CHECK_THAT(ErrorOf(""), Catch::Contains("\"control.case\": missing"));
}

TEST_CASE("ExplicitSwitchesWithoutCase", "[scenario]") {
  const Scenario s = ParseScenario(
      "[control]\nattitude = true\nposition_reference = \"barycenter\"\n"
      "position_feedforward = false\nposition_feedback = true\n",
      "x.toml");
  uvms_switches_t viii;
  REQUIRE(uvms_switches_case(8, &viii) == UVMS_OK);
  CHECK(s.case_number == 0);
  CHECK(s.controller.switches.attitude_control == viii.attitude_control);
  CHECK(s.controller.switches.position_reference == viii.position_reference);
  CHECK(s.controller.switches.position_feedforward == viii.position_feedforward);
  CHECK(s.controller.switches.position_feedback == viii.position_feedback);
  CHECK(s.controller.cart.reference == UVMS_REF_BARYCENTER);
}

TEST_CASE("SetOverridesApplyAndUnknownSetKeysFail", "[scenario]") {
  const Scenario s = ParseScenario(CaseText("IV") + "[run]\nduration_s = 30\n", "x.toml",
                                   {"run.duration_s=120", "control.case = \"VII\"",
                                    "environment.unsteady_flow.enabled=true", "payload.mass_kg=5"});
  CHECK(s.duration_s == 120.0);
  CHECK(s.case_number == 7);
  CHECK(s.plant.env.unsteady.enabled);
  CHECK(s.plant.payload_kg == 5.0);
  CHECK(static_cast<double>(s.controller.arm.payload_kg) == 5.0);
  CHECK(s.overrides.size() == 4);

  const std::string unknown = ErrorOf(CaseText("IV"), {"environment.densty=1000"});
  CHECK_THAT(unknown, Catch::Contains("--set environment.densty=1000"));
  CHECK_THAT(unknown, Catch::Contains("key \"environment.densty\": unknown key"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"nosuch.key=1"}), Catch::Contains("key \"nosuch\""));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.tick_s=fast"}), Catch::Contains("the value is not TOML"));
  // A bare word is a string without its quotes: the error shows the quoted fix.
  CHECK_THAT(ErrorOf(CaseText("IV"), {"control.case=IX"}),
             Catch::Contains("key \"control.case\": the value is not TOML: a string needs quotes, "
                             "as in --set 'control.case=\"IX\"'"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.tick_s=[1, "}), Catch::Contains("the value is not TOML ("));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.tick_s"}), Catch::Contains("expected section.key=value"));
  // A bad value set on the command line is placed at the --set, not at a file line.
  CHECK_THAT(ErrorOf(CaseText("IV"), {"payload.mass_kg=-2"}),
             Catch::Contains("--set payload.mass_kg=-2: key \"payload.mass_kg\": got -2"));
}

TEST_CASE("VerdictLimitsComeFromTheVerdictSectionAndOverrides", "[scenario]") {
  // Absent: the harness's own defaults (VerdictLimits, the one place they are written).
  const uvms::sil::VerdictLimits defaults;
  const Scenario plain = ParseScenario(CaseText("IV"), "x.toml");
  CHECK(plain.verdict.max_error_tick_share == defaults.max_error_tick_share);
  CHECK(plain.verdict.max_attitude_error_rad == defaults.max_attitude_error_rad);
  CHECK(plain.verdict.max_vehicle_excursion_m == defaults.max_vehicle_excursion_m);
  CHECK(plain.verdict.max_ee_error_m == defaults.max_ee_error_m);
  // A [verdict] table sets all four; an override (what campaigns and `uvms run --limit` give)
  // wins over the file.
  const Scenario s = ParseScenario(CaseText("IV") +
                                       "[verdict]\nmax_error_tick_share = 0.25\nmax_attitude_error_rad = 0.125\n"
                                       "max_vehicle_excursion_m = 2.5\nmax_ee_error_m = 0.75\n",
                                   "x.toml", {"verdict.max_ee_error_m=3", "verdict.max_error_tick_share=1"});
  CHECK(s.verdict.max_error_tick_share == 1.0);
  CHECK(s.verdict.max_attitude_error_rad == 0.125);
  CHECK(s.verdict.max_vehicle_excursion_m == 2.5);
  CHECK(s.verdict.max_ee_error_m == 3.0);
  CHECK(ParseScenario(CaseText("IV"), "x.toml", {"verdict.max_attitude_error_rad=0"}).verdict.max_attitude_error_rad == 0.0);

  // Refused, naming the key: negative, not finite, a share above 1, an unknown limit.
  CHECK_THAT(ErrorOf(CaseText("IV") + "[verdict]\nmax_ee_error_m = -1\n"),
             Catch::Contains("x.toml:4: key \"verdict.max_ee_error_m\": got -1 (expected a number >= 0)"));
  for (const char *key : {"verdict.max_error_tick_share", "verdict.max_attitude_error_rad",
                          "verdict.max_vehicle_excursion_m", "verdict.max_ee_error_m"}) {
    INFO(key);
    for (const char *bad : {"-0.5", "nan", "inf"})
      CHECK_THAT(ErrorOf(CaseText("IV"), {std::string(key) + "=" + bad}),
                 Catch::Contains(std::string("--set ") + key + "=" + bad + ": key \"" + key + "\": got"));
  }
  CHECK_THAT(ErrorOf(CaseText("IV"), {"verdict.max_attitude_error_rad=nan"}),
             Catch::Contains("expected a finite number"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"verdict.max_error_tick_share=1.5"}),
             Catch::Contains("key \"verdict.max_error_tick_share\": got 1.5 (expected a probability in [0, 1])"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"verdict.max_speed=1"}),
             Catch::Contains("key \"verdict.max_speed\": unknown key"));
}

TEST_CASE("DensityErrorGivesModel1000AndPlant1025", "[scenario]") {
  const Scenario s = ParseScenario(CaseText("VII") + "[environment]\ndensity_error = true\n", "x.toml");
  CHECK(s.density_error);
  CHECK(static_cast<double>(s.controller.fluid.density_kg_m3) == 1000.0);  // SPEC §6.2
  CHECK(s.plant.env.density_kg_m3 == 1025.0);                              // SPEC §3.2
  const Scenario none = ParseScenario(CaseText("VII"), "x.toml");
  CHECK(static_cast<double>(none.controller.fluid.density_kg_m3) == 1025.0);
  const Scenario explicit_model =
      ParseScenario(CaseText("VII") + "[environment]\nmodel_density_kg_m3 = 1010\n", "x.toml");
  CHECK(static_cast<double>(explicit_model.controller.fluid.density_kg_m3) == 1010.0);
  CHECK(explicit_model.density_error);
}

TEST_CASE("AutoThetaFinalSelectsTheSpecColumn", "[scenario]") {
  uvms_ctrl_config_t case4, case7;
  REQUIRE(uvms_ctrl_config_paper(&case4, 4) == UVMS_OK);
  REQUIRE(uvms_ctrl_config_paper(&case7, 7) == UVMS_OK);
  for (double payload : {0.0, 1.0, 2.0, 5.0, 10.0}) {
    INFO("payload " << payload << " kg");
    const std::string pl = "[payload]\nmass_kg = " + std::to_string(payload) + "\n";
    // Vehicle reference: always the "Veh." column, whatever the payload.
    const Scenario veh = ParseScenario(CaseText("IV") + pl, "x.toml");
    for (int j = 0; j < 7; ++j) CHECK_REAL(veh.controller.theta_final_rad[j], case4.theta_final_rad[j]);
    // Barycenter reference: the payload's column.
    const Scenario bary = ParseScenario(CaseText("VII") + pl, "x.toml");
    std::array<double, 7> column{};
    REQUIRE(uvms::sil::PaperThetaFinalDeg(UVMS_REF_BARYCENTER, payload, &column));
    const auto got = ThetaFinalDeg(bary);
    for (int j = 0; j < 7; ++j) CHECK(got[j] == Approx(column[j]).epsilon(1e-6));
    if (payload == 10.0)
      for (int j = 0; j < 7; ++j) CHECK_REAL(bary.controller.theta_final_rad[j], case7.theta_final_rad[j]);
  }
  // Spot checks against SPEC §8's table: joint 4 of the 0 kg and 5 kg barycenter columns.
  const auto b0 = ThetaFinalDeg(ParseScenario(CaseText("VIII") + "[payload]\nmass_kg = 0\n", "x.toml"));
  CHECK(b0[3] == Approx(102.87));
  const auto b5 = ThetaFinalDeg(ParseScenario(CaseText("II") + "[payload]\nmass_kg = 5\n", "x.toml"));
  CHECK(b5[3] == Approx(96.30));
  // A payload outside the table with the barycenter reference needs explicit angles.
  CHECK_THAT(ErrorOf(CaseText("VII") + "[payload]\nmass_kg = 3\n"), Catch::Contains("theta_final_deg"));
  const Scenario expl = ParseScenario(
      CaseText("VII") + "[payload]\nmass_kg = 3\n[trajectory]\ntheta_final_deg = [170, -76, 265, 100, 192, 89, 96]\n",
      "x.toml");
  CHECK(ThetaFinalDeg(expl)[0] == Approx(170.0));
  // ... but not for a vehicle-reference case, whose column does not depend on the payload.
  CHECK(ErrorOf(CaseText("IV") + "[payload]\nmass_kg = 3\n").empty());
}

TEST_CASE("ThetaFinalReadingsSameMotionAndPrinted", "[scenario]") {
  // SPEC §8's two readings: "vehicle" (same motion) drives every case to the "Veh." column;
  // "printed" is "auto" (same task) with the paper's printed 10 kg joint 1.
  std::array<double, 7> veh{}, bary10{};
  REQUIRE(uvms::sil::PaperThetaFinalDeg(UVMS_REF_VEHICLE, 10.0, &veh));
  REQUIRE(uvms::sil::PaperThetaFinalDeg(UVMS_REF_BARYCENTER, 10.0, &bary10));
  const std::string motion = "[trajectory]\ntheta_final_deg = \"vehicle\"\n";
  const std::string printed = "[trajectory]\ntheta_final_deg = \"printed\"\n";
  for (const char *c : {"I", "II", "III", "IV", "V", "VI", "VII", "VIII"}) {
    INFO("case " << c);
    const auto got = ThetaFinalDeg(ParseScenario(CaseText(c) + motion, "x.toml"));
    for (int j = 0; j < 7; ++j) CHECK(got[j] == Approx(veh[j]).epsilon(1e-6));
  }
  // Same motion needs no barycenter column, so any payload works.
  CHECK(ErrorOf(CaseText("VII") + "[payload]\nmass_kg = 3\n" + motion).empty());
  // "printed": only joint 1 of the 10 kg barycenter column differs from "auto".
  const auto p10 = ThetaFinalDeg(ParseScenario(CaseText("VII") + printed, "x.toml"));
  CHECK(p10[0] == Approx(UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG).epsilon(1e-6));
  CHECK(bary10[0] == Approx(173.19).epsilon(1e-6));
  for (int j = 1; j < 7; ++j) CHECK(p10[j] == Approx(bary10[j]).epsilon(1e-6));
  const auto p5 = ThetaFinalDeg(ParseScenario(CaseText("VII") + "[payload]\nmass_kg = 5\n" + printed,
                                              "x.toml"));
  std::array<double, 7> bary5{};
  REQUIRE(uvms::sil::PaperThetaFinalDeg(UVMS_REF_BARYCENTER, 5.0, &bary5));
  for (int j = 0; j < 7; ++j) CHECK(p5[j] == Approx(bary5[j]).epsilon(1e-6));
  const auto p4 = ThetaFinalDeg(ParseScenario(CaseText("IV") + printed, "x.toml"));
  for (int j = 0; j < 7; ++j) CHECK(p4[j] == Approx(veh[j]).epsilon(1e-6));
  // Anything else is named in the error.
  CHECK_THAT(ErrorOf(CaseText("VII") + "[trajectory]\ntheta_final_deg = \"veh\"\n"),
             Catch::Contains("\"vehicle\""));
}

TEST_CASE("UnsteadyFlowPeriodIsRunDurationAndSeedIsRunSeed", "[scenario]") {
  const Scenario s = ParseScenario(CaseText("IV") +
                                       "[run]\nduration_s = 90\nseed = 42\n"
                                       "[environment]\nsteady_flow_m_s = [0.01, 0, 0]\n"
                                       "[environment.unsteady_flow]\nenabled = true\n",
                                   "x.toml");
  CHECK(s.plant.env.unsteady.enabled);
  CHECK(s.plant.env.unsteady.period_s == 90.0);  // SPEC §6.1: tF = run duration
  CHECK(s.plant.env.unsteady.seed == 42u);
  const uvms::plant::UnsteadyFlowParams d;
  CHECK(s.plant.env.unsteady.amplitude_m_s == d.amplitude_m_s);
  CHECK(s.plant.env.unsteady.harmonics == d.harmonics);
  // Both see v∞0; only the plant sees the unsteady part.
  CHECK(s.plant.env.steady_flow_m_s == uvms::plant::Vec3(0.01, 0, 0));
  CHECK(static_cast<double>(s.controller.fluid.flow_m_s[0]) == Approx(0.01));
  // The trajectory keeps its own duration (tF = 60 s) when the run is longer.
  CHECK(static_cast<double>(s.controller.traj_duration_s) == 60.0);
}

TEST_CASE("TickAndTrajectorySettingsReachTheController", "[scenario]") {
  const Scenario s = ParseScenario(CaseText("VII") +
                                       "[run]\ntick_s = 0.01\nduration_s = 20\n"
                                       "[trajectory]\nmode = \"cartesian_line\"\nduration_s = 15\nstart_s = 1\n"
                                       "[trajectory.cartesian]\ndistance_m = 0.2\ndirection = [-1, 0, 0]\n",
                                   "x.toml");
  CHECK(static_cast<double>(s.controller.tick_s) == Approx(0.01));
  CHECK(uvms::sil::ScenarioTicks(s) == 2000);
  CHECK(s.controller.traj_mode == UVMS_TRAJ_CARTESIAN_LINE);
  CHECK(static_cast<double>(s.controller.cart.duration_s) == 15.0);
  CHECK(static_cast<double>(s.controller.traj_start_s) == 1.0);
  CHECK(s.controller.cart.reference == UVMS_REF_BARYCENTER);  // set from the case
  CHECK(static_cast<double>(s.controller.cart.direction[0]) == -1.0);
}

TEST_CASE("GravityTrimsByDefaultWithThePlantsBallast", "[scenario]") {
  const Scenario earth = ParseScenario(CaseText("IV") + "[environment]\ngravity_m_s2 = \"earth\"\n", "x.toml");
  CHECK(earth.plant.env.trim);  // SPEC §6.3
  CHECK(earth.plant.env.gravity_m_s2 == uvms::plant::GravityEarth());
  const uvms::plant::Plant plant(earth.plant);
  CHECK(static_cast<double>(earth.controller.arm.vehicle.ballast_kg) == Approx(plant.ballast_kg()));
  for (int k = 0; k < 3; ++k)  // the same point (SPEC §6.3), the default h = 0.05 m
    CHECK(static_cast<double>(earth.controller.arm.vehicle.ballast_offset_m[k]) ==
          Approx(plant.ballast().offset_m[k]).margin(1e-12));
  CHECK(plant.ballast().offset_m.norm() > 0.1);  // not at the CoB (the CoM here)
  // h and a trim error: h reaches both models, the error only the plant's ballast.
  const Scenario err = ParseScenario(CaseText("IV") +
                                         "[environment]\ngravity_m_s2 = \"europa\"\n"
                                         "metacentric_height_m = 0.02\nballast_error_m = [0.1, 0, 0]\n",
                                     "x.toml");
  CHECK(err.plant.env.metacentric_height_m == 0.02);
  const uvms::plant::Plant displaced(err.plant);
  const uvms::plant::Vec3 fw_point(err.controller.arm.vehicle.ballast_offset_m[0],
                                   err.controller.arm.vehicle.ballast_offset_m[1],
                                   err.controller.arm.vehicle.ballast_offset_m[2]);
  CHECK((displaced.ballast().offset_m - fw_point - uvms::plant::Vec3(0.1, 0, 0)).norm() < 1e-6);
  CHECK((fw_point - plant.ballast().offset_m).z() > 0.1);  // a smaller h: a higher ballast
  CHECK(static_cast<double>(earth.controller.fluid.gravity_m_s2[2]) == Approx(earth.plant.env.gravity_m_s2[2]));
  const Scenario off = ParseScenario(
      CaseText("IV") + "[environment]\ngravity_m_s2 = [0, 0, -1.315]\ntrim = false\n", "x.toml");
  CHECK_FALSE(off.plant.env.trim);
  CHECK(static_cast<double>(off.controller.arm.vehicle.ballast_kg) == 0.0);
  CHECK(static_cast<double>(off.controller.arm.vehicle.ballast_offset_m[2]) == 0.0);
  CHECK_FALSE(ParseScenario(CaseText("IV"), "x.toml").plant.env.trim);
}

TEST_CASE("ConfigurationsTheLibrariesRejectAreReported", "[scenario]") {
  // limits.quat_norm_tol above 0.5: the key's range admits it, only uvms_ctrl_init refuses it,
  // and the error names the section of the part it refused.
  const std::string msg = ErrorOf(CaseText("IV") + "[limits]\nquat_norm_tol = 0.6\n");
  CHECK_THAT(msg, Catch::Contains("x.toml:3: key \"limits\": the controller rejected its configuration: part "
                                  "\"limits\" (uvms_ctrl_init: UVMS_ERR_RANGE"));
  // θI of joint 1 = 400° is outside the paper arm's joint limits (±360°): named by the reader.
  CHECK_THAT(ErrorOf(CaseText("IV") + "[trajectory]\ntheta_start_deg = [400, 90, 180, 180, 0, 0, 0]\n"),
             Catch::Contains("key \"trajectory.theta_start_deg\": joint 1 at 400° is outside its limits"));
}

TEST_CASE("SyntaxErrorsNameFileAndLine", "[scenario]") {
  const std::string msg = ErrorOf("[control]\ncase = \"IV\"\n[run\n");
  CHECK_THAT(msg, Catch::Contains("x.toml:3: TOML syntax error"));
  CHECK_THROWS_AS(uvms::sil::LoadScenario("/nonexistent/file.toml"), ScenarioError);
}

TEST_CASE("CliExitCodes", "[scenario]") {
  std::ostringstream out, err;
  CHECK(uvms::sil::RunScenarioCli({}, out, err) == 2);
  CHECK(uvms::sil::RunScenarioCli({"check"}, out, err) == 2);
  CHECK(uvms::sil::RunScenarioCli({"check", "a", "b"}, out, err) == 2);
  CHECK(uvms::sil::RunScenarioCli({"check", "--bogus", "a"}, out, err) == 2);
  CHECK(uvms::sil::RunScenarioCli({"--help"}, out, err) == 0);
  const std::string good = std::string(UVMS_SCENARIO_DIR) + "/case_VII_unsteady.toml";
  std::ostringstream out2, err2;
  CHECK(uvms::sil::RunScenarioCli({"check", good, "--set", "run.duration_s=30"}, out2, err2) == 0);
  CHECK_THAT(out2.str(), Catch::Contains("case_VII_unsteady: case VII"));
  CHECK_THAT(out2.str(), Catch::Contains("1000 ticks"));
  std::ostringstream out3, err3;
  CHECK(uvms::sil::RunScenarioCli({"check", good, "--set=run.bogus=1"}, out3, err3) == 1);
  CHECK_THAT(err3.str(), Catch::Contains("run.bogus"));
}

TEST_CASE("AllocationKeyTakesMinPowerAndRefusesTheRetiredNameNamingItsReplacement", "[scenario]") {
  const Scenario def = ParseScenario(CaseText("VII"), "x.toml");
  CHECK(def.controller.alloc_mode == UVMS_ALLOC_PSEUDOINVERSE);
  const Scenario mp =
      ParseScenario(CaseText("VII") + "[thrusters]\nallocation = \"min_power\"\n", "x.toml");
  CHECK(mp.controller.alloc_mode == UVMS_ALLOC_MIN_POWER);
  // The retired name: an error that names it, its retired value, why, and the replacement.
  const std::string e = ErrorOf(CaseText("VII") + "[thrusters]\nallocation = \"min_abs_thrust\"\n");
  CHECK_THAT(e, Catch::Contains("key \"thrusters.allocation\": \"min_abs_thrust\" (value 1) is retired"));
  CHECK_THAT(e, Catch::Contains("optimal vertex jumps between ticks"));
  CHECK_THAT(e, Catch::Contains("use \"min_power\""));
  // Any other unknown name: the usual list of choices.
  CHECK_THAT(ErrorOf(CaseText("VII") + "[thrusters]\nallocation = \"lp\"\n"),
             Catch::Contains("got \"lp\" (expected \"pseudoinverse\" or \"min_power\")"));
}

TEST_CASE("DriveKeySetsControllerAndPlantAndStuckValuesBelongToTheirDrive", "[scenario]") {
  // SPEC §5: the current drive is the default; the key sets both sides alike.
  const Scenario def = ParseScenario(CaseText("VII"), "x.toml");
  CHECK(def.controller.drive == UVMS_DRIVE_CURRENT);
  CHECK(def.plant.propulsion.drive == uvms::plant::MotorDrive::kCurrent);
  const Scenario v = ParseScenario(CaseText("VII") + "[thrusters]\ndrive = \"voltage\"\n", "x.toml");
  CHECK(v.controller.drive == UVMS_DRIVE_VOLTAGE);
  CHECK(v.plant.propulsion.drive == uvms::plant::MotorDrive::kVoltage);
  CHECK_THAT(ErrorOf(CaseText("IV") + "[thrusters]\ndrive = \"pwm\"\n"),
             Catch::Contains("key \"thrusters.drive\": got \"pwm\" (expected \"current\" or \"voltage\")"));
  const std::string stuck = "[[faults.thruster]]\nthruster = 1\nmode = \"stuck\"\n";
  CHECK_THAT(ErrorOf(CaseText("IV") + stuck + "stuck_voltage_V = -5\n"),
             Catch::Contains("only with thrusters.drive = \"voltage\""));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[thrusters]\ndrive = \"voltage\"\n" + stuck + "stuck_current_A = 1\n"),
             Catch::Contains("only with thrusters.drive = \"current\""));
  const Scenario sc = ParseScenario(CaseText("IV") + stuck + "stuck_current_A = -0.1\n", "x.toml");
  REQUIRE(sc.faults.thrusters.size() == 1);
  CHECK(sc.faults.thrusters[0].stuck_current_A == -0.1);
}

TEST_CASE("ArmMassScaleAndHydrodynamicsReachBothModels", "[scenario]") {
  // SPEC §9 item 8's analytic model has a massless, dragless arm: [arm] mass_scale = 0 and
  // hydrodynamics = false give exactly that to the controller's model and to the plant.
  const Scenario paper = ParseScenario(CaseText("IV"), "x.toml");
  const Scenario half = ParseScenario(CaseText("IV") + "[arm]\nmass_scale = 0.5\n", "x.toml");
  const Scenario none =
      ParseScenario(CaseText("IV") + "[arm]\nmass_scale = 0.0\nhydrodynamics = false\n", "x.toml");
  for (size_t i = 0; i < 7; ++i) {
    INFO("link " << i + 1);
    CHECK(half.plant.links[i].mass_kg == 0.5 * paper.plant.links[i].mass_kg);
    CHECK(half.plant.links[i].inertia_kg_m2 == 0.5 * paper.plant.links[i].inertia_kg_m2);
    // the controller's copy in its own precision (float in the host-float build)
    CHECK(half.controller.arm.link[i].mass_kg == static_cast<uvms_real_t>(half.plant.links[i].mass_kg));
    CHECK(half.plant.links[i].diameter_m == paper.plant.links[i].diameter_m);
    CHECK(none.plant.links[i].mass_kg == 0.0);
    CHECK(static_cast<double>(none.controller.arm.link[i].mass_kg) == 0.0);
    CHECK(static_cast<double>(none.controller.arm.link[i].inertia_kg_m2[1]) == 0.0);
    CHECK(none.plant.links[i].diameter_m == 0.0);
    CHECK(static_cast<double>(none.controller.arm.link[i].diameter_m) == 0.0);
  }
  CHECK(none.plant.payload_kg == paper.plant.payload_kg);  // the payload stays
  CHECK_THAT(ErrorOf(CaseText("IV") + "[arm]\nmass_scale = -1\n"),
             Catch::Contains("key \"arm.mass_scale\": got -1 (expected a number >= 0)"));
}

// ---- issue 15 item 5: input bounds; item 6: paths ---------------------------------------------

TEST_CASE("InputBoundsAreCheckedBeforeParsing", "[scenario][bounds]") {
  // A 50,000-part dotted key overflowed toml++'s stack (SIGSEGV) before the raw-text check.
  std::string dotted = "a";
  for (int i = 0; i < 50000; ++i) dotted += ".a";
  CHECK_THAT(ErrorOf(dotted + " = 1\n"), Catch::Contains("x.toml:1: a dotted key of more than 32 parts"));
  CHECK_THAT(ErrorOf("[" + dotted + "]\n"), Catch::Contains("dotted key"));
  CHECK_THAT(ErrorOf("a = " + std::string(100000, '[') + std::string(100000, ']') + "\n"),
             Catch::Contains("x.toml:1: nesting deeper than 32"));
  CHECK_THAT(ErrorOf("a = " + std::string(1000, '{')), Catch::Contains("nesting deeper"));
  CHECK_THAT(ErrorOf("# " + std::string(2u << 20, 'x') + "\n"), Catch::Contains("bytes (expected at most 1048576"));
  CHECK_THAT(ErrorOf(std::string("a = 1\0", 6)), Catch::Contains("NUL byte"));
  // Dots inside strings and comments, and numbers, are no dotted keys.
  CHECK_THAT(ErrorOf(CaseText("IV") + "# " + dotted + "\n"), !Catch::Contains("dotted"));
  CHECK(ErrorOf(CaseText("IV") + "[run]\nname = \"" + dotted.substr(0, 150) + "\"\n").empty());
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.seed=[" + std::string(100, '[') + "]"}), Catch::Contains("nesting deeper"));
}

TEST_CASE("NonRegularFilesAreRefused", "[scenario][bounds]") {
  CHECK_THROWS_WITH(uvms::sil::LoadScenario("/tmp"), Catch::Contains("not a regular file (a directory"));
  CHECK_THROWS_WITH(uvms::sil::LoadScenario("/dev/urandom"), Catch::Contains("not a regular file (a device"));
}

TEST_CASE("BoundedFilesAreReadWholeUpToTheBound", "[scenario][bounds]") {
  // The reader reads in chunks, the first sized by the file's size at stat(): every size around
  // the chunk and the bound is read byte for byte, and one byte past the bound is refused.
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("uvms-test-bounded-" + std::to_string(::getpid()) + ".toml"))
                               .string();
  const std::size_t kBound = uvms::sil::kMaxTomlBytes;
  for (const std::size_t size : {std::size_t(0), std::size_t(1), std::size_t(5000), std::size_t(65536),
                                 std::size_t(65537), std::size_t(300001), kBound - 1, kBound, kBound + 1,
                                 kBound + 70000}) {
    std::string text(size, 'x');
    for (std::size_t i = 0; i < size; ++i) text[i] = char('a' + i % 23);
    {
      std::ofstream out(path, std::ios::binary);
      out << text;
    }
    std::string got, err;
    INFO("file of " << size << " bytes");
    const bool ok = uvms::sil::ReadBoundedFile(path, &got, &err);
    CHECK(ok == (size <= kBound));
    if (ok) {
      CHECK(got == text);
    } else {
      CHECK_THAT(err, Catch::Contains("has more than 1048576 bytes"));
    }
  }
  std::filesystem::remove(path);
}

TEST_CASE("TickCountCannotOverflow", "[scenario][bounds]") {
  // run.tick_s=5e-324 gave "finished, 0 ticks, every metric 0".
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.tick_s=5e-324"}), Catch::Contains("key \"run.tick_s\": got 4.94"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.tick_s=1e-7"}), Catch::Contains("expected a tick in [1e-06"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.duration_s=1e300"}), Catch::Contains("key \"run.duration_s\": got 1e+300"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.duration_s=1e6", "run.tick_s=1e-6"}),
             Catch::Contains("key \"run.duration_s\": duration_s / tick_s = 1e+12 ticks (expected at most 1000000000)"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"link.timeout_s=1e300"}), Catch::Contains("key \"link.timeout_s\""));
}

TEST_CASE("VectorNormsAndSquaredLimitsAreBounded", "[scenario][bounds]") {
  CHECK_THAT(ErrorOf(CaseText("IV"), {"trajectory.cartesian.direction=[1e308, 1e308, 0]"}),
             Catch::Contains("key \"trajectory.cartesian.direction\": has length inf (expected a vector whose length is finite)"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"environment.steady_flow_m_s=[1e200, 1e200, 1e200]"}),
             Catch::Contains("key \"environment.steady_flow_m_s\": has length inf"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"environment.gravity_m_s2=[0, 0, -1e308]", "environment.trim=false"}),
             Catch::Contains("has length") || Catch::Contains("environment.gravity_m_s2"));
  for (const char *key : {"limits.max_vehicle_speed_m_s", "limits.max_vehicle_rate_rad_s",
                          "limits.max_joint_rate_rad_s", "limits.max_motor_speed_rad_s",
                          "limits.max_motor_current_A", "limits.quat_norm_tol", "limits.thrust_limit_N"}) {
    CHECK_THAT(ErrorOf(CaseText("IV"), {std::string(key) + "=1e-200"}),
               Catch::Contains(std::string("key \"") + key + "\": got 1e-200 (expected 0 (check off) or a bound in"));
    CHECK_THAT(ErrorOf(CaseText("IV"), {std::string(key) + "=0"}), !Catch::Contains(key));
  }
  CHECK_THAT(ErrorOf(CaseText("IV"), {"limits.max_motor_current_A=1e200"}), Catch::Contains("got 1e+200"));
}

TEST_CASE("SetValuesWithLineBreaksAreRejected", "[scenario][bounds]") {
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.seed=1\nrun.tick_s=0.1"}),
             Catch::StartsWith("--set run.seed=...: a value with a line break or NUL byte (key \"run.seed\""));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"run.name=\"a\"\r"}), Catch::Contains("line break"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {std::string("run.seed=1\0", 11)}), Catch::Contains("NUL byte"));
}

TEST_CASE("RealtimeFactorIsBounded", "[scenario][bounds]") {
  CHECK_THAT(ErrorOf(CaseText("IV"), {"link.realtime_factor=1e-300"}),
             Catch::Contains("key \"link.realtime_factor\": got 1e-300 (expected 0 or a factor in [0.001, 1000])"));
  CHECK_THAT(ErrorOf(CaseText("IV"), {"link.realtime_factor=1e9"}), Catch::Contains("link.realtime_factor"));
  CHECK(ErrorOf(CaseText("IV"), {"link.realtime_factor=0"}).empty());
  CHECK(ErrorOf(CaseText("IV"), {"link.realtime_factor=1"}).empty());
}

TEST_CASE("RunNameCannotLeaveTheOutputRoot", "[scenario][paths]") {
  for (const char *name : {"/tmp/x", "../x", "a/../../b", "..", ".", "a\\\\b", "a\\u0000b", "a\\nb", ""}) {
    INFO(name);
    CHECK_THAT(ErrorOf(CaseText("IV") + "[run]\nname = \"" + name + "\"\n"), Catch::Contains("key \"run.name\""));
  }
  CHECK(ErrorOf(CaseText("IV") + "[run]\nname = \"case_IV.v2-x\"\n").empty());
}

// ---- thrusters.motor and the motor/propeller keys (sil/scenario/motor_sets.hpp; SPEC §3.4, §5, §7.4) --

namespace {

/// The firmware's value of the field behind a motor-set key, through the key's table row.
double FirmwareValue(const Scenario &s, const char *key) {
  return uvms::sil::ConfigRowOf(key).fw_get(s).get<double>();
}

}  // namespace

TEST_CASE("EveryMotorSetGivesThePlantAndTheFirmwareItsValues", "[scenario][motor_sets]") {
  // Each named set, chosen by name, reaches the plant member and the firmware field of every
  // key it fills (the firmware field in its real type: float on the target).
  for (const uvms::sil::MotorSet &set : uvms::sil::MotorSets()) {
    INFO(set.name);
    const Scenario s = ParseScenario(CaseText("IV") + "[thrusters]\nmotor = \"" + set.name + "\"\n", "x.toml");
    const uvms::plant::PropulsionParams want = set.params();
    for (const uvms::sil::MotorSetKey &k : uvms::sil::MotorSetKeys()) {
      INFO(k.key);
      CHECK(s.plant.propulsion.*k.member == want.*k.member);
      // fw_get gives the field's value in its shortest decimal form: compare in the real type.
      CHECK(static_cast<uvms_real_t>(FirmwareValue(s, k.key)) ==
            static_cast<uvms_real_t>(want.*k.member));
    }
  }
  // No key: the "paper" set, which is the plant's own PaperPlantParams() (never a copy).
  const Scenario def = ParseScenario(CaseText("IV"), "x.toml");
  for (const uvms::sil::MotorSetKey &k : uvms::sil::MotorSetKeys())
    CHECK(def.plant.propulsion.*k.member == uvms::plant::PaperPlantParams().propulsion.*k.member);
  CHECK(std::string(uvms::sil::MotorSets().front().name) == "paper");
}

TEST_CASE("AnExplicitMotorKeyOverridesTheNamedSet", "[scenario][motor_sets]") {
  // Precedence (docs/SCENARIOS.md): a key given explicitly wins over the set's value, in the
  // file or by --set; the set's other keys are untouched.
  for (const uvms::sil::MotorSet &set : uvms::sil::MotorSets()) {
    INFO(set.name);
    const std::string text = CaseText("IV") + "[thrusters]\nmotor = \"" + set.name + "\"\n";
    const Scenario s = ParseScenario(text + "viscous_friction_Nm_s = 0.25\n", "x.toml");
    CHECK(s.plant.propulsion.viscous_friction_Nm_s == 0.25);
    CHECK(FirmwareValue(s, "thrusters.viscous_friction_Nm_s") == 0.25);
    CHECK(s.plant.propulsion.torque_constant_Nm_A == set.params().torque_constant_Nm_A);
    const Scenario o = ParseScenario(text, "x.toml", {"thrusters.resistance_ohm=0.5"});
    CHECK(o.plant.propulsion.resistance_ohm == 0.5);
    CHECK(FirmwareValue(o, "thrusters.resistance_ohm") == 0.5);
    CHECK(o.plant.propulsion.inductance_H == set.params().inductance_H);
  }
}

TEST_CASE("BadMotorValuesFailNamingTheKey", "[scenario][motor_sets]") {
  const std::string t = CaseText("IV") + "[thrusters]\n";
  CHECK_THAT(ErrorOf(t + "torque_constant_Nm_A = 0\n"),
             Catch::Contains("x.toml:4: key \"thrusters.torque_constant_Nm_A\": got 0 (expected a number >= 0.0005)"));
  CHECK_THAT(ErrorOf(t + "inductance_H = 0\n"),
             Catch::Contains("x.toml:4: key \"thrusters.inductance_H\": got 0 (expected a number >= 1e-06)"));
  // The lower bounds are physical (sil/msg/config_table.h), not merely > 0.
  CHECK_THAT(ErrorOf(t + "propeller_diameter_m = 0.005\n"),
             Catch::Contains("x.toml:4: key \"thrusters.propeller_diameter_m\": got 0.005 (expected a number >= 0.01)"));
  CHECK_THAT(ErrorOf(t + "resistance_ohm = -1\n"), Catch::Contains("\"thrusters.resistance_ohm\": got -1"));
  CHECK_THAT(ErrorOf(t + "rotor_inertia_kg_m2 = 0\n"), Catch::Contains("\"thrusters.rotor_inertia_kg_m2\": got 0"));
  CHECK_THAT(ErrorOf(t + "viscous_friction_Nm_s = -1e-3\n"),
             Catch::Contains("\"thrusters.viscous_friction_Nm_s\": got -0.001 (expected a number >= 0)"));
  // SPEC §7.4: the speed solution needs CT2 < 0.
  CHECK_THAT(ErrorOf(t + "ct2 = 0.5\n"),
             Catch::Contains("x.toml:4: key \"thrusters.ct2\": got 0.5 (expected a number < 0)"));
  CHECK_THAT(ErrorOf(t + "motor = \"t300\"\n"),
             Catch::Contains("x.toml:4: key \"thrusters.motor\": got \"t300\" (expected one of: paper"));
  // b = 0 is allowed in both models (the friction sweep, sil/campaigns/paper/exp9_friction.toml).
  const Scenario s = ParseScenario(t + "viscous_friction_Nm_s = 0\n", "x.toml");
  CHECK(s.plant.propulsion.viscous_friction_Nm_s == 0.0);
  CHECK(FirmwareValue(s, "thrusters.viscous_friction_Nm_s") == 0.0);
}

// ---- issue 30 item 1: the vehicle's body and thruster layout, in both models ------------------

namespace {

/// A vectored layout: four horizontal thrusters at 45° in the corners, four vertical ones
/// (the BlueROV2 Heavy's arrangement, here at the paper hull's size). Directions are given
/// unnormalised (length 2) to check the normalisation.
const char *const kVectoredLayout =
    "[[thrusters.thruster]]\nposition_m = [0.4, -0.3, 0.0]\ndirection = [1.4142135623730951, 1.4142135623730951, 0]\n"
    "[[thrusters.thruster]]\nposition_m = [0.4, 0.3, 0.0]\ndirection = [1.4142135623730951, -1.4142135623730951, 0]\n"
    "[[thrusters.thruster]]\nposition_m = [-0.4, -0.3, 0.0]\ndirection = [1.4142135623730951, -1.4142135623730951, 0]\n"
    "[[thrusters.thruster]]\nposition_m = [-0.4, 0.3, 0.0]\ndirection = [1.4142135623730951, 1.4142135623730951, 0]\n"
    "[[thrusters.thruster]]\nposition_m = [0.3, -0.4, -0.1]\ndirection = [0, 0, 2]\n"
    "[[thrusters.thruster]]\nposition_m = [0.3, 0.4, -0.1]\ndirection = [0, 0, 2]\n"
    "[[thrusters.thruster]]\nposition_m = [-0.3, -0.4, -0.1]\ndirection = [0, 0, 2]\n"
    "[[thrusters.thruster]]\nposition_m = [-0.3, 0.4, -0.1]\ndirection = [0, 0, 2]\n";

/// The vectored layout's first k thrusters.
std::string FirstThrusters(std::size_t k) {
  std::string out, text = kVectoredLayout;
  const std::string tag = "[[thrusters.thruster]]";
  std::size_t pos = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t next = text.find(tag, pos + 1);
    out += text.substr(pos, next == std::string::npos ? std::string::npos : next - pos);
    pos = next;
  }
  return out;
}

}  // namespace

TEST_CASE("ThrustLimitsPerThrusterReachTheController", "[scenario][thrusters]") {
  // limits.thrust_limit_N serves every thruster without its own; a [[thrusters.thruster]]'s
  // thrust_limit_N serves that one; 0 is "none"; a bound whose square is no normal float is
  // refused, naming the thruster's key.
  std::string layout = kVectoredLayout;
  const std::string tag = "[[thrusters.thruster]]\n";
  std::size_t third = 0;
  for (int i = 0; i < 3; ++i) third = layout.find(tag, third) + tag.size();
  layout.insert(third, "thrust_limit_N = 12.5\n");  // the third table's
  const Scenario s = ParseScenario(CaseText("IV") + "[limits]\nthrust_limit_N = 40.0\n" + layout, "x.toml");
  for (std::size_t j = 0; j < 8; ++j)
    CHECK(s.controller.limits.thrust_limit_N[j] == uvms_real_t(j == 2 ? 12.5 : 40.0));
  const Scenario none = ParseScenario(CaseText("IV") + kVectoredLayout, "x.toml");
  uvms_ctrl_config_t paper;
  REQUIRE(uvms_ctrl_config_paper(&paper, 4) == UVMS_OK);
  for (std::size_t j = 0; j < 8; ++j) CHECK(none.controller.limits.thrust_limit_N[j] == paper.limits.thrust_limit_N[j]);
  std::string bad = kVectoredLayout;
  bad.insert(bad.find(tag) + tag.size(), "thrust_limit_N = 1e-30\n");
  CHECK_THAT(ErrorOf(CaseText("IV") + bad),
             Catch::Contains("key \"thrusters.thruster[0].thrust_limit_N\": got 1e-30 (expected 0 (check off) or a bound in"));
  bad = kVectoredLayout;
  bad.insert(bad.find(tag) + tag.size(), "thrust_limit_N = -1\n");
  CHECK_THAT(ErrorOf(CaseText("IV") + bad), Catch::Contains("key \"thrusters.thruster[0].thrust_limit_N\": got -1"));
}

TEST_CASE("ThrusterTypesGiveTheirThrustersTheirOwnSetInBothModels", "[scenario][thrusters]") {
  // docs/MODEL.md §5 "Thruster types": the vertical thrusters get a "small" type (the T200
  // set, its own supply and speed gain); the horizontal ones keep the [thrusters] keys.
  std::string layout = kVectoredLayout;
  const std::string tag = "[[thrusters.thruster]]\n";
  std::size_t at = 0;
  for (int i = 0; i < 8; ++i) {
    at = layout.find(tag, at) + tag.size();
    if (i >= 4) layout.insert(at, "type = \"small\"\n");
  }
  const std::string types =
      "[[thrusters.type]]\nname = \"small\"\nmotor = \"t200\"\nvoltage_limit_V = 16.0\nka_1_s = 8.0\n";
  const Scenario s = ParseScenario(CaseText("IV") + "[thrusters]\nct1 = 0.25\n" + types + layout, "x.toml");
  const uvms::plant::PropulsionParams t200 = uvms::sil::FindMotorSet("t200")->params();
  uvms_ctrl_config_t paper;
  REQUIRE(uvms_ctrl_config_paper(&paper, 4) == UVMS_OK);
  for (std::size_t j = 0; j < 8; ++j) {
    INFO("thruster " << j + 1);
    const uvms_thruster_params_t &fw = s.controller.thruster[j];
    if (j < 4) {
      CHECK(!s.plant.thrusters[j].propulsion);
      CHECK(fw.ct1 == uvms_real_t(0.25));  // the [thrusters] key
      CHECK(fw.ct2 == paper.thruster[j].ct2);
      CHECK(fw.voltage_limit_V == paper.thruster[j].voltage_limit_V);
      continue;
    }
    REQUIRE(s.plant.thrusters[j].propulsion);
    const uvms::plant::PropulsionParams &pl = *s.plant.thrusters[j].propulsion;
    CHECK(pl.ct2 == t200.ct2);
    CHECK(pl.ct1 == t200.ct1);  // the named set's, not the [thrusters] override
    CHECK(pl.diameter_m == t200.diameter_m);
    CHECK(pl.rotor_inertia_kg_m2 == t200.rotor_inertia_kg_m2);
    CHECK(pl.drive == s.plant.propulsion.drive);
    CHECK(fw.ct2 == uvms_real_t(t200.ct2));
    CHECK(fw.diameter_m == uvms_real_t(t200.diameter_m));
    CHECK(fw.torque_constant_Nm_A == uvms_real_t(t200.torque_constant_Nm_A));
    CHECK(fw.voltage_limit_V == uvms_real_t(16.0));
    CHECK(fw.speed_gain_1_s == uvms_real_t(8.0));
    CHECK(fw.current_gain_1_s == paper.thruster[j].current_gain_1_s);
  }
  CHECK(s.plant.propulsion.ct1 == 0.25);  // the default type is untouched by the types
  // Errors name the key.
  std::string unknown = layout;
  unknown.replace(unknown.find("type = \"small\""), 14, "type = \"big\"");
  CHECK_THAT(ErrorOf(CaseText("IV") + types + unknown),
             Catch::Contains("key \"thrusters.thruster[4].type\": no [[thrusters.type]] named \"big\" (expected one of: small)"));
  CHECK_THAT(ErrorOf(CaseText("IV") + types + types + layout),
             Catch::Contains("key \"thrusters.type[1].name\": a second type named \"small\""));
  CHECK_THAT(ErrorOf(CaseText("IV") + types + "[[thrusters.type]]\nname = \"spare\"\n" + layout),
             Catch::Contains("key \"thrusters.type[1].name\": no [[thrusters.thruster]] has type = \"spare\""));
  CHECK_THAT(ErrorOf(CaseText("IV") + types),
             Catch::Contains("the paper's layout has no tables to name it"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[[thrusters.type]]\nname = \"small\"\nct2 = 0.1\n" + layout),
             Catch::Contains("key \"thrusters.type[0].ct2\": got 0.1 (expected a number < 0)"));
  CHECK_THAT(ErrorOf(CaseText("IV") + "[[thrusters.type]]\nmotor = \"t200\"\n" + layout),
             Catch::Contains("key \"thrusters.type[0].name\": missing"));
}

TEST_CASE("VehicleBodyKeysReachBothModels", "[scenario][vehicle]") {
  // A symmetric positive definite added-mass matrix, unlike the paper's (a diagonal one with a
  // coupling term between sway and yaw).
  std::string added = "added_mass_coeff = [";
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      added += std::to_string(r == c ? 0.5 + 0.1 * r : (r == 1 && c == 5) || (r == 5 && c == 1) ? 0.05 : 0.0) +
               (r == 5 && c == 5 ? "]\n" : ", ");
  const Scenario s = ParseScenario(CaseText("VII") +
                                       "[vehicle]\nmass_kg = 11.5\nvolume_m3 = 0.0121\nfrontal_area_m2 = 0.11\n"
                                       "drag_coeff = 0.9\ninertia_kg_m2 = [0.16, 0.16, 0.26]\n"
                                       "arm_base_m = [0.2, 0.0, 0.12]\n"
                                       "arm_base_rotvec_rad = [0.0, 1.5707963267948966, 0.0]\n"
                                       "linear_damping = [13.7, 0, 33, 0, 0.8, 0]\n"
                                       "quadratic_damping = [141, 217, 190, 1.19, 0.47, 1.5]\n" + added,
                                   "x.toml");
  const uvms_vehicle_params_t &fw = s.controller.arm.vehicle;
  CHECK(s.plant.vehicle.mass_kg == 11.5);
  CHECK(fw.mass_kg == static_cast<uvms_real_t>(11.5));
  CHECK(s.plant.vehicle.volume_m3 == 0.0121);
  CHECK(fw.volume_m3 == static_cast<uvms_real_t>(0.0121));
  CHECK(s.plant.vehicle.frontal_area_m2 == 0.11);
  CHECK(fw.frontal_area_m2 == static_cast<uvms_real_t>(0.11));
  CHECK(s.plant.vehicle.drag_coeff == 0.9);
  CHECK(fw.drag_coeff == static_cast<uvms_real_t>(0.9));
  const uvms::plant::Vec3 inertia(0.16, 0.16, 0.26), base(0.2, 0.0, 0.12);
  CHECK(s.plant.vehicle.inertia_kg_m2 == inertia);
  CHECK(s.plant.vehicle.base_offset_m == base);
  for (int k = 0; k < 3; ++k) {
    CHECK(fw.inertia_kg_m2[k] == static_cast<uvms_real_t>(inertia[k]));
    CHECK(fw.base_offset_m[k] == static_cast<uvms_real_t>(base[k]));
  }
  const uvms::plant::Vec3 mount(0.0, 1.5707963267948966, 0.0);  // the arm base turned about y
  CHECK(s.plant.vehicle.base_rotvec_rad == mount);
  for (int k = 0; k < 3; ++k) CHECK(fw.base_rotvec_rad[k] == static_cast<uvms_real_t>(mount[k]));
  const double DL[6] = {13.7, 0, 33, 0, 0.8, 0}, DQ[6] = {141, 217, 190, 1.19, 0.47, 1.5};
  for (int k = 0; k < 6; ++k) {
    CHECK(s.plant.vehicle.linear_damping[k] == DL[k]);
    CHECK(s.plant.vehicle.quadratic_damping[k] == DQ[k]);
    CHECK(fw.linear_damping[k] == static_cast<uvms_real_t>(DL[k]));
    CHECK(fw.quadratic_damping[k] == static_cast<uvms_real_t>(DQ[k]));
  }
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) {
      const double want = r == c ? 0.5 + 0.1 * r : (r == 1 && c == 5) || (r == 5 && c == 1) ? 0.05 : 0.0;
      CHECK(s.plant.added_mass_coeff(r, c) == Approx(want).epsilon(1e-15));
      CHECK(s.controller.arm.added_mass_coeff[6 * r + c] == static_cast<uvms_real_t>(s.plant.added_mass_coeff(r, c)));
    }
  // The vehicle's own absolute added mass: the plant's only, the links keep Ma0.
  const Scenario ma = ParseScenario(CaseText("VII") + "[vehicle]\nadded_mass_kg = [" +
                                        "6.36,0,0,0,0,0, 0,7.12,0,0,0,0, 0,0,18.68,0,0,0, "
                                        "0,0,0,0.189,0,0, 0,0,0,0,0.135,0, 0,0,0,0,0,0.222]\n",
                                    "x.toml");
  REQUIRE(ma.plant.vehicle.added_mass_kg.has_value());
  CHECK((*ma.plant.vehicle.added_mass_kg)(2, 2) == 18.68);
  CHECK((*ma.plant.vehicle.added_mass_kg)(0, 1) == 0.0);
  CHECK(ma.plant.added_mass_coeff == ParseScenario(CaseText("VII"), "x.toml").plant.added_mass_coeff);
  CHECK_FALSE(ParseScenario(CaseText("VII"), "x.toml").plant.vehicle.added_mass_kg.has_value());
  // The hull box: the plant's only (contact monitor, scene message).
  const Scenario h = ParseScenario(CaseText("VII") + "[vehicle]\nhull_size_m = [0.46, 0.58, 0.25]\n"
                                                     "hull_center_m = [0, 0, 0.05]\n", "x.toml");
  CHECK(h.plant.vehicle.hull_size_m == uvms::plant::Vec3(0.46, 0.58, 0.25));
  CHECK(h.plant.vehicle.hull_center_m == uvms::plant::Vec3(0.0, 0.0, 0.05));
  const Scenario no_hull = ParseScenario(CaseText("VII"), "x.toml");
  CHECK(std::memcmp(&h.controller, &no_hull.controller, sizeof h.controller) == 0);
  CHECK(std::memcmp(&ma.controller, &no_hull.controller, sizeof ma.controller) == 0);
  // The trim follows the new body: a 11.5 kg vehicle of 12.1 L gets its own ballast.
  const Scenario g = ParseScenario(CaseText("VII") + "[vehicle]\nmass_kg = 11.5\nvolume_m3 = 0.0121\n"
                                                     "[environment]\ngravity_m_s2 = \"earth\"\n",
                                   "x.toml");
  const Scenario g_paper = ParseScenario(CaseText("VII") + "[environment]\ngravity_m_s2 = \"earth\"\n", "x.toml");
  CHECK(g.controller.arm.vehicle.ballast_kg != g_paper.controller.arm.vehicle.ballast_kg);
}

TEST_CASE("BadVehicleBodyFailsNamingTheKey", "[scenario][vehicle]") {
  const std::string v = CaseText("IV") + "[vehicle]\n";
  CHECK_THAT(ErrorOf(v + "mass_kg = 0\n"),
             Catch::Contains("x.toml:4: key \"vehicle.mass_kg\": got 0 (expected a number > 0)"));
  CHECK_THAT(ErrorOf(v + "volume_m3 = -0.1\n"), Catch::Contains("key \"vehicle.volume_m3\": got -0.1"));
  CHECK_THAT(ErrorOf(v + "added_mass_kg = [1,0,0,0,0,0, 0,1,0,0,0,0, 0,0,1,0,0,0, 0,0,0,-1,0,0, "
                         "0,0,0,0,1,0, 0,0,0,0,0,1]\n"),
             Catch::Contains("x.toml:4: key \"vehicle.added_mass_kg\": not positive semidefinite: "
                             "smallest eigenvalue -1"));
  CHECK_THAT(ErrorOf(v + "linear_damping = [1, 2, 3, -0.5, 0, 0]\n"),
             Catch::Contains("x.toml:4: key \"vehicle.linear_damping\": element 3 is -0.5 (expected each >= 0)"));
  CHECK_THAT(ErrorOf(v + "quadratic_damping = [1, 2, 3]\n"),
             Catch::Contains("key \"vehicle.quadratic_damping\": got 3 elements (expected an array of 6 numbers)"));
  CHECK_THAT(ErrorOf(v + "hull_size_m = [1, 0, 0.5]\n"),
             Catch::Contains("x.toml:4: key \"vehicle.hull_size_m\": got (1, 0, 0.5) (expected each > 0)"));
  CHECK_THAT(ErrorOf(v + "inertia_kg_m2 = [1, 0, 1]\n"),
             Catch::Contains("x.toml:4: key \"vehicle.inertia_kg_m2\": got (1, 0, 1) kg·m² (expected principal moments > 0)"));
  CHECK_THAT(ErrorOf(v + "inertia_kg_m2 = [1, 1, 2.5]\n"),
             Catch::Contains("key \"vehicle.inertia_kg_m2\": got (1, 1, 2.5) kg·m²: moment 3 exceeds the sum of the other two"));
  // A flat plate is the limit case I_z = I_x + I_y: allowed.
  CHECK(ErrorOf(v + "inertia_kg_m2 = [1, 1.5, 2.5]\n").empty());
  std::string asym = "added_mass_coeff = [", neg = "added_mass_coeff = [";
  for (int i = 0; i < 36; ++i) {
    const int r = i / 6, c = i % 6;
    asym += std::string(r == c ? "1" : (r == 0 && c == 4) ? "0.2" : "0") + (i == 35 ? "]\n" : ", ");
    neg += std::string(r == c ? (r == 2 ? "-0.5" : "1") : "0") + (i == 35 ? "]\n" : ", ");
  }
  CHECK_THAT(ErrorOf(v + asym),
             Catch::Contains("x.toml:4: key \"vehicle.added_mass_coeff\": not symmetric: |M − Mᵀ| reaches 0.2"));
  CHECK_THAT(ErrorOf(v + neg),
             Catch::Contains("key \"vehicle.added_mass_coeff\": not positive semidefinite: smallest eigenvalue -0.5"));
  CHECK_THAT(ErrorOf(v + "added_mass_coeff = [1, 2, 3]\n"), Catch::Contains("key \"vehicle.added_mass_coeff\""));
}

TEST_CASE("ThrusterLayoutReachesBothModelsNormalised", "[scenario][vehicle]") {
  const Scenario s = ParseScenario(CaseText("VII") + kVectoredLayout, "x.toml");
  REQUIRE(s.plant.thrusters.size() == 8);
  REQUIRE(s.controller.thrusters.num_thrusters == 8);
  const double c = std::sqrt(0.5);
  CHECK(s.plant.thrusters[1].position_m == uvms::plant::Vec3(0.4, 0.3, 0.0));
  CHECK((s.plant.thrusters[1].direction - uvms::plant::Vec3(c, -c, 0.0)).norm() < 1e-15);
  CHECK(s.plant.thrusters[6].direction == uvms::plant::Vec3(0.0, 0.0, 1.0));
  for (std::size_t j = 0; j < 8; ++j)
    for (int k = 0; k < 3; ++k) {
      CHECK(s.controller.thrusters.position_m[j][k] == static_cast<uvms_real_t>(s.plant.thrusters[j].position_m[k]));
      CHECK(s.controller.thrusters.direction[j][k] == static_cast<uvms_real_t>(s.plant.thrusters[j].direction[k]));
    }
  // Without the array the paper's layout stays (SPEC §3.4).
  const Scenario paper = ParseScenario(CaseText("VII"), "x.toml");
  uvms_thruster_geometry_t geom;
  uvms_thruster_geometry_paper(&geom);
  REQUIRE(paper.controller.thrusters.num_thrusters == geom.num_thrusters);
  CHECK(std::memcmp(&paper.controller.thrusters, &geom, sizeof geom) == 0);
  // A fault names a thruster of the layout given: 1..7 for seven thrusters.
  const std::string seven = CaseText("VII") + FirstThrusters(7);
  CHECK(ParseScenario(seven, "x.toml").controller.thrusters.num_thrusters == 7);
  CHECK_THAT(ErrorOf(seven + "[[faults.thruster]]\nthruster = 8\nmode = \"off\"\n"),
             Catch::Contains("got 8 (expected 1..7)"));
}

TEST_CASE("ThrusterLayoutErrorsNameTheLostAxes", "[scenario][vehicle]") {
  const std::string t = CaseText("VII");
  // Six thrusters: the four vectored ones and two vertical ones on the y axis' side (the
  // standard BlueROV2's arrangement) cannot turn the vehicle about y.
  const std::string bluerov2 = FirstThrusters(4) +
                               "[[thrusters.thruster]]\nposition_m = [0.0, -0.4, -0.1]\ndirection = [0, 0, 1]\n"
                               "[[thrusters.thruster]]\nposition_m = [0.0, 0.4, -0.1]\ndirection = [0, 0, 1]\n";
  CHECK_THAT(ErrorOf(t + bluerov2),
             Catch::Contains("x.toml:3: key \"thrusters.thruster\": the layout cannot produce pitch moment "
                             "(about y) (H has rank 5 of 6;"));
  // Only the four horizontal ones: no heave, roll or pitch.
  CHECK_THAT(ErrorOf(t + FirstThrusters(4)),
             Catch::Contains("cannot produce heave force (z), roll moment (about x), pitch moment (about y) "
                             "(H has rank 3 of 6;"));
  // Counts beyond the firmware's maximum, and none.
  CHECK_THAT(ErrorOf(t + kVectoredLayout + FirstThrusters(1)),
             Catch::Contains("key \"thrusters.thruster\": 9 thrusters (expected 1..8, the firmware's UVMS_MAX_THRUSTERS)"));
  CHECK_THAT(ErrorOf(t + "[thrusters]\nthruster = []\n"),
             Catch::Contains("key \"thrusters.thruster\": 0 thrusters (expected 1..8"));
  // Fields: required, and a direction must have a length.
  CHECK_THAT(ErrorOf(t + "[[thrusters.thruster]]\nposition_m = [0, 0, 0]\n"),
             Catch::Contains("\"thrusters.thruster[0].direction\": missing (expected 3 numbers)"));
  CHECK_THAT(ErrorOf(t + "[[thrusters.thruster]]\nposition_m = [0, 0, 0]\ndirection = [0, 0, 0]\n"),
             Catch::Contains("\"thrusters.thruster[0].direction\": has length 0 (expected a non-zero vector)"));
}

TEST_CASE("LostAxesAgreeWithTheFirmwaresUncontrollableAxes", "[scenario][vehicle]") {
  // The scenario layer's check (Eigen, double) against the firmware's own rank-revealing
  // allocation (Jacobi, uvms_real_t): the vectored layout with thrusters removed, every subset
  // of 1..8 thrusters that keeps thruster order; the firmware sees the subset as the usable set.
  const Scenario full = ParseScenario(CaseText("VII") + kVectoredLayout, "x.toml");
  uvms_alloc_t alloc;
  REQUIRE(uvms_alloc_init(&alloc, &full.controller.thrusters) == UVMS_OK);
  int refused = 0;
  for (std::uint32_t mask = 1; mask < 256; ++mask) {
    std::string text = CaseText("VII");
    for (std::size_t j = 0; j < 8; ++j)
      if ((mask >> j) & 1u) {
        const std::string one = FirstThrusters(j + 1).substr(FirstThrusters(j).size());
        text += one;
      }
    REQUIRE(uvms_alloc_set_usable(&alloc, mask) == UVMS_OK);
    const std::string err = ErrorOf(text);
    INFO("mask " << mask << ": " << err);
    CHECK(err.empty() == (alloc.uncontrollable_axes == 0));
    const char *const names[6] = {"surge force (x)", "sway force (y)", "heave force (z)",
                                  "roll moment (about x)", "pitch moment (about y)", "yaw moment (about z)"};
    for (int i = 0; i < 6; ++i)
      CHECK((err.find(names[i]) != std::string::npos) == (((alloc.uncontrollable_axes >> i) & 1u) != 0));
    refused += err.empty() ? 0 : 1;
  }
  CHECK(refused > 100);  // most subsets lose an axis; the check is not vacuous
}

// ---- issue 30 item 1: the arm, in both models -------------------------------------------------

namespace {

/// docs/SCENARIOS.md's example arm (the ```toml block after "a two-link planar arm"), so that
/// the documented example is the tested one.
std::string DocExampleArm() {
  std::ifstream in(std::filesystem::path(UVMS_SCENARIO_DIR) / ".." / ".." / ".." / "docs" / "SCENARIOS.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const std::size_t at = doc.find("a two-link planar arm");
  REQUIRE(at != std::string::npos);
  const std::size_t begin = doc.find("```toml\n", at) + 8, end = doc.find("```", begin);
  REQUIRE(end != std::string::npos);
  return doc.substr(begin, end - begin);
}

/// One link of an explicit arm (TOML).
std::string Link(double a_m, const char *extra = "") {
  return "[[arm.link]]\nalpha_rad = 0.0\na_m = " + std::to_string(a_m) +
         "\nd_m = 0.0\nmass_kg = 1.0\ndiameter_m = 0.05\n" + extra;
}

}  // namespace

TEST_CASE("ArmLinksReachBothModels", "[scenario][arm]") {
  // The documented example is the shipped scenario's arm, verbatim.
  std::ifstream shipped(std::filesystem::path(UVMS_SCENARIO_DIR) / ".." / "vehicles" / "planar_arm_VII_stagnant.toml");
  std::stringstream text;
  text << shipped.rdbuf();
  CHECK_THAT(text.str(), Catch::Contains(DocExampleArm()));
  const Scenario s = ParseScenario(CaseText("VII") + DocExampleArm(), "x.toml");
  REQUIRE(s.plant.links.size() == 2);
  REQUIRE(s.controller.arm.num_joints == 2);
  CHECK(s.plant.links[0].a_m == 0.4);
  CHECK(s.plant.links[1].com_m == uvms::plant::Vec3(0.15, 0.0, 0.0));
  CHECK(s.plant.links[1].inertia_kg_m2 == uvms::plant::Vec3(0.0005, 0.008, 0.008));
  CHECK(s.plant.links[0].diameter_m == 0.06);
  CHECK(s.plant.links[0].drag_coeff == 1.0);  // the element default
  for (std::size_t i = 0; i < 2; ++i) {
    const uvms_link_params_t &F = s.controller.arm.link[i];
    const uvms::plant::LinkParams &L = s.plant.links[i];
    CHECK(F.a_m == static_cast<uvms_real_t>(L.a_m));
    CHECK(F.mass_kg == static_cast<uvms_real_t>(L.mass_kg));
    CHECK(F.diameter_m == static_cast<uvms_real_t>(L.diameter_m));
    for (int k = 0; k < 3; ++k) {
      CHECK(F.com_m[k] == static_cast<uvms_real_t>(L.com_m[k]));
      CHECK(F.inertia_kg_m2[k] == static_cast<uvms_real_t>(L.inertia_kg_m2[k]));
    }
    CHECK(static_cast<double>(F.joint_min_rad) == Approx(-2 * M_PI));  // the paper arm's default
    CHECK(static_cast<double>(F.joint_max_rad) == Approx(2 * M_PI));
  }
  // Slots past N are zero in the configuration (they travel in the message).
  const uvms_link_params_t zero{};
  for (std::size_t i = 2; i < UVMS_MAX_JOINTS; ++i)
    CHECK(std::memcmp(&s.controller.arm.link[i], &zero, sizeof zero) == 0);
  REQUIRE(s.initial.q_rad.size() == 2);
  CHECK(s.initial.q_rad[1] == Approx(M_PI / 2));
  CHECK_REAL(s.controller.theta_final_rad[0], M_PI / 4);
  CHECK(static_cast<double>(s.controller.theta_start_rad[2]) == 0.0);
  for (std::size_t i = 0; i < 2; ++i) {
    const uvms_link_params_t &F = s.controller.arm.link[i];
    const uvms::plant::LinkParams &L = s.plant.links[i];
    CHECK(F.alpha_rad == static_cast<uvms_real_t>(L.alpha_rad));
    CHECK(F.d_m == static_cast<uvms_real_t>(L.d_m));
    CHECK(F.drag_coeff == static_cast<uvms_real_t>(L.drag_coeff));
  }
  // arm.mass_scale applies to the arm given, in both models.
  const Scenario half = ParseScenario(CaseText("VII") + DocExampleArm() + "[arm]\nmass_scale = 0.5\n", "x.toml");
  CHECK(half.plant.links[0].mass_kg == 1.0);
  CHECK(half.controller.arm.link[0].mass_kg == static_cast<uvms_real_t>(1.0));
  CHECK(half.controller.arm.link[1].inertia_kg_m2[1] == static_cast<uvms_real_t>(0.004));
  // The task's target point: where this arm's EE is at θF, the vehicle at its initial pose
  // (the paper's target belongs to the paper's arm). Closed form for the planar arm at
  // θF = (45°, 45°): base frame at s0 = (0.914, 0, 0.152) m, EE in it at
  // (0.4 cos 45° + 0.3 cos 90°, 0.4 sin 45° + 0.3 sin 90°, 0).
  const double c45 = std::sqrt(0.5);
  const uvms::plant::Vec3 target(0.914 + 0.4 * c45, 0.4 * c45 + 0.3, 0.152);
  CHECK((s.metrics.ee_target_m - target).norm() < (UVMS_REAL_IS_FLOAT ? 1e-6 : 1e-12));
  const Scenario given = ParseScenario(CaseText("VII") + DocExampleArm() + "[metrics]\nee_target_m = [1, 2, 3]\n", "x.toml");
  CHECK(given.metrics.ee_target_m == uvms::plant::Vec3(1, 2, 3));
  // With gravity the trim is computed at this arm's θI (the paper's at its stowed pose).
  const Scenario earth = ParseScenario(CaseText("VII") + DocExampleArm() + "[environment]\ngravity_m_s2 = \"earth\"\n", "x.toml");
  REQUIRE(earth.plant.env.trim_pose_rad.size() == 2);
  CHECK(earth.plant.env.trim_pose_rad[1] == Approx(M_PI / 2));
  CHECK(earth.controller.arm.vehicle.ballast_kg != static_cast<uvms_real_t>(0.0));
  // Hold mode without θF: the arm holds θI.
  const Scenario hold = ParseScenario(CaseText("VII") + Link(0.4) +
                                          "[trajectory]\nmode = \"hold\"\ntheta_start_deg = [30]\n", "x.toml");
  CHECK_REAL(hold.controller.theta_final_rad[0], 30.0 * M_PI / 180.0);
}

TEST_CASE("BadArmFailsNamingTheField", "[scenario][arm]") {
  const std::string t = CaseText("VII"), traj = "[trajectory]\ntheta_start_deg = [0]\ntheta_final_deg = [10]\n";
  std::string eight;
  for (int i = 0; i < 8; ++i) eight += Link(0.1);
  CHECK_THAT(ErrorOf(t + eight), Catch::Contains("key \"arm.link\": 8 links (expected 1..7, the firmware's UVMS_MAX_JOINTS)"));
  CHECK_THAT(ErrorOf(t + "[[arm.link]]\nalpha_rad = 0\na_m = 0.3\nd_m = 0\ndiameter_m = 0\n" + traj),
             Catch::Contains("\"arm.link[0].mass_kg\": missing (expected a number)"));
  CHECK_THAT(ErrorOf(t + "[[arm.link]]\nalpha_rad = 0\na_m = 0.3\nd_m = 0\nmass_kg = -1\ndiameter_m = 0\n" + traj),
             Catch::Contains("x.toml:7: key \"arm.link[0].mass_kg\": got -1 (expected a number >= 0)"));
  CHECK_THAT(ErrorOf(t + Link(0.3, "inertia_kg_m2 = [0.01, 0, 0]\n") + traj),
             Catch::Contains("key \"arm.link[0].inertia_kg_m2\": got (0.01, 0, 0) kg·m²: moment 1 exceeds the sum"));
  // A thin rod along its own axis (0, I, I) is a rigid body.
  CHECK(ErrorOf(t + Link(0.3, "inertia_kg_m2 = [0, 0.01, 0.01]\n") + traj).empty());
  // With off-diagonal entries the tensor's eigenvalues are the principal moments: here
  // (−0.01, 0.01, 0.03), so the off-diagonal key is named; a rotated rod is fine.
  CHECK_THAT(ErrorOf(t + Link(0.3, "inertia_kg_m2 = [0.01, 0.01, 0.01]\ninertia_products_kg_m2 = [0.02, 0, 0]\n") + traj),
             Catch::Contains("key \"arm.link[0].inertia_products_kg_m2\": the tensor's eigenvalues are (-0.01, 0.01, 0.03) kg·m² "
                             "(expected principal moments ≥ 0)"));
  CHECK(ErrorOf(t + Link(0.3, "inertia_kg_m2 = [0.005, 0.005, 0.01]\ninertia_products_kg_m2 = [0.005, 0, 0]\n") +
                traj).empty());
  // A link's own added mass: 6 numbers ≥ 0, on a link with a cylinder.
  CHECK(ErrorOf(t + Link(0.3, "added_mass_kg = [0.1, 0.1, 0, 0.001, 0.001, 0]\n") + traj).empty());
  CHECK_THAT(ErrorOf(t + Link(0.3, "added_mass_kg = [0.1, -0.1, 0, 0, 0, 0]\n") + traj),
             Catch::Contains("key \"arm.link[0].added_mass_kg\""));
  CHECK_THAT(ErrorOf(t + "[[arm.link]]\nalpha_rad = 0\na_m = 0.3\nd_m = 0\nmass_kg = 1\ndiameter_m = 0\n"
                         "added_mass_kg = [0.1, 0, 0, 0, 0, 0]\n" + traj),
             Catch::Contains("key \"arm.link[0].added_mass_kg\": the link has no hydrodynamic cylinder "
                             "(diameter_m = 0, length 0.3 m); expected diameter_m > 0 and a length > 0"));
  // A zero-length link (a = d = 0, no placement) has no volume either.
  CHECK_THAT(ErrorOf(t + "[[arm.link]]\nalpha_rad = 0\na_m = 0\nd_m = 0\nmass_kg = 1\ndiameter_m = 0.05\n"
                         "added_mass_kg = [0.1, 0, 0, 0, 0, 0]\n" + traj),
             Catch::Contains("(diameter_m = 0.05, length 0 m)"));
  CHECK_THAT(ErrorOf(t + Link(0.3, "joint_min_rad = 1.0\njoint_max_rad = -1.0\n") + traj),
             Catch::Contains("key \"arm.link[0].joint_max_rad\": joint limits 1 .. -1 rad (expected joint_min_rad < joint_max_rad)"));
  // The trajectory of an arm of N joints: N angles, and no column names of the paper's table.
  CHECK_THAT(ErrorOf(t + Link(0.3) + Link(0.2)),
             Catch::Contains("\"trajectory.theta_start_deg\": missing (expected 2 angles in degrees: the arm of "
                             "[[arm.link]] has no SPEC §8 start pose)"));
  CHECK_THAT(ErrorOf(t + Link(0.3) + Link(0.2) + "[trajectory]\ntheta_start_deg = [0, 0, 0, 0, 0, 0, 0]\n"),
             Catch::Contains("key \"trajectory.theta_start_deg\""));
  CHECK_THAT(ErrorOf(t + Link(0.3) + "[trajectory]\ntheta_start_deg = [0]\n"),
             Catch::Contains("\"trajectory.theta_final_deg\": missing: \"auto\" names a SPEC §8 column of the paper's "
                             "7-joint arm (expected 1 angle in degrees for the arm of [[arm.link]])"));
  CHECK_THAT(ErrorOf(t + Link(0.3) + "[trajectory]\ntheta_start_deg = [0]\ntheta_final_deg = \"vehicle\"\n"),
             Catch::Contains("key \"trajectory.theta_final_deg\": \"vehicle\" names a SPEC §8 column"));
  // θI, and a cycloid's θF, within each joint's limits.
  CHECK_THAT(ErrorOf(t + Link(0.3, "joint_max_rad = 0.5\n") + "[trajectory]\ntheta_start_deg = [45]\ntheta_final_deg = [0]\n"),
             Catch::Contains("key \"trajectory.theta_start_deg\": joint 1 at 45° is outside its limits -360° .. 28.6479°"));
  CHECK_THAT(ErrorOf(t + Link(0.3) + Link(0.2) + "[trajectory]\ntheta_start_deg = [0, 0]\ntheta_final_deg = [10, 400]\n"),
             Catch::Contains("key \"trajectory.theta_final_deg\": joint 2 at 400° is outside its limits -360° .. 360° "
                             "(arm.link[1].joint_min_rad .. joint_max_rad)"));
  // Hold: θF is not used, so not checked.
  CHECK(ErrorOf(t + Link(0.3, "joint_max_rad = 0.5\n") +
                "[trajectory]\nmode = \"hold\"\ntheta_start_deg = [20]\ntheta_final_deg = [45]\n").empty());
}
