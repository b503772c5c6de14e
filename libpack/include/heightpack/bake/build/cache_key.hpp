// Cache keys from the very option structs the build's steps run with. Each struct has one serialisation
// that names every field (those that cannot change an output, such as thread counts and progress
// callbacks, are named and skipped), and a static_assert beside it counts the struct's fields: a field
// added to a struct and not to its key text stops the build instead of silently breaking rebuilds.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/bake/normal_job.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/sea/foam.hpp"
#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack {

namespace detail {
// Converts to any field's type, so T{AnyField{}, ...} tells how many fields an aggregate has.
struct AnyField {
    template <class T>
    constexpr operator T() const;  // only in unevaluated braces; never defined
};
template <class T, class... Fields>
constexpr std::size_t countFields() {
    if constexpr (requires { T{std::declval<Fields>()..., AnyField{}}; })
        return countFields<T, Fields..., AnyField>();
    else
        return sizeof...(Fields);
}
}  // namespace detail

// How many fields the aggregate T has (its direct members, a nested struct counting as one).
template <class T>
constexpr std::size_t fieldCount() {
    static_assert(std::is_aggregate_v<T>, "fieldCount counts the fields of an aggregate");
    return detail::countFields<T>();
}

// Append one line "PREFIXname=value" per field of the options that can shape an output (nested
// structs as PREFIXname.field=...). Numbers with every digit, enums as their values, strings with their
// length, so two different options never give the same text.
void appendKeyText(std::string& text, std::string_view prefix, const LoadOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const MipOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const NormalOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const FresnelOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const PackOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const NormalJobOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const CheckOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const SwellOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const SpectrumOptions& options);
void appendKeyText(std::string& text, std::string_view prefix, const FoamOptions& options);

// appendKeyText into an empty string.
template <class Options>
std::string keyText(const Options& options, std::string_view prefix = "") {
    std::string text;
    appendKeyText(text, prefix, options);
    return text;
}

// The cache key of a step: XXH3-128 (32 hex digits) of the tool's version, the step's key text and the
// hash of its input's bytes (empty for a step without an input file).
std::string cacheKey(std::string_view version, std::string_view text, std::string_view inputHash);

}  // namespace heightpack
