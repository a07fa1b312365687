// The scene catalogue: the built-in scenes (each built to show or to break something: docs/results/),
// the reflective-fraction scenes of the cost curves, scenes loaded by name or path, and staging a
// model on or as a mirror. The geometry builders are in scene.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "sslr_host/gltf_loader.hpp"
#include "sslr_host/scene.hpp"

namespace sslr::host {

namespace {

int addMaterial(Scene& s, glm::vec3 color, float metallic, float roughness, float emissive = 0.0f) {
  Material m;
  m.baseColor = color;
  m.metallic = metallic;
  m.roughness = roughness;
  m.emissive = emissive;
  s.materials.push_back(m);
  return static_cast<int>(s.materials.size() - 1);
}

Camera perspectiveCamera(glm::dvec3 eye, glm::dvec3 target, double fovyDegrees, double nearPlane, double farPlane) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fovyDegrees = fovyDegrees;
  c.nearPlane = nearPlane;
  c.farPlane = farPlane;
  return c;
}

Scene mirrorRoom() {
  Scene s;
  s.name = "mirror-room";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int brushed = addMaterial(s, glm::vec3(0.85f, 0.8f, 0.7f), 1.0f, 0.3f);
  const int wall = addMaterial(s, glm::vec3(0.75f, 0.72f, 0.68f), 0.0f, 0.9f);
  const int red = addMaterial(s, glm::vec3(0.8f, 0.1f, 0.08f), 0.0f, 0.7f, 0.15f);
  const int green = addMaterial(s, glm::vec3(0.1f, 0.7f, 0.15f), 0.0f, 0.7f, 0.15f);
  const int blue = addMaterial(s, glm::vec3(0.1f, 0.2f, 0.85f), 0.0f, 0.7f, 0.15f);
  const int yellow = addMaterial(s, glm::vec3(0.9f, 0.75f, 0.1f), 0.0f, 0.7f, 0.15f);
  // Floor: a sharp mirror in front, a brushed (rough) strip at the back to show the blur.
  s.meshes.push_back(makeQuad({0, 0, 1.5}, {12, 9}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 0, -4.5}, {12, 3}, {0, 1, 0}, brushed));
  s.meshes.push_back(makeQuad({0, 3, -6}, {12, 6}, {0, 0, 1}, wall));   // back wall
  s.meshes.push_back(makeQuad({-6, 3, 0}, {12, 6}, {1, 0, 0}, wall));   // left wall
  s.meshes.push_back(makeQuad({6, 3, 0}, {12, 6}, {-1, 0, 0}, wall));   // right wall
  s.meshes.push_back(makeBox({-2.2, 0.75, -1.0}, {1.5, 1.5, 1.5}, red, 20.0));
  s.meshes.push_back(makeBox({0.4, 1.25, -2.2}, {1.2, 2.5, 1.2}, green, -10.0));
  s.meshes.push_back(makeBox({2.4, 0.5, -0.4}, {1.0, 1.0, 1.0}, blue, 35.0));
  s.meshes.push_back(makeBox({-0.2, 0.3, 1.2}, {0.6, 0.6, 0.6}, yellow, 0.0));
  s.camera = perspectiveCamera({0.0, 2.6, 7.5}, {0.0, 0.9, -1.0}, 55.0, 0.1, 100.0);
  s.background = glm::vec3(0.25f, 0.3f, 0.4f);
  return s;
}

Scene grazingPlane() {
  Scene s;
  s.name = "grazing-plane";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.05f);
  const int stone = addMaterial(s, glm::vec3(0.7f, 0.6f, 0.5f), 0.0f, 0.9f, 0.1f);
  const int red = addMaterial(s, glm::vec3(0.8f, 0.15f, 0.1f), 0.0f, 0.8f, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -500}, {2000, 2000}, {0, 1, 0}, mirror));
  for (int i = 0; i < 12; ++i) {
    const double z = -8.0 - i * i * 4.0;
    const double x = (i % 2 == 0 ? -1.0 : 1.0) * (3.0 + i * 1.5);
    s.meshes.push_back(makeBox({x, 2.0 + i * 0.5, z}, {1.5, 4.0 + i, 1.5}, i % 3 == 0 ? red : stone));
  }
  s.camera = perspectiveCamera({0.0, 0.6, 5.0}, {0.0, 0.9, -30.0}, 50.0, 0.05, 3000.0);
  s.background = glm::vec3(0.45f, 0.55f, 0.7f);
  return s;
}

