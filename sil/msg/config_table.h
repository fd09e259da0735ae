/* SPDX-License-Identifier: Apache-2.0 */
/*
 * config_table.h: THE table of configuration fields. One row per field of the
 * firmware configuration (uvms_ctrl_config_t, carried by lcmtypes/controller_config_t.lcm) and
 * one per scenario key (docs/SCENARIOS.md); a key that sets a firmware field is the same row.
 * Everything that maps configuration is generated from these rows or walks them:
 *   - sil/msg/codec.c            uvms_config_to_msg            (C, UVMS_CONFIG_TABLE)
 *   - sil/msg/config_from_msg.inc uvms_config_from_msg and the PIL image's pil_config_from_rec
 *   - sil/pil/pil_protocol.h pil_config_rec_t (the PIL record), sil/pil/pil_host.c its filling
 *   - sil/scenario/config_schema.cpp  the runtime table: the scenario reader's per-key parse, range
 *                            check and targets, `uvms scenario schema` (JSON) and the key
 *                            tables of docs/SCENARIOS.md (`uvms scenario schema --markdown`)
 * Adding a setting is one row here plus the code that uses it.
 *
 * Usable from C and C++: C expansions use the first four columns only; the others are tokens
 * that only the C++ expansion (sil/scenario/config_schema.cpp) ever expands.
 *
 * X(map, shape, fw, lcm, key, target, type, unit, range, default, doc)
 *   map     how the firmware field travels in the message and the PIL record:
 *             REAL    uvms_real_t scalar or array <-> double field of the same element count
 *             LINK    member `fw` of every arm.link[i] <-> double lcm[7] or lcm[7][3]
 *             THR     member `fw` of every thruster[j] (uvms_thruster_params_t) <-> double
 *                     lcm[8]; the key sets every thruster's, a rule a type's thrusters
 *             COUNT   size_t count <-> int32, valid 1..shape
 *             FLAG    int boolean <-> int8, normalised to 0/1 both ways
 *             SWITCH  int <-> int8, passed as is (uvms_ctrl_init rejects values other than 0/1)
 *             ENUM    enum <-> int8/int32, valid 0..shape (the last enumerator)
 *             U32     uint32_t <-> int32, valid >= 0
 *             NONE    no firmware field (a key only the plant or the harness sees)
 *   shape   REAL, LINK, THR: the LCM field's dimensions ([3], [7][3], or empty for a scalar);
 *           COUNT, ENUM: the largest valid value; otherwise empty
 *   fw      member path in uvms_ctrl_config_t (LINK: the member of uvms_link_params_t; THR:
 *           of uvms_thruster_params_t)
 *   lcm     field of controller_config_t.lcm (and of the PIL record)
 *   key     scenario key ("section.key"; "section.array[].key" inside an array of tables),
 *           "" for a firmware field that has no key
 *   target  where the scenario value goes besides the firmware field, and who applies it:
 *             FW                   the firmware field only (the reader's table walk)
 *             P(path) / H(path)    plant::PlantParams member / Scenario (harness) member; with
 *                                  a firmware field too, the firmware gets the same value
 *             RULE, RULE_P(path), RULE_H(path)
 *                                  a named cross-key rule in sil/scenario/scenario.cpp applies it
 *                                  (the path documents its plant/harness target)
 *             ELEM_P(container, T, member), ELEM_H(container, T, member)
 *                                  a field of each element (type T) of an array of tables
 *             ELEM(T, member)      the same for a field only the firmware gets (a rule applies
 *                                  the elements; LINK rows: to arm.link[i].fw)
 *   type    real | int | bool | string | enum | vec3 | array (the key's TOML value)
 *   unit    the key's unit ("-": none)
 *   range   what the reader checks on a given value: ANY, GE(x), GT(x) (a vec3: each
 *           component), INT(lo, hi), LT(x), INT_GE(lo), PROB ([0, 1]), FRACTION ([0, 1)),
 *           NONEMPTY, NONZERO(min norm),
 *           REALS(n), REALS_GE(n, x) (n numbers, each >= x), ONE_OF({"name", value}...) (error "expected one of: a, b"),
 *           ONE_OF_FN(f) (the same, the choices from f(), a table kept elsewhere),
 *           EITHER({"name", value}...) (error "expected \"a\" or \"b\""), TABLES,
 *           SPECIAL("text") (the rule checks it)
 *   default PAPER: what uvms_ctrl_config_paper(), plant::PaperPlantParams(), the plant's and
 *           the harness's default-constructed structs give (read at run time, never copied);
 *           VAL(v): the reader's own default, given here; FN(f, note): computed by f
 *           (sil/scenario/config_schema.cpp), note for the doc; NOTE(text): no single value
 *   doc     one line
 */
#ifndef UVMS_SIL_CONFIG_TABLE_H
#define UVMS_SIL_CONFIG_TABLE_H

