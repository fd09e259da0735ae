// SPDX-License-Identifier: Apache-2.0
// params.cpp: the paper's parameters (SPEC §3), typed from SPEC, independent of firmware/.
#include "uvms_plant/params.hpp"

#include <cmath>

namespace uvms::plant {

PlantParams PaperPlantParams() {
  PlantParams p;
  const double h = M_PI / 2.0;
  // SPEC §3.1: m [kg], α [rad], a [m], d [m], r [mm], I diag [kg·m²]
  struct Row {
    double m, alpha, a, d, rx, ry, rz, ixx, iyy, izz;
  };
  const Row wam[7] = {
      {10.77, -h, 0.0, 0.0, -4.4, 121.9, -0.7, 0.1349, 0.1133, 0.0905},
      {3.87, h, 0.0, 0.0, -2.4, 31.1, 15.4, 0.0214, 0.0138, 0.0156},
      {1.80, -h, 0.045, 0.550, 6.7, -342.5, 0.0, 0.0591, 0.0032, 0.0593},
      {2.40, h, -0.045, 0.0, -40.0, -0.2, 132.7, 0.0149, 0.0148, 0.0029},
      {0.12, -h, 0.0, 0.300, 0.1, -294.9, 4.4, 0.0001, 0.0001, 0.0001},
      {0.42, h, 0.0, 0.0, -0.1, -17.0, 24.7, 0.0006, 0.0002, 0.0004},
      {0.07, 0.0, 0.0, 0.060, -0.1, 0.2, 56.8, 0.0000, 0.0000, 0.0001},
  };
  for (const Row &r : wam) {
    LinkParams l;
    l.alpha_rad = r.alpha;
    l.a_m = r.a;
    l.d_m = r.d;
    l.mass_kg = r.m;
    l.com_m = Vec3(r.rx, r.ry, r.rz) * 1e-3;
    l.inertia_kg_m2 = Vec3(r.ixx, r.iyy, r.izz);
    p.links.push_back(l);
  }
  // SPEC §8: the stowed pose θI [deg], where the vehicle is trimmed (SPEC §6.3).
  for (const double deg : {180.0, 90.0, 180.0, 180.0, 0.0, 0.0, 0.0})
    p.env.trim_pose_rad.push_back(deg * M_PI / 180.0);
  // SPEC §3.3 [26–27]
  p.added_mass_coeff << 0.1, 0, 0, 0, 0, 0,  //
      0, 0.1, -0.01, 0, 0, 0,                //
      0, -0.01, 0.1, 0, -0.001, 0,           //
      0, 0, 0, 0.01, 0, 0.001,               //
      0, 0, -0.001, 0, 0.01, 0,              //
      0, 0, 0, 0.001, 0, 0.01;
  // SPEC §3.4
  const double tp[8][6] = {
      {-0.5, 0.5, 0.5, 1, 0, 0},  {-0.5, -0.5, 0.5, 1, 0, 0}, {-0.5, 0.5, -0.5, 1, 0, 0},
      {-0.5, -0.5, -0.5, 1, 0, 0}, {0.1, 0.5, 0, 0, 0, 1},     {0.1, -0.5, 0, 0, 0, 1},
      {0.1, 0, 0.5, 0, 1, 0},     {0.1, 0, -0.5, 0, 1, 0},
  };
  for (const auto &t : tp) {
    ThrusterGeometry g;
    g.position_m = Vec3(t[0], t[1], t[2]);
    g.direction = Vec3(t[3], t[4], t[5]);
    p.thrusters.push_back(g);
  }
  return p;
}

}  // namespace uvms::plant