Scene thinObjects() {
  Scene s;
  s.name = "thin-objects";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int white = addMaterial(s, glm::vec3(0.9f), 0.0f, 0.8f, 0.2f);
  const int orange = addMaterial(s, glm::vec3(0.9f, 0.4f, 0.1f), 0.0f, 0.8f, 0.2f);
  const int wall = addMaterial(s, glm::vec3(0.3f, 0.35f, 0.45f), 0.0f, 0.9f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {16, 16}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 3, -8}, {16, 6}, {0, 0, 1}, wall));
  for (int i = 0; i < 9; ++i)  // poles
    s.meshes.push_back(makeBox({-4.0 + i, 1.25, -2.0 - 0.3 * i}, {0.06, 2.5, 0.06}, i % 2 ? white : orange));
  for (int k = 0; k < 3; ++k)  // fence rails
    s.meshes.push_back(makeBox({0.0, 0.4 + 0.45 * k, -4.5}, {9.0, 0.05, 0.05}, white));
  for (int i = 0; i < 19; ++i)  // fence pickets
    s.meshes.push_back(makeBox({-4.5 + 0.5 * i, 0.75, -4.5}, {0.04, 1.5, 0.04}, white));
  s.camera = perspectiveCamera({0.0, 1.8, 5.0}, {0.0, 0.8, -3.0}, 50.0, 0.1, 100.0);
  s.background = glm::vec3(0.2f, 0.22f, 0.3f);
  return s;
}

Scene skyHeavy() {
  Scene s;
  s.name = "sky-heavy";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int teal = addMaterial(s, glm::vec3(0.1f, 0.6f, 0.6f), 0.0f, 0.7f, 0.2f);
  s.meshes.push_back(makeBox({0.0, 0.0, 0.0}, {2.0, 0.1, 2.0}, mirror));  // a small mirror slab
  s.meshes.push_back(makeBox({0.0, 0.7, -0.4}, {0.5, 1.2, 0.5}, teal, 30.0));
  s.camera = perspectiveCamera({0.0, 1.2, 6.0}, {0.0, 2.0, 0.0}, 60.0, 0.1, 100.0);
  s.background = glm::vec3(0.5f, 0.65f, 0.85f);
  return s;
}

// Analytic test scenes: simple enough that the tests compute the true reflection by hand.
Scene mirrorBox() {
  Scene s;
  s.name = "mirror-box";
  const int mirror = addMaterial(s, glm::vec3(1.0f), 1.0f, 0.0f);
  const int red = addMaterial(s, glm::vec3(0.9f, 0.2f, 0.1f), 0.0f, 1.0f, 0.3f);
  const int wall = addMaterial(s, glm::vec3(0.2f, 0.5f, 0.8f), 0.0f, 1.0f, 0.3f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {10, 10}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 2.5, -5}, {10, 5}, {0, 0, 1}, wall));
  s.meshes.push_back(makeBox({0.5, 0.75, -1.5}, {1.5, 1.5, 1.5}, red, 25.0));
  s.camera = perspectiveCamera({0.0, 2.0, 5.0}, {0.0, 0.5, -1.0}, 50.0, 0.1, 50.0);
  return s;
}

Scene tiltedMirror() {
  Scene s;
  s.name = "tilted-mirror";
  const int mirror = addMaterial(s, glm::vec3(1.0f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.6f, 0.6f, 0.2f), 0.0f, 1.0f, 0.3f);
  const int wall = addMaterial(s, glm::vec3(0.2f, 0.7f, 0.4f), 0.0f, 1.0f, 0.3f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {12, 12}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 3, -6}, {12, 6}, {0, 0, 1}, wall));
  // A mirror leaning forward by 30 degrees: it faces the camera and the floor in front of it.
  s.meshes.push_back(makeQuad({0, 1.5, -3}, {5, 3}, {0.0, -std::sin(glm::radians(30.0)),
                                                    std::cos(glm::radians(30.0))}, mirror));
  s.camera = perspectiveCamera({1.0, 2.5, 4.0}, {0.0, 1.2, -3.0}, 50.0, 0.1, 50.0);
  return s;
}


