// shared/language.h - the subset of C++20 and GLSL 4.50 the shared headers are written in: GLM
// stands in for GLSL's types in C++; SSLR_FN, SSLR_INOUT, SSLR_OUT and SSLR_DEFAULT bridge the rest.
#ifndef SSLR_SHARED_LANGUAGE_H
#define SSLR_SHARED_LANGUAGE_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstddef>
#include <cstdint>
namespace sslr::shared {
using glm::ivec2;
using glm::ivec4;
using glm::bvec4;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::mat4;
using uint = std::uint32_t;
using glm::abs;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp2;
using glm::log2;
using glm::floor;
using glm::isinf;
using glm::isnan;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::inversesqrt;
using glm::reflect;
using glm::sign;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
}  // namespace sslr::shared
#define SSLR_FN inline
#define SSLR_INOUT(T) T&
#define SSLR_OUT(T) T&
#define SSLR_DEFAULT(v) = v  // a member's default in C++ (a GLSL block member has none)
#else
#define SSLR_FN
#define SSLR_INOUT(T) inout T
#define SSLR_OUT(T) out T
#define SSLR_DEFAULT(v)
#endif

#endif  // SSLR_SHARED_LANGUAGE_H