/* clang-format off */
#define UVMS_CONFIG_TABLE(X) \
  /* ---- [run] (SPEC §3.5) ---- */ \
  X(NONE, , , , "run.name", H(name), string, "-", NONEMPTY, NOTE("the file's stem"), \
    "run name (results, report)") \
  X(NONE, , , , "run.duration_s", H(duration_s), real, "s", GT(0), PAPER, \
    "run length, ≥ tick_s; also the unsteady-flow period tF (SPEC §6.1)") \
  X(REAL, , tick_s, tick_s, "run.tick_s", H(tick_s), real, "s", GT(0), PAPER, \
    "controller period = plant step") \
  X(NONE, , , , "run.seed", H(seed), int, "-", INT_GE(0), PAPER, \
    "seed of the unsteady flow and of the injected faults") \
  /* ---- [control]: Table X, PD gains, joint servo (SPEC §3.5, §7.2, §8, §9) ---- */ \
  X(NONE, , , , "control.case", RULE, enum, "-", SPECIAL("\"I\"..\"VIII\" (or 1..8)"), \
    NOTE("required unless all four switches are given"), \
    "Table X case: the four switches (uvms_switches_case); Scenario::case_number") \
  X(SWITCH, , switches.attitude_control, attitude_control, "control.attitude", RULE, bool, "-", \
    ANY, NOTE("the case's"), "attitude PD and attitude feedforward on") \
  X(ENUM, UVMS_REF_BARYCENTER, switches.position_reference, position_reference, \
    "control.position_reference", RULE, enum, "-", \
    ONE_OF({"vehicle", UVMS_REF_VEHICLE}, {"barycenter", UVMS_REF_BARYCENTER}), NOTE("the case's"), \
    "point held: vehicle CoM or system barycenter; also the Cartesian line's reference") \
  X(SWITCH, , switches.position_feedforward, position_feedforward, "control.position_feedforward", \
    RULE, bool, "-", ANY, NOTE("the case's"), "position feedforward [31]/[32] on") \
  X(SWITCH, , switches.position_feedback, position_feedback, "control.position_feedback", RULE, \
    bool, "-", ANY, NOTE("the case's"), "position PD [45] on") \
  X(REAL, , gains.kpf_N_m, kpf_N_m, "control.kpf_N_m", FW, real, "N/m", GE(0), PAPER, \
    "K_PF, position stiffness") \
  X(REAL, , gains.kdf_N_s_m, kdf_N_s_m, "control.kdf_N_s_m", FW, real, "N·s/m", GE(0), PAPER, \
    "K_DF, position damping") \
  X(REAL, , gains.kpn_Nm_rad, kpn_Nm_rad, "control.kpn_Nm_rad", FW, real, "N·m/rad", GE(0), PAPER, \
    "K_PN, attitude stiffness") \
  X(REAL, , gains.kdn_Nm_s_rad, kdn_Nm_s_rad, "control.kdn_Nm_s_rad", FW, real, "N·m·s/rad", GE(0), \
    PAPER, "K_DN, attitude damping") \
  X(REAL, , joint_kq_1_s2, joint_kq_1_s2, "control.joint_kq_1_s2", FW, real, "1/s²", GE(0), PAPER, \
    "joint servo position gain Kq (SPEC §8)") \
  X(REAL, , joint_kqd_1_s, joint_kqd_1_s, "control.joint_kqd_1_s", FW, real, "1/s", GE(0), PAPER, \
    "joint servo rate gain Kqd (SPEC §8)") \
  /* ---- [thrusters]: the thruster loops and the motors (SPEC §3.4, §5, §7.4) ---- */ \
  X(ENUM, UVMS_DRIVE_VOLTAGE, drive, drive, "thrusters.drive", P(propulsion.drive), enum, "-", \
    EITHER({"current", UVMS_DRIVE_CURRENT}, {"voltage", UVMS_DRIVE_VOLTAGE}), PAPER, \
    "motor power stage (docs/MODEL.md §5): current = the current follows the controller's " \
    "integrated command over the tick (the paper's reading); voltage = V [53] is held") \
  X(ENUM, UVMS_ALLOC_MIN_POWER, alloc_mode, alloc_mode, "thrusters.allocation", FW, enum, \
    "-", EITHER({"pseudoinverse", UVMS_ALLOC_PSEUDOINVERSE}, \
                {"min_power", UVMS_ALLOC_MIN_POWER}), PAPER, \
    "thrust allocation (allocation.h): pseudoinverse = least Σ P² [38]; min_power = least " \
    "Σ|T|^1.5 delivering the pseudoinverse's wrench (alloc_power.h)") \
  X(SWITCH, , feedforward_lead, feedforward_lead, "control.feedforward_lead", FW, bool, "-", ANY, \
    PAPER, "lead the feedforward wrench by the thruster chain's ramp lag (KB + b/J)/(KA·KB), " \
    "docs/MODEL.md §7.5; current drive only; false: the paper's feedforward") \
  X(NONE, , , , "thrusters.motor", RULE, enum, "-", ONE_OF_FN(MotorSetChoices), \
    VAL("paper"), "named propeller + motor parameter set (sil/scenario/motor_sets.cpp, docs/MODEL.md §5): " \
    "fills the ten propeller and motor keys below; a key given explicitly overrides the set's " \
    "value. These keys describe every thruster whose table names no type") \
  UVMS_THRUSTER_PARAM_ROWS_(UVMS_THRUSTER_KEY_ROW_, X) \
  X(NONE, , , , "thrusters.type", RULE, array, "-", TABLES, NOTE("none"), \
    "[[thrusters.type]] a thruster type, one table each (at most 8), for thrusters whose " \
    "propeller or motor differ from the [thrusters] keys'; a [[thrusters.thruster]] names it " \
    "with type = \"name\"") \
  X(NONE, , , , "thrusters.type[].name", RULE, string, "-", NONEMPTY, NOTE("required"), \
    "the type's name, unique") \
  X(NONE, , , , "thrusters.type[].motor", RULE, enum, "-", ONE_OF_FN(MotorSetChoices), \
    NOTE("the [thrusters] values"), \
    "named parameter set the type starts from (as thrusters.motor); its keys below override it") \
  UVMS_THRUSTER_PARAM_ROWS_(UVMS_THRUSTER_TYPE_ROW_, X) \
  X(NONE, , , , "thrusters.thruster", RULE_P(thrusters), array, "-", TABLES, PAPER, \
    "[[thrusters.thruster]] the thruster layout, one table per thruster (1..8, " \
    "UVMS_MAX_THRUSTERS), replacing the paper's (SPEC §3.4) in both models; it must produce " \
    "every wrench (rank 6: an error names the axes a layout cannot push or turn about)") \
  X(NONE, , , , "thrusters.thruster[].position_m", \
    ELEM_P(thrusters, plant::ThrusterGeometry, position_m), vec3, "m", ANY, NOTE("required"), \
    "a_j: the thruster's point from the vehicle CoM, vehicle frame") \
  X(NONE, , , , "thrusters.thruster[].type", RULE, string, "-", NONEMPTY, \
    NOTE("the [thrusters] keys"), "the name of this thruster's [[thrusters.type]]") \
  X(NONE, , , , "thrusters.thruster[].thrust_limit_N", RULE, real, "N", GE(0), \
    NOTE("limits.thrust_limit_N"), \
    "this thruster's |thrust| limit (0: none), e.g. a smaller propeller or a weaker ESC") \
  X(NONE, , , , "thrusters.thruster[].direction", \
    ELEM_P(thrusters, plant::ThrusterGeometry, direction), vec3, "-", \
    NONZERO(UVMS_ALLOC_MIN_DIRECTION_NORM), NOTE("required"), \
    "u_j: the direction of positive thrust, vehicle frame; normalised to unit length") \
  X(COUNT, UVMS_MAX_THRUSTERS, thrusters.num_thrusters, num_thrusters, "", FW, int, "-", ANY, \
    PAPER, "number of thrusters n, set from [[thrusters.thruster]]") \
  X(REAL, [8][3], thrusters.position_m, thruster_position_m, "", FW, array, "m", ANY, PAPER, \
    "thruster positions a_j, vehicle frame, set from [[thrusters.thruster]]") \
  X(REAL, [8][3], thrusters.direction, thruster_direction, "", FW, array, "-", ANY, PAPER, \
    "thruster directions u_j (unit), vehicle frame, set from [[thrusters.thruster]]") \
  /* ---- [limits]: the controller's fault handling (docs/FAULTS.md); 0 switches a check off ---- */ \
  X(REAL, , limits.max_vehicle_speed_m_s, max_vehicle_speed_m_s, "limits.max_vehicle_speed_m_s", \
    FW, real, "m/s", GE(0), PAPER, "sensed |v0| above it: record rejected") \
  X(REAL, , limits.max_vehicle_rate_rad_s, max_vehicle_rate_rad_s, \
    "limits.max_vehicle_rate_rad_s", FW, real, "rad/s", GE(0), PAPER, \
    "sensed |ω0| above it: record rejected") \
  X(REAL, , limits.max_joint_rate_rad_s, max_joint_rate_rad_s, "limits.max_joint_rate_rad_s", FW, \
    real, "rad/s", GE(0), PAPER, "a sensed joint rate above it: record rejected") \
  X(REAL, , limits.max_motor_speed_rad_s, max_motor_speed_rad_s, "limits.max_motor_speed_rad_s", \
    FW, real, "rad/s", GE(0), PAPER, "a usable motor's speed above it: record rejected") \
  X(REAL, , limits.max_motor_current_A, max_motor_current_A, "limits.max_motor_current_A", FW, \
    real, "A", GE(0), PAPER, "a usable motor's current above it: record rejected") \
  X(REAL, , limits.quat_norm_tol, quat_norm_tol, "limits.quat_norm_tol", FW, real, "-", GE(0), \
    PAPER, "||q| − 1| above it: record rejected (uvms_ctrl_init accepts ≤ 0.5)") \
  X(REAL, [8], limits.thrust_limit_N, thrust_limit_N, "", FW, array, "N", ANY, PAPER, \
    "|thrust| limit of each thruster (0: none), set from limits.thrust_limit_N and " \
    "[[thrusters.thruster]] thrust_limit_N") \
  X(NONE, , , , "limits.thrust_limit_N", RULE, real, "N", GE(0), \
    FN(PaperThrustLimitDefault, "the paper's"), \
    "|thrust| limit of every thruster without its own (0: none); saturation keeps the " \
    "direction, attitude first") \
  X(U32, , limits.sensor_hold_max_ticks, sensor_hold_max_ticks, "limits.sensor_hold_max_ticks", FW, \
    int, "ticks", INT(0, UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT), PAPER, \
    "rejected records bridged with the last good one, then zero thrust") \
  /* ---- [payload] (SPEC §2, §3.2): the same payload for the controller's model and the plant ---- */ \
  X(REAL, , arm.payload_kg, payload_kg, "payload.mass_kg", P(payload_kg), real, "kg", GE(0), PAPER, \
    "payload mass (0, 1, 2, 5, 10 in the sweeps); selects the auto θF column") \
  X(REAL, [3], arm.payload_offset_m, payload_offset_m, "payload.offset_m", P(payload_offset_m), \
    vec3, "m", ANY, PAPER, "EE → payload, frame N") \
  /* ---- [arm]: simplifications for model studies (SPEC §9 item 8), in both models ---- */ \
  X(NONE, , , , "arm.mass_scale", RULE, real, "-", GE(0), VAL(1.0), \
    "multiplies every link's mass and inertia in the controller's model (arm.link[i]) and the " \
    "plant (links[i]); 0: a massless arm, as in the analytic model") \
  X(NONE, , , , "arm.hydrodynamics", RULE, bool, "-", ANY, VAL(true), \
    "false: link diameter 0 in both models (no volume, buoyancy, drag or added mass)") \
  X(NONE, , , , "arm.link", RULE, array, "-", TABLES, NOTE("the paper's WAM arm (SPEC §3.1)"), \
    "[[arm.link]] the arm, one table per link from the base (1..7 joints, UVMS_MAX_JOINTS), " \
    "standard DH (link i: Rz(θ_i), then d_i along z, a_i along x, Rx(α_i)), optionally " \
    "followed by a fixed placement (general links); replaces the paper's arm in both models. " \
    "The trajectory then needs explicit angles") \
  X(COUNT, UVMS_MAX_JOINTS, arm.num_joints, num_joints, "", FW, int, "-", ANY, PAPER, \
    "number of joints N, set from [[arm.link]]") \
  X(LINK, [7], alpha_rad, link_alpha_rad, "arm.link[].alpha_rad", ELEM_P(links, ArmLink, alpha_rad), \
    real, "rad", ANY, NOTE("required"), "DH twist α_i") \
  X(LINK, [7], a_m, link_a_m, "arm.link[].a_m", ELEM_P(links, ArmLink, a_m), real, "m", ANY, \
    NOTE("required"), "DH length a_i") \
  X(LINK, [7], d_m, link_d_m, "arm.link[].d_m", ELEM_P(links, ArmLink, d_m), real, "m", ANY, \
    NOTE("required"), "DH offset d_i") \
  X(LINK, [7][3], placement_m, link_placement_m, "arm.link[].placement_m", \
    ELEM_P(links, ArmLink, placement_m), vec3, "m", ANY, PAPER, \
    "general link (docs/MODEL.md §2): a fixed translation t_i after the DH transform, in the " \
    "frame after Rx(α_i); with placement_rotvec_rad, frame i = frame i−1·Rz(θ)·Tz(d)·Tx(a)·" \
    "Rx(α)·T(t_i)·Rot(ρ_i) (0, 0: standard DH)") \
  X(LINK, [7][3], placement_rotvec_rad, link_placement_rotvec_rad, \
    "arm.link[].placement_rotvec_rad", ELEM_P(links, ArmLink, placement_rotvec_rad), vec3, "rad", \
    ANY, PAPER, "ρ_i: the fixed rotation after t_i, a rotation vector (unit axis × angle); " \
    "joint i+1 turns about the z axis of the frame it gives") \
  X(LINK, [7], mass_kg, link_mass_kg, "arm.link[].mass_kg", ELEM_P(links, ArmLink, mass_kg), real, \
    "kg", GE(0), NOTE("required"), "link mass m_i") \
  X(LINK, [7][3], com_m, link_com_m, "arm.link[].com_m", ELEM_P(links, ArmLink, com_m), vec3, "m", \
    ANY, PAPER, "proximal joint → link CoM, frame i") \
  X(LINK, [7][3], inertia_kg_m2, link_inertia_kg_m2, "arm.link[].inertia_kg_m2", \
    ELEM_P(links, ArmLink, inertia_kg_m2), vec3, "kg·m²", \
    SPECIAL("≥ 0, each at most the sum of the other two (with inertia_products_kg_m2: the " \
    "tensor's eigenvalues)"), PAPER, \
    "diagonal (I_xx, I_yy, I_zz) of the link's inertia about its CoM, frame-i axes") \
  X(LINK, [7][3], inertia_products_kg_m2, link_inertia_products_kg_m2, \
    "arm.link[].inertia_products_kg_m2", ELEM_P(links, ArmLink, inertia_products_kg_m2), vec3, \
    "kg·m²", ANY, PAPER, \
    "off-diagonal entries (I_xy, I_xz, I_yz) of that tensor as they stand in it (I_xy = " \
    "−∫x·y dm, URDF's ixy; a tool that reports +∫x·y dm needs them negated); 0: principal axes") \
  X(LINK, [7], diameter_m, link_diameter_m, "arm.link[].diameter_m", \
    ELEM_P(links, ArmLink, diameter_m), real, "m", GE(0), NOTE("required"), \
    "hydrodynamic cylinder diameter d_L along the link (0: no volume, buoyancy, drag or added " \
    "mass)") \
  X(LINK, [7], drag_coeff, link_drag_coeff, "arm.link[].drag_coeff", \
    ELEM_P(links, ArmLink, drag_coeff), real, "-", GE(0), PAPER, "cross-flow drag coefficient C_D0L") \
  X(LINK, [7][6], added_mass_kg, link_added_mass_kg, "arm.link[].added_mass_kg", \
    ELEM_P(links, ArmLink, added_mass_kg), array, "kg ×3, kg·m² ×3", REALS_GE(6, 0), PAPER, \
    "the link's own added mass, diagonal on (a; ω̇) of its center of buoyancy, frame-i axes " \
    "(docs/MODEL.md §3.3); all 0: ρ·V_i·vehicle.added_mass_coeff. Needs diameter_m > 0") \
  X(LINK, [7], joint_min_rad, joint_min_rad, "arm.link[].joint_min_rad", \
    ELEM(ArmLink, joint_min_rad), real, "rad", ANY, PAPER, \
    "lower joint limit (the controller's sensor plausibility check)") \
  X(LINK, [7], joint_max_rad, joint_max_rad, "arm.link[].joint_max_rad", \
    ELEM(ArmLink, joint_max_rad), real, "rad", ANY, PAPER, "upper joint limit, above the lower") \
  X(REAL, [36], arm.added_mass_coeff, added_mass_coeff, "vehicle.added_mass_coeff", \
    RULE_P(added_mass_coeff), array, "-", SPECIAL("36 finite numbers, a symmetric positive " \
    "semidefinite 6×6 matrix"), PAPER, \
    "added-mass coefficients Ma0 (SPEC §3.3), row-major 6×6 on (v̇; ω̇), body frame, per unit " \
    "ρ·V: the vehicle's added mass is ρ·V0·Ma0 and each link's ρ·V_i·Ma0 (both models)") \
  /* ---- [vehicle] (SPEC §3.2) ---- */ \
  X(NONE, , , , "vehicle.added_mass_kg", RULE_P(vehicle.added_mass_kg), array, \
    "kg, kg·m, kg·m²", SPECIAL("36 finite numbers, a symmetric positive semidefinite 6×6 " \
    "matrix"), NOTE("ρ·V0·Ma0"), \
    "the vehicle's own added mass, absolute, row-major 6×6 on (v̇; ω̇) at the center of " \
    "buoyancy, vehicle frame, as identification papers give it; replaces ρ·V0·Ma0 for the " \
    "vehicle only (plant: the controller's model has v̇0 = ω̇0 = 0)") \
  X(NONE, , , , "vehicle.position_m", H(initial.r0_m), vec3, "m", ANY, PAPER, \
    "initial r0, inertial; the vehicle starts at rest") \
  X(NONE, , , , "vehicle.attitude_rpy_deg", RULE_H(initial.attitude), vec3, "deg", ANY, \
    VAL(Json::array({0.0, 0.0, 0.0})), \
    "initial attitude [roll, pitch, yaw], R = Rz(yaw)·Ry(pitch)·Rx(roll)") \
  X(REAL, [3], arm.vehicle.cob_m, vehicle_cob_m, "vehicle.cob_m", P(vehicle.cob_m), vec3, "m", ANY, \
    PAPER, "center of buoyancy from the CoM, vehicle frame") \
  X(REAL, , arm.vehicle.mass_kg, vehicle_mass_kg, "vehicle.mass_kg", P(vehicle.mass_kg), real, \
    "kg", GT(0), PAPER, "vehicle mass m0 without the arm, payload and trim ballast") \
  X(REAL, , arm.vehicle.volume_m3, vehicle_volume_m3, "vehicle.volume_m3", P(vehicle.volume_m3), \
    real, "m³", GE(0), PAPER, "displaced volume V0: buoyancy ρ·V0·g, and the added mass ρ·V0·Ma0") \
  X(REAL, , arm.vehicle.frontal_area_m2, vehicle_frontal_area_m2, "vehicle.frontal_area_m2", \
    P(vehicle.frontal_area_m2), real, "m²", GE(0), PAPER, \
    "frontal area A0 of the drag ½ρ·C_D0·A0·|w|·w (SPEC §3.2)") \
  X(REAL, , arm.vehicle.drag_coeff, vehicle_drag_coeff, "vehicle.drag_coeff", \
    P(vehicle.drag_coeff), real, "-", GE(0), PAPER, "drag coefficient C_D0 (SPEC §3.2)") \
  X(REAL, [6], arm.vehicle.linear_damping, vehicle_linear_damping, "vehicle.linear_damping", \
    P(vehicle.linear_damping), array, "N·s/m ×3, N·m·s/rad ×3", REALS_GE(6, 0), PAPER, \
    "Fossen's diagonal linear damping D_L on the velocity relative to the fluid, (u, v, w, p, " \
    "q, r) in the vehicle frame (docs/MODEL.md §3.2); adds to the drag of C_D0 (both models)") \
  X(REAL, [6], arm.vehicle.quadratic_damping, vehicle_quadratic_damping, \
    "vehicle.quadratic_damping", P(vehicle.quadratic_damping), array, \
    "N·s²/m² ×3, N·m·s²/rad² ×3", REALS_GE(6, 0), PAPER, \
    "Fossen's diagonal quadratic damping D_Q: τ_k = −(D_L,k + D_Q,k·|ν_k|)·ν_k (both models)") \
  X(REAL, [3], arm.vehicle.inertia_kg_m2, vehicle_inertia_kg_m2, "vehicle.inertia_kg_m2", \
    RULE_P(vehicle.inertia_kg_m2), vec3, "kg·m²", SPECIAL("principal moments > 0, each at most the " \
    "sum of the other two"), PAPER, \
    "principal moments of inertia about the CoM, along the vehicle axes") \
  X(REAL, [3], arm.vehicle.base_offset_m, base_offset_m, "vehicle.arm_base_m", \
    P(vehicle.base_offset_m), vec3, "m", ANY, PAPER, \
    "s0: the arm's base point (joint 1) from the vehicle CoM, vehicle frame") \
  X(REAL, [3], arm.vehicle.base_rotvec_rad, base_rotvec_rad, "vehicle.arm_base_rotvec_rad", \
    P(vehicle.base_rotvec_rad), vec3, "rad", ANY, PAPER, \
    "the arm base frame's rotation from the vehicle axes, a rotation vector (unit axis × " \
    "angle); joint 1 turns about its z axis (0: the vehicle's z, SPEC §2)") \
  X(NONE, , , , "vehicle.hull_size_m", P(vehicle.hull_size_m), vec3, "m", GT(0), PAPER, \
    "the hull as a box: edge lengths along the vehicle axes (plant: contact monitor; the run " \
    "log's scene message: drawing)") \
  X(NONE, , , , "vehicle.hull_center_m", P(vehicle.hull_center_m), vec3, "m", ANY, PAPER, \
    "the hull box's center from the vehicle CoM, vehicle frame") \
  X(REAL, , arm.vehicle.ballast_kg, ballast_kg, "", FW, real, "kg", ANY, PAPER, \
    "trim ballast mass (SPEC §6.3), set from environment.trim") \
  X(REAL, [3], arm.vehicle.ballast_offset_m, ballast_offset_m, "", FW, vec3, "m", ANY, PAPER, \
    "trim ballast point from the CoM, vehicle frame (SPEC §6.3), set from environment.trim") \
  /* ---- [trajectory] (SPEC §8) ---- */ \
  X(ENUM, UVMS_TRAJ_CARTESIAN_LINE, traj_mode, traj_mode, "trajectory.mode", FW, enum, "-", \
    ONE_OF({"joint_cycloid", UVMS_TRAJ_JOINT_CYCLOID}, {"cartesian_line", UVMS_TRAJ_CARTESIAN_LINE}, \
           {"hold", UVMS_TRAJ_HOLD}), PAPER, "how the joint reference is made") \
  X(REAL, , traj_start_s, traj_start_s, "trajectory.start_s", FW, real, "s", GE(0), PAPER, \
    "time the motion begins") \
  X(REAL, , traj_duration_s, traj_duration_s, "trajectory.duration_s", FW, real, "s", GT(0), PAPER, \
    "tF of both modes (also cart.duration_s); separate from run.duration_s") \
  X(REAL, [7], theta_start_rad, theta_start_rad, "trajectory.theta_start_deg", RULE, array, "deg", \
    SPECIAL("N finite numbers (N joints)"), FN(ThetaStartDegDefault, nullptr), \
    "θI; also the plant's initial joint angles; required with [[arm.link]]") \
  X(REAL, [7], theta_final_rad, theta_final_rad, "trajectory.theta_final_deg", RULE, array, "deg", \
    SPECIAL("\"auto\" | \"printed\" | \"vehicle\" | N finite numbers"), VAL("auto"), \
    "θF of the joint cycloid (SPEC §8's two readings): \"auto\" = same task, the column of the " \
    "reference and payload (10 kg joint 1 corrected, docs/MODEL.md C26); \"printed\" = the same " \
    "as printed; \"vehicle\" = same motion, the \"Veh.\" column for every case; the names are " \
    "the paper arm's, so with [[arm.link]] N angles are required (joint_cycloid)") \
  /* ---- [trajectory.cartesian]: the straight EE line (SPEC §8 [78]; cartesian_line mode) ---- */ \
  X(REAL, , cart.distance_m, cart_distance_m, "trajectory.cartesian.distance_m", FW, real, "m", ANY, \
    PAPER, "line length rΔ") \
  X(REAL, [3], cart.direction, cart_direction, "trajectory.cartesian.direction", FW, vec3, "-", \
    NONZERO(UVMS_TRAJ_MIN_DIRECTION_NORM), PAPER, "line direction, inertial; normalised by the " \
    "firmware") \
  X(REAL, , cart.damping_m, cart_damping_m, "trajectory.cartesian.damping_m", FW, real, "m", GT(0), \
    PAPER, "DLS damping λ") \
  X(REAL, , cart.position_gain_1_s, cart_position_gain_1_s, \
    "trajectory.cartesian.position_gain_1_s", FW, real, "1/s", GE(0), PAPER, "CLIK gain K") \
  X(REAL, , cart.nullspace_gain_1_s, cart_nullspace_gain_1_s, \
    "trajectory.cartesian.nullspace_gain_1_s", FW, real, "1/s", GE(0), PAPER, \
    "null-space gain k0 toward the start pose") \
  X(REAL, , cart.max_joint_rate_rad_s, cart_max_joint_rate_rad_s, \
    "trajectory.cartesian.max_joint_rate_rad_s", FW, real, "rad/s", GT(0), PAPER, \
    "joint-rate limit of the rate law") \
  X(REAL, , cart.duration_s, cart_duration_s, "", FW, real, "s", ANY, PAPER, \
    "tF of the line, set from trajectory.duration_s") \
  X(ENUM, UVMS_REF_BARYCENTER, cart.reference, cart_reference, "", FW, enum, "-", ANY, PAPER, \
    "the line's reference, set from control.position_reference") \
  /* ---- [environment] (SPEC §3.2, §6) ---- */ \
  X(NONE, , , , "environment.density_kg_m3", P(env.density_kg_m3), real, "kg/m³", GT(0), PAPER, \
    "plant ρ; also the controller model's unless set apart below") \
  X(NONE, , , , "environment.density_error", RULE_H(density_error), bool, "-", ANY, PAPER, \
    "true: the controller's model uses 1000 kg/m³ (SPEC §6.2)") \
  X(REAL, , fluid.density_kg_m3, density_kg_m3, "environment.model_density_kg_m3", RULE, real, \
    "kg/m³", GT(0), NOTE("`density_kg_m3`, or 1000 with `density_error`"), \
    "the controller model's ρ; with density_error both must agree") \
  X(REAL, [3], fluid.gravity_m_s2, gravity_m_s2, "environment.gravity_m_s2", \
    RULE_P(env.gravity_m_s2), vec3, "m/s²", \
    SPECIAL("\"paper\" (0) | \"earth\" (0, 0, −9.81) | \"europa\" (0, 0, −1.315) | [gx, gy, gz]"), \
    PAPER, "gravity in both models (SPEC §6.3; presets: the plant's GravityPreset)") \
  X(NONE, , , , "environment.trim", RULE_P(env.trim), bool, "-", ANY, PAPER, \
    "trim ballast (SPEC §6.3; default: on when gravity ≠ 0); the controller's model carries " \
    "the same ballast (arm.vehicle.ballast_kg, ballast_offset_m)") \
  X(NONE, , , , "environment.trim_payload_kg", P(env.trim_payload_kg), real, "kg", GE(0), PAPER, \
    "nominal payload the trim is computed for") \
  X(NONE, , , , "environment.metacentric_height_m", P(env.metacentric_height_m), real, "m", GE(0), \
    PAPER, "h: the ballast puts the center of gravity h below the center of buoyancy, stowed " \
    "(θI, trim payload) and level (SPEC §6.3)") \
  X(NONE, , , , "environment.ballast_error_m", P(env.ballast_error_m), vec3, "m", ANY, PAPER, \
    "plant only: the ballast displaced from its trim point, vehicle frame (a trim error; the " \
    "controller's model keeps the trim point)") \
  X(REAL, [3], fluid.flow_m_s, flow_m_s, "environment.steady_flow_m_s", P(env.steady_flow_m_s), \
    vec3, "m/s", ANY, PAPER, "steady flow v∞0, inertial; the only flow the controller sees") \
  X(NONE, , , , "environment.angle_of_attack", P(env.angle_of_attack), bool, "-", ANY, PAPER, \
    "plant: C_D = C_D0L·sin²α [21]") \
  X(FLAG, , fluid.angle_of_attack, angle_of_attack, "environment.model_angle_of_attack", RULE, \
    bool, "-", ANY, NOTE("`angle_of_attack`"), "the same in the controller's model") \
  X(NONE, , , , "environment.variable_coefficients", P(env.variable_coefficients), bool, "-", ANY, \
    PAPER, "SPEC §6.4, plant only; the firmware model has constant coefficients") \
  X(NONE, , , , "environment.coeff_table", RULE_P(env.coeff_table), array, "-", TABLES, \
    FN(CoeffTableDefault, "the plant's `DefaultCoeffTable()` (an approximation)"), \
    "[[environment.coeff_table]] rows, distances strictly increasing; needs " \
    "variable_coefficients = true") \
  X(NONE, , , , "environment.coeff_table[].distance_diameters", \
    ELEM_P(env.coeff_table, plant::CoeffTableRow, distance_diameters), real, "link diameters", \
    GE(0), NOTE("required"), "distance travelled by the aerodynamic center") \
  X(NONE, , , , "environment.coeff_table[].drag_factor", \
    ELEM_P(env.coeff_table, plant::CoeffTableRow, drag_factor), real, "-", GE(0), PAPER, \
    "multiplies C_D0L") \
  X(NONE, , , , "environment.coeff_table[].added_mass_factor", \
    ELEM_P(env.coeff_table, plant::CoeffTableRow, added_mass_factor), real, "-", GE(0), PAPER, \
    "multiplies the link's added mass") \
  /* ---- [environment.unsteady_flow] (SPEC §6.1 [28]; period = run.duration_s, seed = run.seed) */ \
  X(NONE, , , , "environment.unsteady_flow.enabled", P(env.unsteady.enabled), bool, "-", ANY, \
    PAPER, "unsteady flow on (the plant only; the controller sees v∞0)") \
  X(NONE, , , , "environment.unsteady_flow.amplitude_m_s", P(env.unsteady.amplitude_m_s), real, \
    "m/s", GE(0), PAPER, "amplitude Av") \
  X(NONE, , , , "environment.unsteady_flow.harmonics", P(env.unsteady.harmonics), int, "-", \
    INT(0, plant::UnsteadyFlow::kMaxHarmonics), PAPER, "number of harmonics n") \
  /* ---- [integrator]: CVODE (SPEC §5; plant only) ---- */ \
  X(NONE, , , , "integrator.method", P(integrator.method), enum, "-", \
    ONE_OF({"adams", static_cast<long>(plant::IntegratorParams::Method::kAdams)}, \
           {"bdf", static_cast<long>(plant::IntegratorParams::Method::kBdf)}), PAPER, \
    "linear multistep method") \
  X(NONE, , , , "integrator.rel_tol", P(integrator.rel_tol), real, "-", GT(0), PAPER, \
    "relative tolerance") \
  X(NONE, , , , "integrator.abs_tol", P(integrator.abs_tol), real, "state units", GT(0), PAPER, \
    "absolute tolerance") \
  X(NONE, , , , "integrator.max_steps", P(integrator.max_steps), int, "-", INT_GE(1), PAPER, \
    "steps per tick at most") \
  X(NONE, , , , "integrator.motor_speed_abs_tol", P(integrator.motor_speed_abs_tol_rad_s), real, \
    "rad/s", GT(0), PAPER, "absolute tolerance of the motor speeds (abs_tol's for the rest)") \
  X(NONE, , , , "integrator.early_step_growth_max", P(integrator.early_step_growth_max), real, "-", \
    GT(1), PAPER, "largest step growth in the first steps after each tick's restart") \
  /* ---- [contact]: contact monitor (SPEC §5; plant only) ---- */ \
  X(NONE, , , , "contact.enabled", P(contact.enabled), bool, "-", ANY, PAPER, \
    "links, hull and obstacles checked every tick") \
  X(NONE, , , , "contact.clearance_m", P(contact.clearance_m), real, "m", GE(0), PAPER, \
    "a distance below this ends the run") \
  X(NONE, , , , "contact.self_collision", P(contact.self_collision), bool, "-", ANY, PAPER, \
    "link–link checks (off: the paper's stowed pose overlaps itself, see params.hpp)") \
  X(NONE, , , , "contact.obstacle", RULE_P(contact.obstacles), array, "-", TABLES, \
    PAPER, "[[contact.obstacle]] vertical cylinders; replaces the list") \
  X(NONE, , , , "contact.obstacle[].name", ELEM_P(contact.obstacles, plant::CylinderObstacle, name), \
    string, "-", NONEMPTY, PAPER, "obstacle name") \
  X(NONE, , , , "contact.obstacle[].base_center_m", \
    ELEM_P(contact.obstacles, plant::CylinderObstacle, base_center_m), vec3, "m", ANY, PAPER, \
    "center of the bottom disc, inertial") \
  X(NONE, , , , "contact.obstacle[].height_m", \
    ELEM_P(contact.obstacles, plant::CylinderObstacle, height_m), real, "m", GT(0), PAPER, "height") \
  X(NONE, , , , "contact.obstacle[].radius_m", \
    ELEM_P(contact.obstacles, plant::CylinderObstacle, radius_m), real, "m", GT(0), PAPER, "radius") \
  /* ---- [link]: the lockstep link (harness) ---- */ \
  X(NONE, , , , "link.timeout_s", H(link.timeout_s), real, "s", GT(0), PAPER, \
    "wall-clock wait for a tick's actuators (udpm; in memq mode none: nothing can arrive late)") \
  X(NONE, , , , "link.max_missed", H(link.max_missed), int, "-", INT(1, 1000000), PAPER, \
    "consecutive missed ticks that stop the run") \
  X(NONE, , , , "link.realtime_factor", H(link.realtime_factor), real, "-", GE(0), PAPER, \
    "0: as fast as possible; r > 0: r × real time") \
  X(NONE, , , , "link.publish_truth", H(link.publish_truth), bool, "-", ANY, PAPER, \
    "truth_t also published on the link for live listeners (always in the log)") \
  X(NONE, , , , "link.spin_us", H(link.spin_us), int, "µs", INT(0, UVMS_SPIN_US_MAX), PAPER, \
    "udpm: busy-poll the link this long before blocking (sil/link/lcm_wait.h); 0 in paced runs") \
  /* ---- [verdict]: when a run that completed its ticks still fails (harness; docs/FAULTS.md) ---- */ \
  X(NONE, , , , "verdict.max_error_tick_share", H(verdict.max_error_tick_share), real, "-", PROB, \
    PAPER, "controller error status (actuators_t.status ≠ UVMS_OK) on a larger share of the " \
    "ticks: failed, controller_errors") \
  X(NONE, , , , "verdict.max_attitude_error_rad", H(verdict.max_attitude_error_rad), real, "rad", \
    GE(0), PAPER, "max attitude error (against t = 0) above it: failed, diverged") \
  X(NONE, , , , "verdict.max_vehicle_excursion_m", H(verdict.max_vehicle_excursion_m), real, "m", \
    GE(0), PAPER, "max |r0 − r0(0)| above it: failed, diverged") \
  X(NONE, , , , "verdict.max_ee_error_m", H(verdict.max_ee_error_m), real, "m", GE(0), PAPER, \
    "max EE error (SPEC §10) above it: failed, diverged") \
  X(NONE, , , , "verdict.max_thrust_loss_s", H(verdict.max_thrust_loss_s), real, "s", GE(0), \
    PAPER, "thrust lost (the thrusters produce under 1 % of the commanded thrust) for longer: " \
    "failed, thrust_lost") \
  /* ---- [metrics]: the run's analyses into summary.json (harness; docs/MODEL.md §10) ---- */ \
  X(NONE, , , , "metrics.ee_target_m", H(metrics.ee_target_m), vec3, "m", ANY, PAPER, \
    "the paper's target point, SPEC §8 (inertial): the task-space error of joint_cycloid and " \
    "hold maneuvers is the EE's distance from it (task_error_* in summary.json)") \
  /* ---- [faults]: fault injection by the harness (docs/FAULTS.md) ---- */ \
  X(NONE, , , , "faults.thruster", RULE_H(faults.thrusters), array, "-", TABLES, \
    PAPER, "[[faults.thruster]] thruster faults, any number") \
  X(NONE, , , , "faults.thruster[].thruster", ELEM_H(faults.thrusters, ThrusterFault, thruster), \
    int, "-", SPECIAL("1..number of thrusters"), NOTE("required"), \
    "j: the j-th table of [[thrusters.thruster]] (SPEC §3.4's numbering by default)") \
  X(NONE, , , , "faults.thruster[].mode", ELEM_H(faults.thrusters, ThrusterFault, mode), enum, "-", \
    EITHER({"off", static_cast<long>(ThrusterFault::Mode::kOff)}, \
           {"stuck", static_cast<long>(ThrusterFault::Mode::kStuck)}, \
           {"efficiency", static_cast<long>(ThrusterFault::Mode::kEfficiency)}), PAPER, \
    "off: no voltage/current; stuck: the stuck value whatever is commanded; efficiency: " \
    "thrust × efficiency") \
  X(NONE, , , , "faults.thruster[].start_s", ELEM_H(faults.thrusters, ThrusterFault, start_s), \
    real, "s", GE(0), PAPER, "the fault acts from the first tick at or after this time") \
  X(NONE, , , , "faults.thruster[].stuck_voltage_V", \
    ELEM_H(faults.thrusters, ThrusterFault, stuck_voltage_V), real, "V", ANY, PAPER, \
    "the stuck driver's voltage (mode stuck, thrusters.drive = \"voltage\" only)") \
  X(NONE, , , , "faults.thruster[].stuck_current_A", \
    ELEM_H(faults.thrusters, ThrusterFault, stuck_current_A), real, "A", ANY, PAPER, \
    "the stuck driver's current (mode stuck, thrusters.drive = \"current\" only)") \
  X(NONE, , , , "faults.thruster[].efficiency", ELEM_H(faults.thrusters, ThrusterFault, efficiency), \
    real, "-", FRACTION, VAL(0.5), "thrust factor (mode efficiency only)") \
  X(NONE, , , , "faults.thruster[].reported", ELEM_H(faults.thrusters, ThrusterFault, reported), \
    bool, "-", ANY, PAPER, "the controller is told (thruster_usable_mask bit cleared) ...") \
  X(NONE, , , , "faults.thruster[].detect_delay_s", \
    ELEM_H(faults.thrusters, ThrusterFault, detect_delay_s), real, "s", GE(0), PAPER, \
    "... this long after start_s") \
  UVMS_SENSOR_FAULT_ROWS_(X, position, "m", "m", position_m) \
  UVMS_SENSOR_FAULT_ROWS_(X, attitude, "rad", "rad", attitude_rad) \
  UVMS_SENSOR_FAULT_ROWS_(X, velocity, "m_s", "m/s", velocity_m_s) \
  UVMS_SENSOR_FAULT_ROWS_(X, angular_velocity, "rad_s", "rad/s", angular_velocity_rad_s) \
  UVMS_SENSOR_FAULT_ROWS_(X, joint_position, "rad", "rad", joint_position_rad) \
  UVMS_SENSOR_FAULT_ROWS_(X, joint_velocity, "rad_s", "rad/s", joint_velocity_rad_s) \
  UVMS_SENSOR_FAULT_ROWS_(X, motor_speed, "rad_s", "rad/s", motor_speed_rad_s) \
  UVMS_SENSOR_FAULT_ROWS_(X, motor_current, "A", "A", motor_current_A) \
  X(NONE, , , , "faults.link.drop_rate", H(faults.link.drop_rate), real, "-", PROB, PAPER, \
    "probability that a message is lost") \
  X(NONE, , , , "faults.link.delay_rate", H(faults.link.delay_rate), real, "-", PROB, PAPER, \
    "... arrives one tick late (then dropped as out of sequence)") \
  X(NONE, , , , "faults.link.duplicate_rate", H(faults.link.duplicate_rate), real, "-", PROB, PAPER, \
    "... arrives twice (the copy is dropped and counted)") \
  X(NONE, , , , "faults.link.corrupt_rate", H(faults.link.corrupt_rate), real, "-", PROB, PAPER, \
    "... has one bit flipped (the receiver's CRC check rejects it); the four add up to ≤ 1") \
  X(NONE, , , , "faults.link.sensors", H(faults.link.sensors), bool, "-", ANY, PAPER, \
    "apply to sensors_t (plant → controller)") \
  X(NONE, , , , "faults.link.actuators", H(faults.link.actuators), bool, "-", ANY, PAPER, \
    "apply to actuators_t (controller → plant)")

