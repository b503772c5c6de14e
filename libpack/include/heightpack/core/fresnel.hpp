// The 1D Fresnel / water-colour ramp of "Rendering Ocean Water" (Isidoro, Vlachos, Brennan), indexed by
// N.V so a shader does mix(waterColour, reflection, F) with one fetch.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "heightpack/core/image.hpp"

namespace heightpack {

enum class FresnelModel {
    Exact,    // unpolarised dielectric Fresnel reflectance, (Rs + Rp) / 2
    Schlick,  // R0 + (1 - R0)(1 - cos)^5, R0 = ((n - 1) / (n + 1))^2
};
template <>
struct NameTable<FresnelModel> {
    static constexpr EnumName<FresnelModel> entries[] = {
        {FresnelModel::Exact, "exact", "unpolarised dielectric Fresnel reflectance"},
        {FresnelModel::Schlick, "schlick", "Schlick's approximation"},
    };
};

// What the texture coordinate is.
enum class FresnelIndex {
    NdotV,     // u = N.V
    TwoNdotV,  // u = saturate(2 N.V), as the Isidoro shader indexes it: the ramp covers N.V in [0, 0.5]
};
template <>
struct NameTable<FresnelIndex> {
    static constexpr EnumName<FresnelIndex> entries[] = {
        {FresnelIndex::NdotV, "nv", "u = N.V"},
        {FresnelIndex::TwoNdotV, "2nv", "u = saturate(2 N.V)"},
    };
};

using Rgb = std::array<double, 3>;  // linear RGB in [0,1]

struct FresnelOptions {
    double ior = 1.333;  // air to water
    FresnelModel model = FresnelModel::Exact;
    FresnelIndex index = FresnelIndex::NdotV;
    int size = 256;
    Rgb deep = {0.02, 0.10, 0.16};     // seen looking straight down (N.V = 1)
    Rgb shallow = {0.10, 0.40, 0.45};  // seen at grazing angles (N.V = 0)
};

// Reflectance of light arriving at angle acos(cosTheta) from the normal, from air onto a dielectric of
// index ior (>= 1). cosTheta is clamped to [0, 1].
double fresnelReflectance(double cosTheta, double ior, FresnelModel model);

// The N.V that texel i of a ramp stands for: its centre u = (i + 0.5) / size, through the indexing.
double rampCosine(int texel, int size, FresnelIndex index);

// size x 1 RGBA ramp: rgb = mix(shallow, deep, N.V) (linear), a = Fresnel reflectance.
Image makeFresnelRamp(const FresnelOptions& options);

// Linear filtering of a ramp at texture coordinate u, clamped to the edge, as GL_LINEAR does it.
std::array<float, 4> sampleRamp(const Image& ramp, double u);

}  // namespace heightpack
