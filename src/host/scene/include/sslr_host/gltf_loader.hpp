// glTF 2.0 (.gltf / .glb) scenes through tinygltf, with every input checked.
#pragma once

#include <string>

#include "sslr_host/scene.hpp"

namespace sslr::host {

// Loads triangle meshes (indexed or not), node transforms, metallic-roughness materials (base
// colour factor + texture, metallic and roughness factors) and the first camera. Errors name the
// file and the element ("mesh 2 primitive 0: index 77 >= vertex count 24"); non-triangle
// primitives are skipped with a warning in Scene::warnings.
Expected<Scene> loadGltf(const std::string& path);

}  // namespace sslr::host