/* The propeller, motor and loop parameters of a thruster (SPEC §3.4, §5, §7.4), one firmware
 * set per thruster (uvms_ctrl_config_t.thruster[j]): R(X, fw, lcm, leaf, target, unit, range,
 * doc) per parameter, expanded twice: as the [thrusters] keys every thruster gets
 * (UVMS_THRUSTER_KEY_ROW_) and as the keys of a [[thrusters.type]] (UVMS_THRUSTER_TYPE_ROW_,
 * applied by a rule to that type's thrusters). The lower bounds of the propeller and motor
 * keys are physical, far below any thruster's (paper set, T200 set): thrust ∝ ρD⁴ω², so a
 * propeller of millimetres pushes next to nothing at any speed a motor reaches; no motor that
 * turns a propeller has a winding, an inductance, a torque constant or a rotor below these. */
#define UVMS_THRUSTER_PARAM_ROWS_(R, X) \
  R(X, speed_gain_1_s, speed_gain_1_s, "ka_1_s", FW, "1/s", GT(0), "speed loop gain KA [64]") \
  R(X, current_gain_1_s, current_gain_1_s, "kb_1_s", FW, "1/s", GT(0), "current loop gain KB [66]") \
  R(X, voltage_limit_V, voltage_limit_V, "voltage_limit_V", FW, "V", GT(0), \
    "motor |V| clamp (the paper sets none, see thruster.h)") \
  R(X, diameter_m, propeller_diameter_m, "propeller_diameter_m", P(propulsion.diameter_m), "m", \
    GE(0.01), "propeller diameter D, in the controller's thruster model and the plant's " \
    "propellers; at least 1 cm (T ∝ ρD⁴ω²: 10 N from 1 cm takes ≈ 84,000 rpm with the paper's CT2)") \
  R(X, ct1, ct1, "ct1", P(propulsion.ct1), "-", ANY, "thrust coefficient CT1 (advance term, SPEC §5 [47–52])") \
  R(X, ct2, ct2, "ct2", P(propulsion.ct2), "-", LT(0), \
    "thrust coefficient CT2; < 0 keeps the discriminant of the speed solution ≥ 0 (SPEC §7.4)") \
  R(X, cq1, cq1, "cq1", P(propulsion.cq1), "-", ANY, "torque coefficient CQ1 (advance term, SPEC §5)") \
  R(X, cq2, cq2, "cq2", P(propulsion.cq2), "-", ANY, \
    "torque coefficient CQ2 (the paper's < 0 makes the water drive the shaft: MODEL.md C12)") \
  R(X, resistance_ohm, motor_resistance_ohm, "resistance_ohm", P(propulsion.resistance_ohm), "Ω", \
    GE(1e-3), "armature resistance Rm [53]; at least 1 mΩ (a copper winding with its leads has more)") \
  R(X, inductance_H, motor_inductance_H, "inductance_H", P(propulsion.inductance_H), "H", GE(1e-6), \
    "armature inductance Lm [53]; at least 1 µH (small brushless motors: tens of µH)") \
  R(X, torque_constant_Nm_A, motor_torque_constant_Nm_A, "torque_constant_Nm_A", \
    P(propulsion.torque_constant_Nm_A), "N·m/A", GE(5e-4), "torque constant km = back-EMF " \
    "constant [V·s/rad] [53–55]; at least 5e-4 (≈ 19,000 rpm/V, beyond the fastest small brushless motors)") \
  R(X, viscous_friction_Nm_s, motor_viscous_friction_Nm_s, "viscous_friction_Nm_s", \
    P(propulsion.viscous_friction_Nm_s), "N·m·s", GE(0), "shaft viscous friction b [54–55]") \
  R(X, rotor_inertia_kg_m2, rotor_inertia_kg_m2, "rotor_inertia_kg_m2", \
    P(propulsion.rotor_inertia_kg_m2), "kg·m²", GE(1e-9), \
    "rotor + propeller inertia J [54–55]; at least 1e-9, about a 1 cm propeller's alone")