// The matte box colours of the scenes built to break the tracer (slightly emissive, so that their
// reflections read clearly in the shade).
struct BoxColours {
  int red, green, blue, yellow;
};
BoxColours addBoxColours(Scene& s, float emissive) {
  BoxColours c;
  c.red = addMaterial(s, glm::vec3(0.8f, 0.12f, 0.1f), 0.0f, 0.7f, emissive);
  c.green = addMaterial(s, glm::vec3(0.12f, 0.7f, 0.2f), 0.0f, 0.7f, emissive);
  c.blue = addMaterial(s, glm::vec3(0.12f, 0.25f, 0.85f), 0.0f, 0.7f, emissive);
  c.yellow = addMaterial(s, glm::vec3(0.9f, 0.75f, 0.1f), 0.0f, 0.7f, emissive);
  return c;
}

// The scenes below were built to break the tracer (issue: robust tracing), not to show it off.

// A mirror leaning 20 degrees towards a camera at eye height, its face to the viewer: its
// reflected rays come back towards the camera and pass behind the boxes standing between the two.
Scene facingMirror() {
  Scene s;
  s.name = "facing-mirror";
  const int mirror = addMaterial(s, glm::vec3(0.95f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.55f, 0.5f, 0.42f), 0.0f, 0.9f, 0.1f);
  const int wall = addMaterial(s, glm::vec3(0.6f, 0.62f, 0.66f), 0.0f, 0.9f, 0.05f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {20, 20}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 3, -7}, {20, 6}, {0, 0, 1}, wall));
  const double lean = glm::radians(20.0);
  s.meshes.push_back(makeQuad({0, 1.65, -4.5}, {5, 3}, {0, -std::sin(lean), std::cos(lean)}, mirror));
  s.meshes.push_back(makeBox({-1.6, 0.5, -2.2}, {0.9, 1.0, 0.9}, box.red, 15.0));
  s.meshes.push_back(makeBox({0.3, 0.35, -1.4}, {0.7, 0.7, 0.7}, box.green, -25.0));
  s.meshes.push_back(makeBox({1.7, 0.7, -2.6}, {0.8, 1.4, 0.8}, box.blue, 40.0));
  s.camera = perspectiveCamera({0.0, 1.6, 4.0}, {0.0, 1.3, -4.5}, 55.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.32f, 0.38f);
  return s;
}

