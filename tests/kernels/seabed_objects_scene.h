// seabed_objects_scene.h — the scene the underwater kernels' tests render (kd_multiple's, the froxels',
// the discrete-ordinates kernel's): a camera 4 m down looking slightly down, the sun 30° from the
// zenith behind the camera's left, Jerlov II water over a flat bottom of albedo 0.3, a sphere and a box
// in view and, above the view, a sphere whose shadow the view rays cross. Each test says what differs.
#ifndef SEASIM_TESTS_SEABED_OBJECTS_SCENE_H
#define SEASIM_TESTS_SEABED_OBJECTS_SCENE_H

#include <string>

namespace seasim::test {

struct SeabedObjectsScene {
  std::string name;           // [scene] name
  int width = 40, height = 24;
  double g = -1;              // the water's g; < 0: Jerlov II's own
  double bottom_depth = 5;    // m; 0: no bottom
  bool objects = true;        // the sphere (albedo 0.2) and the box (0.4) in view
  bool shadow_sphere = true;  // the sphere above the view (albedo 0.6)
  std::string more_objects;   // [[objects]] tables after those
  std::string rest;           // the tables after the objects: [underwater], [spectral], [quality]
};

inline std::string seabedObjectsScene(const SeabedObjectsScene& s) {
  auto number = [](double v) {
    std::string t = std::to_string(v);
    t.erase(t.find_last_not_of('0') + 1);
    if (t.back() == '.') t.pop_back();
    return t;
  };
  std::string text = "[scene]\nname = \"" + s.name +
                     "\"\n[camera]\nposition = [0, -4, 0]\nlook_at = [0, -4.5, -8]\nfov_deg = 70\nwidth = " +
                     std::to_string(s.width) + "\nheight = " + std::to_string(s.height) +
                     "\n[sun]\nzenith_deg = 30\nazimuth_deg = 60\n[sky]\nradiance = 0.05\n[water]\njerlov = \"II\"\n";
  if (s.g >= 0) text += "g = " + number(s.g) + "\n";
  if (s.bottom_depth > 0) text += "[bottom]\ntype = \"flat\"\ndepth = " + number(s.bottom_depth) + "\nalbedo = 0.3\n";
  if (s.objects)
    text +=
        "[[objects]]\ntype = \"sphere\"\ncenter = [-1, -4.5, -5]\nradius = 0.8\nalbedo = 0.2\n"
        "[[objects]]\ntype = \"box\"\nmin = [0.8, -5, -7.5]\nmax = [2.2, -3.8, -6.3]\nalbedo = 0.4\n";
  if (s.shadow_sphere) text += "[[objects]]\ntype = \"sphere\"\ncenter = [0.5, -1.5, -6]\nradius = 0.7\nalbedo = 0.6\n";
  return text + s.more_objects + s.rest;
}

}  // namespace seasim::test

#endif