#define UVMS_THRUSTER_KEY_ROW_(X, fw, lcm, leaf, target, unit, range, doc) \
  X(THR, [8], fw, lcm, "thrusters." leaf, target, real, unit, range, PAPER, doc)
#define UVMS_THRUSTER_TYPE_ROW_(X, fw, lcm, leaf, target, unit, range, doc) \
  X(NONE, , , , "thrusters.type[]." leaf, RULE, real, unit, range, NOTE("the [thrusters] value"), doc)

/* [faults.sensors]: noise (standard deviation) and bias of one sensor group G in its unit U
 * (key suffix S): keys G_noise_S and G_bias_S, targets SensorFaults.<member>.std and .bias. */
#define UVMS_SENSOR_FAULT_ROWS_(X, group, suffix, unit, member) \
  X(NONE, , , , "faults.sensors." #group "_noise_" suffix, H(faults.sensors.member.std), real, \
    unit, GE(0), PAPER, "standard deviation of the zero-mean noise on every component") \
  X(NONE, , , , "faults.sensors." #group "_bias_" suffix, H(faults.sensors.member.bias), real, \
    unit, ANY, PAPER, "added to every component")
/* clang-format on */

/* How each map kind travels in the message and in the PIL record: R(lcm, shape) for a real
 * (double in the message, float in the record), I(lcm) for an integer, nothing for NONE. */
