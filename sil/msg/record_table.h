/* SPDX-License-Identifier: Apache-2.0 */
/*
 * record_table.h: the table of the per-tick record fields, as config_table.h is for the
 * configuration. One row per real-valued quantity that crosses the link every tick:
 *
 *   X(name, dims, unit, doc)
 *
 *   name  the one name of the quantity: the firmware's struct field (uvms/controller.h), the
 *         LCM message field (lcmtypes/), and the PIL record field (sil/pil/pil_protocol.h)
 *   dims  its C array shape as in the .lcm file ([3], [7] joints, [8] thrusters), empty for a
 *         scalar; codec.c checks each against the firmware field at compile time. Reals are
 *         double in the messages, uvms_real_t in the firmware and float in the PIL records
 *   unit  SI unit, as the name's suffix says ("1": dimensionless)
 *   doc   what it is (the .lcm comment says the same, with SPEC's equation numbers)
 *
 * From these lists come: the codec both ways (sil/msg/codec.c: sensors message -> firmware
 * sensors; firmware command and telemetry -> actuators and telemetry messages; the first
 * difference between two actuator messages), and the PIL records and their mappings
 * (sil/pil/). tests/sil/test_record_table.cpp fails when a row and its .lcm field differ
 * (name, type, shape, unit), or when a real field of a message has no row.
 *
 * The header fields (utime, tick, session, crc32), status, flags and the integer counters are
 * mapped by name in codec.c, next to these lists.
 */
#ifndef UVMS_SIL_RECORD_TABLE_H
#define UVMS_SIL_RECORD_TABLE_H

/* sensors_t <- uvms_ctrl_sensors_t (after time_s, which comes from utime) */
#define UVMS_SENSOR_FIELDS(X)                                                                  \
  X(position_m, [3], "m", "vehicle CoM position r0, inertial frame")                          \
  X(quaternion_wxyz, [4], "1", "vehicle attitude R0 (vehicle -> inertial), unit, scalar first") \
  X(velocity_m_s, [3], "m/s", "vehicle CoM velocity v0, inertial frame")                      \
  X(angular_velocity_rad_s, [3], "rad/s", "vehicle angular velocity w0, inertial frame")      \
  X(joint_position_rad, [7], "rad", "joint angles theta_i")                     \
  X(joint_velocity_rad_s, [7], "rad/s", "joint rates")                          \
  X(motor_speed_rad_s, [8], "rad/s", "propeller shaft speed w_j")            \
  X(motor_current_A, [8], "A", "motor current I_j")

/* actuators_t <- uvms_ctrl_command_t: what the plant applies */
#define UVMS_ACTUATOR_FIELDS(X)                                                                \
  X(motor_voltage_V, [8], "V", "motor terminal voltage V_j")                 \
  X(motor_current_cmd_A, [8], "A", "integrated current command I*_j")        \
  X(motor_current_rate_A_s, [8], "A/s", "its rate dI*_j/dt")                 \
  X(joint_acceleration_rad_s2, [7], "rad/s^2", "commanded joint acceleration")

/* telemetry_t <- uvms_ctrl_command_t: the joint reference the command was computed from */
#define UVMS_REFERENCE_FIELDS(X)                                                               \
  X(joint_ref_rad, [7], "rad", "joint reference theta_ref")                     \
  X(joint_ref_rate_rad_s, [7], "rad/s", "joint reference rate")                 \
  X(joint_ref_accel_rad_s2, [7], "rad/s^2", "joint reference acceleration")

