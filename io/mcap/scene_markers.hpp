#pragma once
// /owsim/scene of flight.mcap (INTERFACE.md "Robotics output"): every object of the scene as
// built, as visualization_msgs markers in frame `map` (local East-North-Up) that Foxglove's 3D
// panel and rviz show without configuration. One marker an object, its namespace and text the
// object's id, id 0:
//   conductor       LINE_STRIP of its built polyline, line width its diameter but at least 0.1 m
//                   (a 2 cm wire would vanish at a corridor's scale), orange;
//   pole, tree      CYLINDER from its base to its top, its diameter; pole brown, tree green;
//   mesh            TRIANGLE_LIST of its triangles (three points each), coloured by its class
//                   (building grey, pole brown, tree green);
//   fog box         CUBE filling the box, translucent light grey.
// Fog layers and a fog-filled sky are unbounded and the ground is everywhere: neither is drawn
// (the viewers draw their own ground grid).
#include <string>

#include "geometry/scene.hpp"
#include "io/mcap/ros2_messages.hpp"

namespace owsim::ros2 {

[[nodiscard]] MarkerArray scene_markers(const Scene& scene, const Time& stamp);

}  // namespace owsim::ros2