// Vertical mirror walls turned about the vertical axis so that their reflections run across the
// screen, nearly parallel to the image plane, to the boxes and the other wall.
Scene mirrorWalls() {
  Scene s;
  s.name = "mirror-walls";
  const int mirror = addMaterial(s, glm::vec3(0.95f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.5f, 0.48f, 0.45f), 0.0f, 0.9f, 0.1f);
  const int wall = addMaterial(s, glm::vec3(0.7f, 0.66f, 0.6f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -4}, {14, 20}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 2.5, -12}, {14, 5}, {0, 0, 1}, wall));
  // A wall normal along +x (left wall) or -x (right wall), turned towards the camera about +y.
  auto yawed = [](double side, double degrees) {
    const double a = glm::radians(degrees);
    return glm::dvec3(side * std::cos(a), 0.0, std::sin(a));
  };
  // Left wall: a mirror turned 20 degrees towards the camera; right wall: 12 degrees. They face
  // each other across the room: a corridor of two mirrors.
  s.meshes.push_back(makeQuad({-3.2, 1.6, -5.5}, {9.0, 3.2}, yawed(1.0, 20.0), mirror));
  s.meshes.push_back(makeQuad({3.4, 1.6, -6.0}, {10.0, 3.2}, yawed(-1.0, 12.0), mirror));
  s.meshes.push_back(makeBox({-1.2, 0.6, -8.5}, {1.0, 1.2, 1.0}, box.red, 20.0));
  s.meshes.push_back(makeBox({1.0, 0.9, -6.5}, {0.8, 1.8, 0.8}, box.green, -15.0));
  s.meshes.push_back(makeBox({-0.6, 0.4, -3.5}, {0.8, 0.8, 0.8}, box.blue, 30.0));
  s.meshes.push_back(makeBox({1.6, 0.3, -2.2}, {0.6, 0.6, 0.6}, box.yellow, 10.0));
  s.camera = perspectiveCamera({0.2, 1.6, 4.0}, {0.0, 1.2, -8.0}, 60.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// Curved mirrors: smooth vertex normals send reflected rays in every direction at once.
Scene curvedMirror() {
  Scene s;
  s.name = "curved-mirror";
  const int mirror = addMaterial(s, glm::vec3(0.95f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.5f, 0.5f, 0.46f), 0.0f, 0.9f, 0.1f);
  const int wall = addMaterial(s, glm::vec3(0.55f, 0.6f, 0.68f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -2}, {16, 16}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 3, -7}, {16, 6}, {0, 0, 1}, wall));
  s.meshes.push_back(makeSphere({-1.2, 1.0, -2.0}, 1.0, mirror, 48, 96));
  s.meshes.push_back(makeCylinder({1.6, 0.0, -2.8}, 0.6, 2.2, mirror, 96));
  s.meshes.push_back(makeBox({-3.2, 0.6, -3.8}, {1.0, 1.2, 1.0}, box.red, 25.0));
  s.meshes.push_back(makeBox({0.4, 0.35, -4.8}, {0.7, 0.7, 0.7}, box.green, -10.0));
  s.meshes.push_back(makeBox({3.3, 0.5, -1.0}, {0.8, 1.0, 0.8}, box.yellow, 35.0));
  s.camera = perspectiveCamera({0.0, 2.0, 4.5}, {0.0, 0.9, -2.5}, 55.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// A copper mirror sphere over a gold mirror floor, the sphere a faceted mesh (`segments` around,
// half as many rings) with interpolated normals, as glTF spheres are: the depth shows flat facets
// while the shading normal turns smoothly, where reflected rays have refused true hits
// (docs/results/curved-objects.md).
Scene sphereOverMirror(int segments) {
  Scene s;
  s.name = "sphere-over-mirror-" + std::to_string(segments);
  const int copper = addMaterial(s, glm::vec3(0.95f, 0.64f, 0.54f), 1.0f, 0.0f);
  const int gold = addMaterial(s, glm::vec3(1.0f, 0.78f, 0.34f), 1.0f, 0.0f);
  const int wall = addMaterial(s, glm::vec3(0.55f, 0.6f, 0.68f), 0.0f, 0.9f, 0.1f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {12, 12}, {0, 1, 0}, gold));
  s.meshes.push_back(makeQuad({0, 3, -6}, {12, 6}, {0, 0, 1}, wall));
  s.meshes.push_back(makeSphere({0.0, 1.0, 0.0}, 0.8, copper, segments / 2, segments));
  s.camera = perspectiveCamera({0.0, 1.6, 4.5}, {0.0, 0.7, 0.0}, 52.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// A sphere resting on a silver mirror floor (touching it at a point: beside it, a gap under its
// underside) and boxes standing on it (contact lines), a wall far behind: rays leaving the floor
// beside an object's foot pass over the floor pixels around it on their way to the wall or under
// the sphere, and a floor mirror can never reflect the floor.
Scene objectsOnMirror() {
  Scene s;
  s.name = "objects-on-mirror";
  const int silver = addMaterial(s, glm::vec3(0.92f), 1.0f, 0.0f);
  const int matte = addMaterial(s, glm::vec3(0.7f, 0.45f, 0.3f), 0.0f, 0.8f);
  const int wall = addMaterial(s, glm::vec3(0.55f, 0.6f, 0.68f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -3}, {14, 14}, {0, 1, 0}, silver));
  s.meshes.push_back(makeQuad({0, 3, -10}, {14, 6}, {0, 0, 1}, wall));
  s.meshes.push_back(makeSphere({-0.9, 0.7, -2.0}, 0.7, matte, 32, 64));
  s.meshes.push_back(makeBox({1.2, 0.5, -2.6}, {1.0, 1.0, 1.0}, box.red, 30.0));
  s.meshes.push_back(makeBox({0.2, 0.3, -0.6}, {0.6, 0.6, 0.6}, box.blue, -20.0));
  s.camera = perspectiveCamera({0.0, 1.5, 3.5}, {0.0, 0.4, -2.0}, 55.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// A mirror wall on the right, turned 20 degrees about the vertical away from the view: rays
// meeting it leave straight along the view direction, away from the camera, towards the boxes
// standing along it deep in the scene (screen-space steps shrink towards the vanishing point).
Scene turnedMirror() {
  Scene s;
  s.name = "turned-mirror";
  const int mirror = addMaterial(s, glm::vec3(0.95f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.5f, 0.48f, 0.45f), 0.0f, 0.9f, 0.1f);
  const int wall = addMaterial(s, glm::vec3(0.68f, 0.66f, 0.62f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -5}, {20, 26}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 3, -17}, {20, 6}, {0, 0, 1}, wall));
  // Normal (-cos 20, 0, -sin 20): the camera is on its front side, and a ray from the eye to the
  // wall's near end reflects to (0, 0, -1).
  const double yaw = glm::radians(20.0);
  s.meshes.push_back(makeQuad({7.1, 1.75, -5.0}, {14.0, 3.5}, {-std::cos(yaw), 0.0, -std::sin(yaw)}, mirror));
  s.meshes.push_back(makeBox({3.0, 0.6, -3.0}, {0.8, 1.2, 0.8}, box.red, 20.0));
  s.meshes.push_back(makeBox({4.3, 0.9, -7.0}, {0.9, 1.8, 0.9}, box.green, -15.0));
  s.meshes.push_back(makeBox({2.2, 0.4, -9.5}, {0.8, 0.8, 0.8}, box.blue, 30.0));
  s.meshes.push_back(makeBox({5.6, 1.1, -11.5}, {1.0, 2.2, 1.0}, box.yellow, 10.0));
  s.meshes.push_back(makeBox({-2.2, 0.5, -4.0}, {1.0, 1.0, 1.0}, box.blue, 40.0));
  s.camera = perspectiveCamera({0.0, 1.6, 5.0}, {2.6, 1.2, -8.0}, 60.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// Two parallel mirror walls with pillars between them, seen down their length: rays bounce
// across the corridor, pass behind the pillars and run towards the vanishing point.
Scene mirrorCorridor() {
  Scene s;
  s.name = "mirror-corridor";
  const int mirror = addMaterial(s, glm::vec3(0.95f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.52f, 0.5f, 0.46f), 0.0f, 0.9f, 0.1f);
  const int wall = addMaterial(s, glm::vec3(0.66f, 0.64f, 0.6f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -7}, {8, 22}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 1.7, -18}, {8, 3.4}, {0, 0, 1}, wall));
  s.meshes.push_back(makeQuad({-2.0, 1.7, -7.0}, {22.0, 3.4}, {1, 0, 0}, mirror));
  s.meshes.push_back(makeQuad({2.0, 1.7, -7.0}, {22.0, 3.4}, {-1, 0, 0}, mirror));
  const int pillarColour[4] = {box.red, box.green, box.blue, box.yellow};
  for (int i = 0; i < 4; ++i)
    s.meshes.push_back(makeCylinder({i % 2 ? 1.1 : -1.1, 0.0, -3.0 - 3.0 * i}, 0.22, 3.4, pillarColour[i], 48));
  s.meshes.push_back(makeBox({0.1, 0.3, -4.6}, {0.6, 0.6, 0.6}, box.yellow, 25.0));
  s.meshes.push_back(makeBox({-0.4, 0.45, -10.5}, {0.9, 0.9, 0.9}, box.red, -20.0));
  s.camera = perspectiveCamera({0.4, 1.5, 4.0}, {0.0, 1.3, -17.0}, 60.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// A mirror sphere beside a mirror panel turned about two axes, seen from above at about 47
// degrees: reflected rays leave in every direction, many of them up and off the screen.
Scene mirrorsFromAbove() {
  Scene s;
  s.name = "mirrors-from-above";
  const int mirror = addMaterial(s, glm::vec3(0.95f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.5f, 0.5f, 0.46f), 0.0f, 0.9f, 0.1f);
  const int wall = addMaterial(s, glm::vec3(0.55f, 0.6f, 0.68f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -1}, {16, 16}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 1, -6}, {16, 2}, {0, 0, 1}, wall));
  s.meshes.push_back(makeSphere({-1.6, 1.1, -1.2}, 1.1, mirror, 48, 96));
  s.meshes.push_back(makeQuad({1.7, 1.2, -1.6}, {3.0, 2.2}, glm::normalize(glm::dvec3(-0.75, 0.4, 0.35)), mirror));
  s.meshes.push_back(makeBox({0.0, 0.5, -3.6}, {1.0, 1.0, 1.0}, box.red, 20.0));
  s.meshes.push_back(makeBox({-3.6, 0.7, 0.6}, {0.8, 1.4, 0.8}, box.green, -15.0));
  s.meshes.push_back(makeBox({3.7, 0.4, 0.9}, {0.8, 0.8, 0.8}, box.blue, 35.0));
  s.meshes.push_back(makeBox({0.3, 0.3, 1.3}, {0.6, 0.6, 0.6}, box.yellow, 0.0));
  s.camera = perspectiveCamera({1.0, 7.5, 5.5}, {0.0, 0.3, -1.2}, 50.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// A row of floor panels from roughness 0 to 0.5 (the High preset's cutoff) under the same boxes.
Scene glossy() {
  Scene s;
  s.name = "glossy";
  const int wall = addMaterial(s, glm::vec3(0.6f, 0.6f, 0.62f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.25f);
  const int panels = 6;
  for (int i = 0; i < panels; ++i) {
    const int m = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.1f * i);
    s.meshes.push_back(makeQuad({-5.0 + 2.0 * i, 0.0, -1.0}, {2.0, 8.0}, {0, 1, 0}, m));
  }
  s.meshes.push_back(makeQuad({0, 3, -5}, {14, 6}, {0, 0, 1}, wall));
  for (int i = 0; i < panels; ++i) {
    const int m = i % 3 == 0 ? box.red : (i % 3 == 1 ? box.green : box.blue);
    s.meshes.push_back(makeBox({-5.0 + 2.0 * i, 0.6, -3.6}, {0.8, 1.2, 0.8}, m, 20.0 * i));
  }
  s.camera = perspectiveCamera({0.0, 2.2, 5.5}, {0.0, 0.6, -2.5}, 60.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  return s;
}

// The glossy scene with two small emitters at 1,000x the scene's average luminance in front of the
// box row, over the panels of roughness 0.1 and 0.3: HDR radiance that the blur and temporal reuse
// would spread into fireflies (Settings::radianceClamp; docs/results/glossy.md, "HDR").
Scene brightEmitter() {
  Scene s = glossy();
  s.name = "bright-emitter";
  const int emitter = addMaterial(s, glm::vec3(1.0f, 0.95f, 0.85f), 0.0f, 0.9f, 1000.0f);
  s.meshes.push_back(makeBox({-3.0, 0.2, -2.2}, {0.3, 0.4, 0.3}, emitter, 0.0));
  s.meshes.push_back(makeBox({1.0, 0.2, -2.2}, {0.3, 0.4, 0.3}, emitter, 0.0));
  return s;
}

}  // namespace

// The cost-curve scene: a floor with boxes and a back wall that together fill the screen, seen
// from 20 degrees above. The bottom `percent` of the screen's rows are mirror (floor first, then
// the wall upwards; at 100 the boxes are mirrors too, so that every pixel reflects); the rest is
// rough stone. Lines parallel to the camera's x axis (floor z = const, wall y = const) project to
// single rows, so the band edge is exact: row fraction v looks down at
// theta(v) = pitch - atan((2v - 1) tan(fovy / 2)) and meets the floor or the wall there.
Scene reflectiveFraction(int percent) {
  Scene s;
  s.name = "reflective-" + std::to_string(percent);
  const double h = 3.0, eyeZ = 6.0, wallZ = -14.0, pitch = glm::radians(20.0), fovy = 50.0;
  const bool all = percent >= 100;
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int stone = addMaterial(s, glm::vec3(0.55f, 0.52f, 0.5f), 0.0f, 0.9f);
  const int red = all ? addMaterial(s, glm::vec3(0.9f, 0.3f, 0.25f), 1.0f, 0.0f)
                      : addMaterial(s, glm::vec3(0.8f, 0.12f, 0.1f), 0.0f, 0.7f, 0.15f);
  const int blue = all ? addMaterial(s, glm::vec3(0.3f, 0.4f, 0.9f), 1.0f, 0.0f)
                       : addMaterial(s, glm::vec3(0.12f, 0.25f, 0.85f), 0.0f, 0.7f, 0.15f);
  const double floorNear = eyeZ + 2.0, wallTop = 40.0;
  double floorEdge = floorNear, wallEdge = 0.0;  // where the mirror band ends on floor and wall
  if (all) {
    floorEdge = wallZ;
    wallEdge = wallTop;
  } else if (percent > 0) {
    const double v = percent / 100.0;
    const double theta = pitch - std::atan((2.0 * v - 1.0) * std::tan(glm::radians(fovy) / 2.0));
    const double floorZ = theta > 0.0 ? eyeZ - h / std::tan(theta) : -1e30;
    if (floorZ >= wallZ) {
      floorEdge = floorZ;
    } else {
      floorEdge = wallZ;
      wallEdge = h + (eyeZ - wallZ) * std::tan(-theta);
    }
  }
  auto floorPart = [&](double z0, double z1, int material) {
    if (z0 > z1) s.meshes.push_back(makeQuad({0, 0, 0.5 * (z0 + z1)}, {80, z0 - z1}, {0, 1, 0}, material));
  };
  auto wallPart = [&](double y0, double y1, int material) {
    if (y1 > y0) s.meshes.push_back(makeQuad({0, 0.5 * (y0 + y1), wallZ}, {80, y1 - y0}, {0, 0, 1}, material));
  };
  floorPart(floorNear, floorEdge, mirror);
  floorPart(floorEdge, wallZ, stone);
  wallPart(0.0, wallEdge, mirror);
  wallPart(wallEdge, wallTop, stone);
  for (int i = 0; i < 5; ++i)
    s.meshes.push_back(makeBox({-6.0 + 3.0 * i, 1.25, -6.0 + (i % 2) * 2.0}, {1.2, 2.5, 1.2}, i % 2 ? blue : red,
                               15.0 * i));
  s.camera = perspectiveCamera({0.0, h, eyeZ}, {0.0, h - std::tan(pitch), eyeZ - 1.0}, fovy, 0.1, 100.0);
  return s;
}

std::vector<std::string> builtinSceneNames() {
  return {"mirror-room",   "grazing-plane", "thin-objects",  "sky-heavy",       "mirror-box",
          "tilted-mirror", "facing-mirror", "mirror-walls",  "curved-mirror",   "glossy",
          "turned-mirror", "mirror-corridor", "mirrors-from-above", "sphere-over-mirror-32", "sphere-over-mirror-128",
          "objects-on-mirror", "bright-emitter"};
}

std::vector<std::string> assetSceneNames() { return {"spider-on-mirror", "wuson-as-mirror"}; }

std::string assetScenePath(const std::string& name) {
  const char* dir = std::getenv("SSLR_ASSET_DIR");
  return std::string(dir && *dir ? dir : SSLR_DEFAULT_ASSET_DIR) + "/scenes/" + name + ".gltf";
}

Expected<Scene> makeBuiltinScene(const std::string& name) {
  if (name == "mirror-room") return mirrorRoom();
  if (name == "grazing-plane") return grazingPlane();
  if (name == "thin-objects") return thinObjects();
  if (name == "sky-heavy") return skyHeavy();
  if (name == "mirror-box") return mirrorBox();
  if (name == "tilted-mirror") return tiltedMirror();
  if (name == "facing-mirror") return facingMirror();
  if (name == "mirror-walls") return mirrorWalls();
  if (name == "curved-mirror") return curvedMirror();
  if (name == "glossy") return glossy();
  if (name == "bright-emitter") return brightEmitter();
  if (name == "turned-mirror") return turnedMirror();
  if (name == "mirror-corridor") return mirrorCorridor();
  if (name == "mirrors-from-above") return mirrorsFromAbove();
  if (name == "sphere-over-mirror-32") return sphereOverMirror(32);
  if (name == "sphere-over-mirror-128") return sphereOverMirror(128);
  if (name == "objects-on-mirror") return objectsOnMirror();
  if (name.rfind("reflective-", 0) == 0) {
    const std::string digits = name.substr(11);
    if (!digits.empty() && digits.size() <= 3 && std::all_of(digits.begin(), digits.end(), ::isdigit) &&
        std::stoi(digits) <= 100)
      return reflectiveFraction(std::stoi(digits));
  }
  std::string known;
  for (const auto& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
  for (const auto& n : assetSceneNames()) known += ", " + n;
  return Status::error("unknown scene '" + name + "' (built-in scenes: " + known +
                       ", reflective-N with N = 0..100; or give a .gltf/.glb file)");
}

Expected<Scene> loadScene(const std::string& nameOrPath) {
  auto endsWith = [&](const char* suffix) {
    const std::string s(suffix);
    return nameOrPath.size() >= s.size() &&
           std::equal(s.rbegin(), s.rend(), nameOrPath.rbegin(),
                      [](char a, char b) { return std::tolower(a) == std::tolower(b); });
  };
  if (endsWith(".gltf") || endsWith(".glb")) return loadGltf(nameOrPath);
  const auto assets = assetSceneNames();
  if (std::find(assets.begin(), assets.end(), nameOrPath) != assets.end()) {
    const std::string path = assetScenePath(nameOrPath);
    auto scene = loadGltf(path);
    if (!scene) return Status::error("scene '" + nameOrPath + "' is the file " + path + ": " + scene.error() +
                                     " (set SSLR_ASSET_DIR to the folder holding scenes/)");
    return scene;
  }
  return makeBuiltinScene(nameOrPath);
}

void addMirrorFloor(Scene& scene) {
  const Bounds b = scene.worldBounds();
  if (b.empty()) return;
  const glm::dvec3 size = b.max - b.min;
  const double extent = 3.0 * std::max({size.x, size.z, size.y, 1e-3});
  Material mirror;
  mirror.baseColor = glm::vec3(0.9f);
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  scene.materials.push_back(mirror);
  // A hair below the model, so that a model standing at y = min does not z-fight with it.
  const glm::dvec3 center(0.5 * (b.min.x + b.max.x), b.min.y - 1e-3 * std::max(size.y, 1e-3),
                          0.5 * (b.min.z + b.max.z));
  scene.meshes.push_back(makeQuad(center, {extent, extent}, {0.0, 1.0, 0.0},
                                  static_cast<int>(scene.materials.size()) - 1));
}


Expected<Scene> stageModel(Scene model, ModelStage stage) {
  const Bounds b = model.worldBounds();
  if (b.empty()) return Status::error("cannot stage '" + model.name + "': it has no triangles");
  const glm::dvec3 size = b.max - b.min;
  const double extent = std::max({size.x, size.y, size.z});
  if (!(extent > 0.0) || !std::isfinite(extent))
    return Status::error("cannot stage '" + model.name + "': its extent is zero or not finite");
  // Largest side 3 units, centred on the origin in x and z, standing on y = 0.
  const double scale = 3.0 / extent;
  const glm::dvec3 base(0.5 * (b.min.x + b.max.x), b.min.y, 0.5 * (b.min.z + b.max.z));
  const glm::dmat4 stagedFromWorld = glm::translate(glm::scale(glm::dmat4(1.0), glm::dvec3(scale)), -base);
  Scene s = std::move(model);
  for (Mesh& m : s.meshes) m.worldFromModel = stagedFromWorld * m.worldFromModel;
  if (stage == ModelStage::AsMirror) {
    for (Material& m : s.materials) m = Material{glm::vec3(0.95f), 1.0f, 0.0f};
    s.textures.clear();
  }
  const double height = size.y * scale;
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int wall = addMaterial(s, glm::vec3(0.62f, 0.62f, 0.64f), 0.0f, 0.9f, 0.1f);
  const BoxColours box = addBoxColours(s, 0.2f);
  // The floor a hair below the model's lowest point, so that its feet do not z-fight with it.
  s.meshes.push_back(makeQuad({0, -1e-3, -1}, {18, 18}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 2.5, -6}, {18, 5}, {0, 0, 1}, wall));
  s.meshes.push_back(makeBox({-3.0, 0.5, -2.0}, {0.9, 1.0, 0.9}, box.red, 20.0));
  s.meshes.push_back(makeBox({3.1, 0.7, -2.6}, {0.8, 1.4, 0.8}, box.green, -15.0));
  s.meshes.push_back(makeBox({0.4, 0.4, -4.3}, {0.8, 0.8, 0.8}, box.blue, 30.0));
  s.meshes.push_back(makeBox({-2.2, 0.3, 1.8}, {0.6, 0.6, 0.6}, box.yellow, 10.0));
  // On a mirror: a low camera, the model's reflection in front of it. As the mirror: from above
  // its top, so that its curved faces reflect the floor, the boxes and the wall.
  s.camera = stage == ModelStage::OnMirror
                 ? perspectiveCamera({0.6, 0.3 * height + 0.25, 5.2}, {0.0, 0.35 * height, -1.0}, 50.0, 0.1, 100.0)
                 : perspectiveCamera({0.8, height + 1.6, 5.0}, {0.0, 0.45 * height, -0.8}, 50.0, 0.1, 100.0);
  s.background = glm::vec3(0.3f, 0.33f, 0.4f);
  s.name += stage == ModelStage::OnMirror ? "-on-mirror" : "-as-mirror";
  return s;
}

}  // namespace sslr::host
