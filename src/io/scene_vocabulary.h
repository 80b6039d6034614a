#pragma once
// The names the scene format gives to shapes, material types and texture types, shared by its reader
// and its writer (docs/scene-format.md).
#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"
#include "core/texture.h"

namespace wideray {

inline const std::vector<std::string> kShapes = {"cube", "icosphere", "torus", "quad", "terrain"};
inline const std::vector<std::pair<std::string, Integrator>> kIntegrators = {{"whitted", Integrator::Whitted},
                                                                             {"path", Integrator::Path}};
/// Object types of the analytic primitives (a hyperboloid of two sheets is "hyperboloid" with "sheets": 2).
inline const std::vector<std::pair<std::string, AnalyticShape>> kAnalyticShapes = {
    {"ellipsoid", AnalyticShape::Ellipsoid}, {"cylinder", AnalyticShape::Cylinder},
    {"cone", AnalyticShape::Cone},           {"paraboloid", AnalyticShape::Paraboloid},
    {"hyperboloid", AnalyticShape::Hyperboloid}, {"quadric", AnalyticShape::Quadric},
    {"torus", AnalyticShape::Torus}, {"blob", AnalyticShape::Blob}};
inline const std::vector<std::pair<std::string, CsgOperation>> kCsgOperations = {
    {"union", CsgOperation::Union}, {"intersection", CsgOperation::Intersection},
    {"difference", CsgOperation::Difference}, {"xor", CsgOperation::Xor}};
inline const std::vector<std::pair<std::string, EnvironmentMapping>> kEnvironmentMappings = {
    {"latlong", EnvironmentMapping::LatLong}, {"equal_area", EnvironmentMapping::EqualArea}};
inline const std::vector<std::string> kMaterialTypes = {"diffuse", "plastic", "mirror", "conductor", "dielectric"};
inline const std::vector<std::pair<std::string, TextureType>> kTextureTypes = {
    {"checker", TextureType::Checker}, {"noise", TextureType::Noise},   {"fbm", TextureType::Fbm},
    {"turbulence", TextureType::Turbulence}, {"marble", TextureType::Marble}, {"image", TextureType::Image}};

/// The name a vocabulary table gives `value` (every value of the enums is in its table).
template <class T>
const std::string& nameOf(const std::vector<std::pair<std::string, T>>& table, T value) {
    for (const auto& [name, v] : table)
        if (v == value) return name;
    return table.front().first;
}

inline bool hasOctaves(TextureType type) {
    return type == TextureType::Fbm || type == TextureType::Turbulence || type == TextureType::Marble;
}

} // namespace wideray