/* telemetry_t <- uvms_ctrl_telemetry_t: the tick's intermediate quantities */
#define UVMS_TELEMETRY_FIELDS(X)                                                               \
  X(force_ff_N, [3], "N", "position feedforward F_r")                                         \
  X(force_fb_N, [3], "N", "position feedback F_fb")                                           \
  X(force_des_N, [3], "N", "desired force F_P0")                                              \
  X(moment_ff_Nm, [3], "N m", "attitude feedforward N_r about the vehicle CoM")               \
  X(moment_fb_Nm, [3], "N m", "attitude feedback N_fb")                                       \
  X(moment_des_Nm, [3], "N m", "desired moment N_P0")                                         \
  X(thrust_des_N, [8], "N", "allocated thrust P_j along u_j")                \
  X(thrust_pos_N, [8], "N", "position share of P_j")                         \
  X(thrust_att_N, [8], "N", "attitude share of P_j")                         \
  X(omega_des_rad_s, [8], "rad/s", "desired shaft speed")                    \
  X(current_des_A, [8], "A", "desired current")                              \
  X(advance_speed_m_s, [8], "m/s", "model advance speed v_a")                \
  X(ee_estimate_m, [3], "m", "end-effector estimate p_EE_hat")                                \
  X(barycenter_m, [3], "m", "barycenter p_cm from the sensed state")                          \
  X(barycenter_v_m_s, [3], "m/s", "barycenter velocity from the sensed state")                \
  X(position_ref_m, [3], "m", "position reference r_d (vehicle or barycenter)")               \
  X(attitude_error_rad, [3], "rad", "rotation vector phi*e of E = R0d R0^T")                  \
  X(base_force_N, [3], "N", "arm base force f1")                                              \
  X(base_moment_Nm, [3], "N m", "arm base moment n1 about the base point")                    \
  X(base_accel_model_m_s2, [3], "m/s^2", "vehicle acceleration assumed by the model")         \
  X(joint_torque_model_Nm, [7], "N m", "joint torques of the model")            \
  X(force_deliverable_N, [3], "N", "force the commanded thrusts produce")                     \
  X(moment_deliverable_Nm, [3], "N m", "moment about the vehicle CoM they produce")           \
  X(thrust_scale_pos, , "1", "saturation scale of the position thrust part")                  \
  X(thrust_scale_att, , "1", "saturation scale of the attitude thrust part")

/* truth_t <- the plant's state (sil/run/plant_messages.cpp maps it from plant::Truth, whose
 * containers are the plant's own; the firmware never sees it). In the log only. */
#define UVMS_TRUTH_FIELDS(X)                                                                   \
  X(position_m, [3], "m", "vehicle CoM r0")                                                   \
  X(quaternion_wxyz, [4], "1", "vehicle attitude R0 (vehicle -> inertial), scalar first")     \
  X(velocity_m_s, [3], "m/s", "vehicle CoM velocity v0")                                      \
  X(angular_velocity_rad_s, [3], "rad/s", "vehicle angular velocity w0")                      \
  X(acceleration_m_s2, [3], "m/s^2", "vehicle CoM acceleration")                              \
  X(angular_acceleration_rad_s2, [3], "rad/s^2", "vehicle angular acceleration")              \
  X(joint_position_rad, [7], "rad", "joint angles")                                           \
  X(joint_velocity_rad_s, [7], "rad/s", "joint rates")                                        \
  X(joint_torque_Nm, [7], "N m", "joint torques of the held acceleration")                    \
  X(motor_speed_rad_s, [8], "rad/s", "shaft speed w_j")                                       \
  X(motor_current_A, [8], "A", "current I_j")                                                 \
  X(motor_voltage_V, [8], "V", "terminal voltage V_j")                                        \
  X(thrust_N, [8], "N", "produced thrust along u_j")                                          \
  X(thrust_force_N, [3], "N", "net produced thrust force")                                    \
  X(thrust_moment_Nm, [3], "N m", "net produced thrust moment about the vehicle CoM")         \
  X(ee_position_m, [3], "m", "actual end-effector position")                                  \
  X(barycenter_m, [3], "m", "actual barycenter")                                              \
  X(barycenter_velocity_m_s, [3], "m/s", "its velocity")                                      \
  X(flow_velocity_m_s, [3], "m/s", "fluid velocity at the vehicle")                           \
  X(thruster_energy_J, , "J", "integral of sum max(V_j I_j, 0) dt")                           \
  X(thruster_energy_signed_J, , "J", "integral of sum V_j I_j dt")                            \
  X(manipulator_energy_J, , "J", "integral of sum |tau_i theta_dot_i| dt")                    \
  X(propulsive_energy_J, , "J", "ideal actuator-disk energy")                                 \
  X(min_clearance_m, , "m", "the contact monitor's smallest distance")

#endif /* UVMS_SIL_RECORD_TABLE_H */