#define UVMS_CFG_WIRE_REAL(R, I, shape, lcm) R(lcm, shape)
#define UVMS_CFG_WIRE_LINK(R, I, shape, lcm) R(lcm, shape)
#define UVMS_CFG_WIRE_THR(R, I, shape, lcm) R(lcm, shape)
#define UVMS_CFG_WIRE_COUNT(R, I, shape, lcm) I(lcm)
#define UVMS_CFG_WIRE_FLAG(R, I, shape, lcm) I(lcm)
#define UVMS_CFG_WIRE_SWITCH(R, I, shape, lcm) I(lcm)
#define UVMS_CFG_WIRE_ENUM(R, I, shape, lcm) I(lcm)
#define UVMS_CFG_WIRE_U32(R, I, shape, lcm) I(lcm)
#define UVMS_CFG_WIRE_NONE(R, I, shape, lcm)

/*
 * Retired choices of enum keys: a name (and its value in the firmware enum and the logs) that
 * once meant something and is never reused. A scenario that names one, or a log whose
 * configuration holds its value, is refused with an error naming the replacement and why.
 *   X(key, name, value, replacement, why)
 */
#define UVMS_RETIRED_CHOICES(X) \
  X("thrusters.allocation", "min_abs_thrust", 1, "min_power", \
    "its least-Σ|T| linear program is degenerate: the optimal vertex jumps between ticks " \
    "(docs/MODEL.md §7.3)")

#endif /* UVMS_SIL_CONFIG_TABLE_H */
