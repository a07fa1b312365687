// A Scene as a self-contained glTF 2.0 file (one JSON text, geometry in a data: URI), for the
// built-in scenes in assets/scenes and for any viewer: `sslr-render --scene NAME --export-gltf F`.
#pragma once

#include <string>

#include "sslr_host/scene.hpp"

namespace sslr::host {

// Meshes keep their own node transform (worldFromModel, written as a matrix), materials their
// metallic-roughness factors (emissive as emissiveFactor), the camera its node and projection.
// What glTF has no field for (the background colour, the light direction) goes into
// asset.extras.sslr, which loadGltf reads back; other viewers ignore it. Textures are not
// written (the built-in scenes have none): a scene with textures is refused with the reason.
Expected<std::string> gltfFromScene(const Scene& scene);

// base64 of raw bytes (RFC 4648, padded), for glTF's data: URIs; the tests' files use it too.
std::string base64(const std::string& bytes);

}  // namespace sslr::host
