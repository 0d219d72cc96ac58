// A mesh scene's pressure load, parsed: groups.pressure and [pressure], the pressure s(t) p with
// the load factor s(t) of [loading] (physics/mechanics/surface_pressure.hpp, run/mesh_scene_loads.hpp).
#pragma once

#include <string>
#include <vector>

namespace needlefem {

class Case;

struct PressureSpec {
  std::vector<std::string> groups;  // groups.pressure, the loaded surface groups; empty: no pressure
  double value_pa;                  // p: positive pushes into the tissue
  bool follower;  // on the deformed area along the deformed normal (a fluid's); else a dead load
};

PressureSpec parse_pressure_spec(const Case& c);

}  // namespace needlefem
